// The accuracy knobs (TracerOptions): each is a DSL-level choice that generates different
// code (so the kernel cache keys on it), the command line parses them, and with every
// setting the backends stay bitwise identical in strict mode and the multipass strategy
// (built from the same DSL functions) computes the same bits as the single kernel.
#include <gtest/gtest.h>

#include <bit>
#include <cstring>
#include <set>

#include "TestUtil.h"
#include "rill/rt/Tracer.h"
#include "rill/rt/accel/Grid.h"

namespace rt {
namespace {

std::vector<TracerOptions> all_knobs() {
  std::vector<TracerOptions> v;
  for (int k = 0; k < 8; ++k) {
    TracerOptions t;
    t.triangle = (k & 4) ? TriangleTest::Watertight : TriangleTest::MollerTrumbore;
    t.offset = (k & 2) ? SelfIntersection::Scaled : SelfIntersection::Epsilon;
    t.traversal = (k & 1) ? Traversal::Recompute : Traversal::Incremental;
    v.push_back(t);
  }
  return v;
}

TEST(Knobs, DefaultsAndNames) {
  TracerOptions d;
  EXPECT_EQ(d.str(), "moller scaled incremental");
  EXPECT_EQ(parse_triangle_test("watertight"), TriangleTest::Watertight);
  EXPECT_EQ(parse_self_intersection("scaled"), SelfIntersection::Scaled);
  EXPECT_EQ(parse_traversal("recompute"), Traversal::Recompute);
  EXPECT_THROW(parse_triangle_test("woop"), std::invalid_argument);
  EXPECT_THROW(parse_self_intersection(""), std::invalid_argument);
  EXPECT_THROW(parse_traversal("Recompute"), std::invalid_argument);
}

// Every combination, with either megakernel loop, captures a different program: the kernel
// cache (keyed on the program's hash) can never hand one setting's kernel to another.
TEST(Knobs, EverySettingGeneratesDifferentCode) {
  Scene s = builtin_scene("cornell");
  Grid g = build_grid(s, 0);
  std::set<uint64_t> hashes;
  for (const TracerOptions& k : all_knobs()) {
    Tracer t(s, g, k);
    EXPECT_EQ(t.options().str(), k.str());
    hashes.insert(t.program(MegakernelLoop::Ray).hash());
    hashes.insert(t.program(MegakernelLoop::Segment).hash());
  }
  EXPECT_EQ(hashes.size(), 16u);
}

bool same_bits(const RenderResult& a, const RenderResult& b, std::string& why) {
  if (a.color.size() != b.color.size()) return why = "sizes differ", false;
  for (size_t p = 0; p < a.color.size(); ++p)
    if (std::memcmp(&a.color[p], &b.color[p], sizeof(glm::vec3)) != 0 || a.prim[p] != b.prim[p] ||
        std::bit_cast<uint32_t>(a.depth[p]) != std::bit_cast<uint32_t>(b.depth[p]))
      return why = "pixel " + std::to_string(p) + " differs", false;
  if (a.rays != b.rays) return why = "ray counts differ", false;
  return true;
}

class KnobsOnBackend : public ::testing::TestWithParam<std::string> {};

// Strict mode: the same bits on every backend and with both strategies, for every setting.
TEST_P(KnobsOnBackend, StrictIsIdenticalAcrossBackendsAndStrategies) {
  RT_REQUIRE_BACKEND(GetParam());
  Scene s = builtin_scene("cornell");
  Grid g = build_grid(s, 0);
  for (const TracerOptions& k : all_knobs()) {
    SCOPED_TRACE(k.str());
    Tracer t(s, g, k);
    RenderSettings rs;
    rs.outputs.depth = rs.outputs.prim = rs.outputs.normal = true;  // the AOVs compared
    rs.width = 20;
    rs.height = 16;
    rs.max_depth = 2;
    const RenderResult cpu = t.render(rs, s.camera);
    rs.backend = GetParam();
    const RenderResult mine = t.render(rs, s.camera);
    rs.strategy = Strategy::Multipass;
    const RenderResult multi = t.render(rs, s.camera);
    std::string why;
    EXPECT_TRUE(same_bits(cpu, mine, why)) << "cpu vs " << GetParam() << ": " << why;
    EXPECT_TRUE(same_bits(mine, multi, why)) << "megakernel vs multipass: " << why;
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, KnobsOnBackend, ::testing::ValuesIn(testing::backend_names()),
                         [](const auto& info) { return rill::testing::param_name(info.param); });

}  // namespace
}  // namespace rt
