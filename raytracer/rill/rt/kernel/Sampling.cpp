// Monte Carlo building blocks (Sampling.h).
#include "rill/rt/kernel/Sampling.h"

namespace rt {

using namespace rill;

Basis::Basis(const Float3& normal) : n(normal) {
  const Float sign = select(normal.z() >= 0.0f, Float(1.0f), Float(-1.0f));
  const Float a = -1.0f / (sign + normal.z());
  const Float b = normal.x() * normal.y() * a;
  s = Float3(1.0f + sign * normal.x() * normal.x() * a, sign * b, -sign * normal.x());
  t = Float3(b, sign + normal.y() * normal.y() * a, -normal.y());
}

Float3 cosine_hemisphere(const Float2& u) {
  const Float r = sqrt(u.x());
  const Float phi = (2.0f * kPi) * u.y();
  return Float3(r * cos(phi), r * sin(phi), sqrt(max(1.0f - u.x(), 0.0f)));
}

Float2 uniform_triangle(const Float2& u) {
  const Float su = sqrt(u.x());
  return Float2(1.0f - su, u.y() * su);  // (b1, b2): b0 = su (1 - u.y)
}

Float power_heuristic(const Float& a, const Float& b) {
  const Bool a_larger = a >= b;
  // The smaller over the larger, in [0, 1]; 1 when both are infinite (inf / inf is NaN).
  Float r = select(a_larger, b, a) / select(a_larger, a, b);
  r = select(a == b, Float(1.0f), r);
  const Float r2 = r * r;
  const Float w = select(a_larger, 1.0f / (1.0f + r2), r2 / (1.0f + r2));
  return select(a > 0.0f, w, Float(0.0f));
}

Float luminance(const Float3& c) {
  return 0.2126f * c.x() + 0.7152f * c.y() + 0.0722f * c.z();
}

}  // namespace rt
