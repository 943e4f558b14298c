// Spot and directional lights' data and cone (LightShape.h).
#include "rill/rt/kernel/LightShape.h"

#include <algorithm>
#include <cmath>

#include "rill/rt/kernel/DeviceArrays.h"

namespace rt {

using namespace rill;

namespace {
double cos_deg(float deg) {
  return std::cos(static_cast<double>(deg) * (M_PI / 180.0));
}
}  // namespace

bool light_shaped(const Light& l, Integrator integrator) {
  if (l.type != LightType::Point) return true;
  return integrator == Integrator::Whitted && l.falloff == Falloff::InverseSquare;
}

bool any_light_shaped(const Scene& s) {
  for (const Light& l : s.lights)
    if (light_shaped(l, s.options.integrator)) return true;
  return false;
}

double spot_cone_factor(const Light& l, double cos_theta) {
  if (l.type != LightType::Spot) return 1.0;
  const double co = static_cast<float>(cos_deg(l.outer_deg)),
               ci = static_cast<float>(cos_deg(l.inner_deg));
  if (cos_theta >= ci) return 1.0;
  if (!(ci > co)) return cos_theta >= co ? 1.0 : 0.0;
  const double t = std::clamp((cos_theta - co) / (ci - co), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

void LightShapes::upload(const std::vector<Light>& lights) {
  std::vector<glm::vec4> sh;
  std::vector<glm::vec3> ax;
  for (const Light& l : lights) {
    const float kind = l.type == LightType::Spot          ? kShapeSpot
                       : l.type == LightType::Directional ? kShapeDirectional
                                                          : kShapePoint;
    sh.emplace_back(kind, static_cast<float>(cos_deg(l.outer_deg)),
                    static_cast<float>(cos_deg(l.inner_deg)),
                    l.falloff == Falloff::InverseSquare ? 1.0f : 0.0f);
    const glm::dvec3 d(l.direction);
    const double n = glm::length(d);
    ax.push_back(n > 0.0 ? glm::vec3(d / n) : glm::vec3(0.0f, -1.0f, 0.0f));
  }
  upload_padded(shape, sh);
  upload_padded(axis, ax);
}

Float LightShapes::cone(const Int& l, const Float3& wi) const {
  const Float4 s = shape[l];
  const Float co = s.y(), ci = s.z();
  const Float c = -dot(axis[l], wi);  // the cosine between the axis and the way to the point
  const Float width = ci - co;
  const Float t =
      select(width > 0.0f,
             clamp((c - co) / select(width > 0.0f, width, Float(1.0f)), Float(0.0f), Float(1.0f)),
             select(c >= co, Float(1.0f), Float(0.0f)));
  const Float smooth = select(c >= ci, Float(1.0f), t * t * (3.0f - 2.0f * t));
  return select(s.x() == kShapeSpot, smooth, Float(1.0f));
}

}  // namespace rt
