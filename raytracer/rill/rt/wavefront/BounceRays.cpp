// The wavefront strategy's read-back of its paths' rays (Records.h: append_bounce_rays;
// render/BounceRays.h). Host code: the record fields come back as they are stored, so the rays
// are bitwise those the intersect stage traces next.
#include <stdexcept>
#include <string>
#include <vector>

#include "rill/rt/wavefront/Records.h"

namespace rt {
namespace wf {

void append_bounce_rays(const rill::Stream<PathRecord>& paths, int width, int height, int sample,
                        BounceRays& out) {
  const size_t n = static_cast<size_t>(width) * static_cast<size_t>(height);
  // A stream may hold more elements than the window (padding): the first n are its pixels.
  const std::vector<glm::vec4> o = paths.field<Float4>("o").download();
  const std::vector<glm::vec4> d = paths.field<Float4>("d").download();
  const std::vector<glm::ivec3> ints = paths.field<Int3>("ints").download();
  const std::vector<int32_t> done = paths.field<Int>("done").download();
  for (size_t i = 0; i < n; ++i) {
    if (done[i] != 0) continue;
    if (ints[i].x != out.bounce)
      throw std::logic_error("bounce rays: a path going on after " + std::to_string(ints[i].x) +
                             " scatterings where " + std::to_string(out.bounce) + " were expected");
    out.origins.emplace_back(o[i]);
    out.directions.emplace_back(d[i]);
    out.pixels.push_back(static_cast<int32_t>(i));
    out.samples.push_back(sample);
  }
}

}  // namespace wf
}  // namespace rt
