// The mirror shader (Builtin.h): all of the path's weight but (1 - reflect) goes on along the
// reflected direction; no local light.
#include "rill/rt/shaders/Builtin.h"

namespace rt {

SurfaceShader mirror_shader() {
  SurfaceShader s;
  s.name = "mirror";
  s.doc = "a perfect mirror";
  s.params = {{"reflect", ParamType::Number, ParamValue::of(0.9f), "reflectance, 0 to 1"}};
  s.scatter = [](const ShadingPoint& sp, const Float& weight) {
    Scatter out;
    Float r = sp.number("reflect");
    out.local_weight = weight * (1.0f - r);
    out.reflect_weight = weight * r;
    out.reflect_dir = reflect(-sp.s.V, sp.s.nf);
    return out;
  };
  s.lobes = [](const MaterialParams& p) { return Lobes{p.nonzero("reflect"), false}; };
  return s;
}

}  // namespace rt
