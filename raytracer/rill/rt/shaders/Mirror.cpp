// The mirror shader (Builtin.h): all of the path's weight but (1 - reflect) goes on along the
// reflected direction; no local light.
#include "rill/rt/shaders/Builtin.h"
#include "rill/rt/shaders/Lobes.h"
#include "rill/rt/shaders/PhongLight.h"

namespace rt {

SurfaceShader mirror_shader() {
  SurfaceShader s;
  s.name = "mirror";
  s.doc = "a perfect mirror";
  s.params = {{"reflect", ParamType::Number, ParamValue::of(0.9f), "reflectance, 0 to 1"}};
  s.scatter = [](const ShadingPoint& sp, const Float& weight) {
    return mirror_scatter(sp, weight, sp.number("reflect"));
  };
  s.lobes = [](const MaterialParams& p) { return Lobes{p.nonzero("reflect"), false}; };
  s.check = [](const MaterialParams& p) { return reflect_problem(p.number("reflect")); };
  // Path tracing: a delta lobe of reflectance `reflect` (the rest is absorbed).
  s.bsdf = mixture_bsdf(
      [](const ShadingPoint& sp) {
        return std::vector<Lobe>{mirror_lobe(sp, sp.number("reflect"))};
      },
      [](const MaterialParams&) { return false; });
  s.albedo = [](const ShadingPoint& sp) { return Float3(sp.number("reflect")); };
  return s;
}

}  // namespace rt
