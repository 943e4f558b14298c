// The wavefront strategy's intersect stage (Wavefront.h): the closest hit of each path's ray.
#include "rill/rt/wavefront/Records.h"
#include "rill/rt/wavefront/Wavefront.h"

namespace rt {

using namespace rill;
using namespace wf;

// Launched on the paths not done (masked).
Program Wavefront::capture_intersect() const {
  return rill::program("wf_intersect", [&] {
    Input<Float4> o("path.o");
    Input<Float4> d("path.d");
    Output<HitRecord> hit("hit");
    hit = store(S_.intersector.intersect(Ray{o.xyz(), d.xyz(), o.w()}, nullptr));
  });
}

}  // namespace rt
