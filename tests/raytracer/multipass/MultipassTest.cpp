// The multipass strategy's knobs and statistics: masked launches on and off and every
// intersector threshold give the single kernel's bits; the per-pass statistics are
// consistent (written <= processed, the passes that must run did run, without a mask every
// launch processes every element, with masks the trace passes process exactly the rays in
// their state), and masking processes fewer elements than running every kernel everywhere.
#include <gtest/gtest.h>

#include <cstring>
#include <map>

#include "TestUtil.h"
#include "rill/rt/Tracer.h"
#include "rill/rt/accel/Grid.h"

namespace rt {
namespace {

class Multipass : public ::testing::TestWithParam<std::string> {};

std::map<std::string, PassStats> by_name(const RenderResult& r) {
  std::map<std::string, PassStats> m;
  for (const PassStats& p : r.passes) m[p.name] = p;
  return m;
}

bool same_image(const RenderResult& a, const RenderResult& b) {
  return a.color.size() == b.color.size() &&
         std::memcmp(a.color.data(), b.color.data(), a.color.size() * sizeof(glm::vec3)) == 0 &&
         a.prim == b.prim && a.rays == b.rays;
}

TEST_P(Multipass, MaskingAndThresholdsKeepTheBitsAndStatsAreConsistent) {
  RT_REQUIRE_BACKEND(GetParam());
  Scene s = builtin_scene("thesis-a");
  Grid g = build_grid(s, 0);
  Tracer t(s, g);
  RenderSettings rs;
  rs.outputs.depth = rs.outputs.prim = rs.outputs.normal = true;  // the AOVs compared
  rs.backend = GetParam();
  rs.width = 20;
  rs.height = 14;
  rs.max_depth = 2;
  const RenderResult mega = t.render(rs, s.camera);
  EXPECT_TRUE(mega.passes.empty());

  rs.strategy = Strategy::Multipass;
  rs.masking = true;
  const RenderResult on = t.render(rs, s.camera);
  rs.masking = false;
  const RenderResult off = t.render(rs, s.camera);
  EXPECT_TRUE(same_image(mega, on)) << "masking on";
  EXPECT_TRUE(same_image(mega, off)) << "masking off";

  auto pon = by_name(on), poff = by_name(off);
  int64_t total_on = 0, total_off = 0;
  for (const auto& [name, p] : pon) {
    SCOPED_TRACE(name);
    const PassStats& q = poff.at(name);
    EXPECT_LE(p.written, p.processed);
    EXPECT_LE(q.written, q.processed);
    EXPECT_EQ(p.calls, q.calls);  // the host loop sees the same counts either way
    EXPECT_EQ(p.written, q.written);
    EXPECT_GE(p.ms, 0.0);
    // Without masks every launch runs on every element (the stream is padded on GLSL).
    if (q.calls > 0) {
      EXPECT_EQ(q.processed % q.calls, 0);
      EXPECT_GE(q.processed / q.calls, int64_t{rs.width} * rs.height);
    }
    total_on += p.processed;
    total_off += q.processed;
  }
  for (const char* must : {"raygen", "voxel_precalc", "traverser", "intersector", "surface",
                           "shadow_rays", "shadow_light", "combine"})
    EXPECT_GT(pon.at(must).calls, 0) << must;
  // Traverser and intersector write every ray they run on: masked, they run on exactly the
  // rays in their state.
  EXPECT_EQ(pon.at("traverser").processed, pon.at("traverser").written);
  EXPECT_EQ(pon.at("intersector").processed, pon.at("intersector").written);
  EXPECT_LT(pon.at("intersector").processed, poff.at("intersector").processed);
  EXPECT_LT(total_on, total_off);

  // The threshold changes how often the intersector reruns, not the image.
  rs.masking = true;
  rs.wait_threshold = 0.05;
  const RenderResult eager = t.render(rs, s.camera);
  rs.wait_threshold = 1.0;
  const RenderResult once = t.render(rs, s.camera);
  EXPECT_TRUE(same_image(mega, eager)) << "threshold 5%";
  EXPECT_TRUE(same_image(mega, once)) << "threshold 100%";
  EXPECT_GE(by_name(eager).at("intersector").calls, by_name(once).at("intersector").calls);

  rs.wait_threshold = 0.0;
  EXPECT_THROW(t.render(rs, s.camera), std::runtime_error);
}

INSTANTIATE_TEST_SUITE_P(Backends, Multipass, ::testing::ValuesIn(testing::backend_names()),
                         [](const auto& info) { return rill::testing::param_name(info.param); });

}  // namespace
}  // namespace rt
