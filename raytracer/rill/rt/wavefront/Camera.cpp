// The wavefront strategy's camera stage (Wavefront.h): a new path per pixel.
#include "rill/rt/wavefront/Records.h"
#include "rill/rt/wavefront/Wavefront.h"

namespace rt {

using namespace rill;
using namespace wf;

// The path along the pixel's camera ray, as the megakernel's capture_path starts it; a pixel
// that cannot see the scene gets the miss's shading (the same operations) and is done. The
// AOVs start as a miss leaves them, the shadow query inactive.
Program Wavefront::capture_camera() const {
  return rill::program("wf_camera", [&] {
    const Int2 pix = element_coord();
    const PathIntegrator& P = *path_;
    PathItem path = P.start(Ray{S_.camera.eye, Float3(0.0f, 0.0f, 1.0f), Float(kBig)});
    const Bool sees = S_.F.geometry ? S_.camera.may_see_scene(pix, S_.F.dynamic) : Bool(true);
    RILL_IF(!sees) {
      (void)P.shade(path, Hit{Float(0.0f), Float2(0.0f), Int(-1)}, pix);
    }
    RILL_ELSE {
      S_.camera.aim(path.ray, pix);
    }
    RILL_ENDIF;
    Output<PathRecord> out_path("path");
    out_path = store(path);
    if (P.shadow_rays()) {
      Output<Int> active("shadow.active");
      active = 0;
    }
    Output<Aov> aov("aov");
    aov = Aov{as_float(Int(0x7f800000)), Int(-1), Float3(0.0f)};
    Output<Float3> albedo("albedo");
    albedo = Float3(0.0f);
  });
}

}  // namespace rt
