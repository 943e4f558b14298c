// The wavefront strategy's shade stage (Wavefront.h): PathIntegrator::shade on what each
// path's ray hit.
#include "rill/rt/wavefront/Records.h"
#include "rill/rt/wavefront/Wavefront.h"

namespace rt {

using namespace rill;
using namespace wf;

// Launched on the paths not done (masked). Writes the path back, its shadow query, and, on
// the camera ray (depth 0), the AOVs. A scene without geometry has no intersect stage: every
// ray misses.
Program Wavefront::capture_shade() const {
  return rill::program("wf_shade", [&] {
    // Every field but done, which is false: the launch is masked to the paths not done.
    const PathRecord in_path{Input<Float4>("path.o"),        Input<Float4>("path.d"),
                             Input<Float3>("path.radiance"), Input<Float3>("path.throughput"),
                             Input<Int3>("path.ints"),       Int(0)};
    const Hit hit =
        S_.F.geometry ? load(Input<HitRecord>("hit")) : Hit{Float(0.0f), Float2(0.0f), Int(-1)};
    const Int2 image_pix = element_coord() + S_.camera.origin;
    PathItem path = load(in_path, Bool(false));
    const Int depth = path.depth;
    FirstHit first;
    first.depth = as_float(Int(0x7f800000));
    const ShadowQuery shadow = path_->shade(path, hit, image_pix, &first);
    Output<PathRecord> out_path("path");
    out_path = store(path);
    if (path_->shadow_rays()) {
      Output<ShadowRecord> out_shadow("shadow");
      out_shadow = store(shadow);
    }
    Output<Aov> aov("aov");
    Output<Float3> albedo("albedo");
    RILL_IF(depth == 0) {
      aov = Aov{first.depth, first.prim, first.normal};
      albedo = first.albedo;
    }
    RILL_ENDIF;
  });
}

}  // namespace rt
