// The wavefront strategy's shadow stage (Wavefront.h): the light samples' shadow rays.
#include "rill/rt/wavefront/Records.h"
#include "rill/rt/wavefront/Wavefront.h"

namespace rt {

using namespace rill;
using namespace wf;

// Launched on the active shadow queries (masked): the ray traced for any hit, then
// PathIntegrator::shadow_result, which reads and writes only the path's radiance and ray
// count (ints.z). The query is then inactive.
Program Wavefront::capture_shadow() const {
  return rill::program("wf_shadow", [&] {
    Input<Float4> o("shadow.o");
    Input<Float3> d("shadow.d");
    Input<Float3> contribution("shadow.contribution");
    Input<Float3> radiance("path.radiance");
    Input<Int3> ints("path.ints");
    // active is true: the launch is masked to the active queries.
    const ShadowQuery query{Ray{o.xyz(), d, o.w()}, contribution, Bool(true)};
    PathItem path = path_->start(query.ray);  // only radiance and rays are used
    path.radiance = radiance;
    path.rays = ints.z();
    const Bool any_hit = true;
    path_->shadow_result(path, query, S_.intersector.intersect(query.ray, &any_hit));
    Output<Float3> out_radiance("path.radiance");
    out_radiance = path.radiance;
    Output<Int3> out_ints("path.ints");
    out_ints = Int3(ints.x(), ints.y(), path.rays);
    Output<Int> active("shadow.active");
    active = 0;
  });
}

}  // namespace rt
