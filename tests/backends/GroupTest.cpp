// Lane-group operations (rill/Group.h) on every backend, checked by invariants that hold for
// any group size: each element writes out its group's size, its lane index and an id of its
// group (the smallest element index in it, from group_min), and the host recomputes every
// result from the members of each group, lanes and predicates as the elements report them.
// A group of one (cpu, OpenCL, GLSL here) and the simd backend's lane blocks, short tail
// groups and 2D tiles included, must all agree with that recomputation.
//
// GroupSizeIndependentProgram is the other half of the contract: a program whose outputs do
// not depend on the group gives the same bits on every backend, here the host's.
#include "BackendTest.h"

namespace rill::testing {
namespace {

class GroupTest : public BackendTest {};

using I4 = glm::ivec4;

// The program under test: v is each element's input; `odd` branches make groups diverge.
Program group_program() {
  return program("group_ops", [] {
    Input<Int> v("v");
    Output<Int4> info("info"), red("red"), ballot("ballot"), more("more");
    Int size = group_size(), lane = lane_index();
    info = Int4(size, lane, group_min(element_index()), group_count(Bool(true)));
    red = Int4(
        group_sum(v), group_max(v), group_count(v > 0),
        select(group_any(v > 50), Int(1), Int(0)) + select(group_all(v > -90), Int(2), Int(0)));
    ballot = group_ballot(v > 0);
    Int next = group_broadcast(v, (lane + 1) % size);
    Int inside = -1, looped = 0;
    // Inside a branch only the lanes taking it count.
    RILL_IF(v % 3 != 0) {
      inside = group_sum(Int(1)) * 1000 + group_ballot(Bool(true)).x() % 1000;
    }
    RILL_ENDIF;
    // In a loop, the lanes still looping: element e runs (v & 7) iterations.
    RILL_FOR(Int k = 0, k < (v & 7), k += 1) {
      looped += group_count(Bool(true));
    }
    RILL_ENDFOR;
    Float half = group_broadcast(to_float(v) * 0.5f, Int(0));
    more = Int4(next, inside, looped, as_int(half));
  });
}

// What one group's elements must hold, from the members as they report themselves.
void check_groups(const std::vector<int32_t>& v, const std::vector<I4>& info,
                  const std::vector<I4>& red, const std::vector<I4>& ballot,
                  const std::vector<I4>& more, const std::string& where) {
  std::map<int32_t, std::vector<size_t>> groups;  // id -> members
  for (size_t i = 0; i < v.size(); ++i) groups[info[i].z].push_back(i);
  for (const auto& [id, members] : groups) {
    SCOPED_TRACE(where + ", group of element " + std::to_string(id));
    const int32_t size = info[members[0]].x;
    ASSERT_GE(size, 1);
    ASSERT_LE(size, 128);  // the ballot's width
    ASSERT_LE(static_cast<int32_t>(members.size()), size);
    ASSERT_EQ(static_cast<int32_t>(members[0]), id) << "the id is the smallest member";
    std::map<int32_t, size_t> by_lane;
    uint32_t sum = 0;
    int32_t max = std::numeric_limits<int32_t>::min(), positive = 0;
    bool any50 = false, all90 = true;
    std::array<uint32_t, 4> bits{}, bits3{};
    int32_t count3 = 0;
    for (size_t m : members) {
      ASSERT_EQ(info[m].x, size);
      ASSERT_GE(info[m].y, 0);
      ASSERT_LT(info[m].y, size);
      ASSERT_TRUE(by_lane.emplace(info[m].y, m).second) << "lane " << info[m].y << " twice";
      sum += static_cast<uint32_t>(v[m]);
      max = std::max(max, v[m]);
      const auto lane = static_cast<size_t>(info[m].y);
      if (v[m] > 0) {
        ++positive;
        bits[lane / 32] |= 1u << (lane % 32);
      }
      if (v[m] % 3 != 0) {
        ++count3;
        bits3[lane / 32] |= 1u << (lane % 32);
      }
      any50 = any50 || v[m] > 50;
      all90 = all90 && v[m] > -90;
    }
    for (size_t m : members) {
      SCOPED_TRACE("element " + std::to_string(m) + ", lane " + std::to_string(info[m].y));
      EXPECT_EQ(info[m].w, static_cast<int32_t>(members.size()));
      EXPECT_EQ(red[m],
                I4(static_cast<int32_t>(sum), max, positive, (any50 ? 1 : 0) + (all90 ? 2 : 0)));
      EXPECT_EQ(ballot[m], I4(static_cast<int32_t>(bits[0]), static_cast<int32_t>(bits[1]),
                              static_cast<int32_t>(bits[2]), static_cast<int32_t>(bits[3])));
      // Broadcast from the next lane, or the element's own value where that lane is empty.
      auto next = by_lane.find((info[m].y + 1) % size);
      EXPECT_EQ(more[m].x, next == by_lane.end() ? v[m] : v[next->second]);
      const int32_t inside =
          v[m] % 3 != 0 ? count3 * 1000 + static_cast<int32_t>(bits3[0] % 1000u) : -1;
      EXPECT_EQ(more[m].y, inside);
      int32_t looped = 0;
      for (int32_t k = 0; k < (v[m] & 7); ++k)
        for (size_t o : members) looped += (v[o] & 7) > k ? 1 : 0;
      EXPECT_EQ(more[m].z, looped);
      auto first = by_lane.find(0);
      const float half =
          static_cast<float>(first == by_lane.end() ? v[m] : v[first->second]) * 0.5f;
      EXPECT_EQ(more[m].w, std::bit_cast<int32_t>(half));
    }
  }
}

TEST_P(GroupTest, ResultsAgreeWithTheReportedGroups) {
  // 1001 elements: the simd backend's last group is short.
  const std::vector<int32_t> v = small_ints(11, 1001, -100, 100);
  Kernel k = compile(group_program());
  auto [info, red, ballot, more] = run_kernel<Int4, Int4, Int4, Int4>(k, 1001, v);
  check_groups(v, info, red, ballot, more, "1D");
}

TEST_P(GroupTest, ResultsAgreeWithTheReportedGroupsOn2DStreams) {
  // Shapes whose rows the simd backend tiles in pairs, with odd rows and short rows.
  for (auto [w, h] : {std::pair<int64_t, int64_t>{37, 5}, {4, 9}, {1, 7}, {64, 2}}) {
    const size_t n = static_cast<size_t>(w * h);
    const std::vector<int32_t> v = small_ints(static_cast<uint32_t>(w * 131 + h), n, -100, 100);
    Kernel k = compile(group_program());
    Stream<Int> in(w, h);
    in.upload(v);
    Stream<Int4> info(w, h), red(w, h), ballot(w, h), more(w, h);
    k.inputs(in).outputs(info, red, ballot, more);
    k.execute();
    check_groups(v, info.download(), red.download(), ballot.download(), more.download(),
                 std::to_string(w) + "x" + std::to_string(h));
  }
}

TEST_P(GroupTest, GroupOfOneWhereTheBackendHasNoLanes) {
  // What each backend reports: the simd backend's lanes in strict and fast, a group of one
  // for the others (docs/programming-model.md, "Lane groups").
  Program p = program("group_size", [] {
    Output<Int> s("s");
    s = group_size();
  });
  const std::vector<int32_t> s = run_n<Int>(p, 5);
  int32_t expected = 1;
  // simd: the lanes its description states for strict ("lockstep C, 16 lanes in strict
  // (AVX-512), 8 in fast" where the CPU has AVX-512, else "lockstep C, 8 lanes").
  if (backend_name() == "simd") {
    const std::string d = rill::backend("simd").description();
    const std::string tag = "lockstep C, ";
    const size_t at = d.find(tag);
    ASSERT_NE(at, std::string::npos) << d;
    expected = std::stoi(d.substr(at + tag.size()));
    EXPECT_TRUE(expected == 8 || expected == 16) << d;
  }
  // vulkan and glsl-compute: the device's subgroups where it has them, as the description
  // says ("lane groups: subgroups of 8" on lavapipe, 32 on NVIDIA's GL), else a group of one.
  bool lanes = backend_name() == "simd";
  if (backend_name() == "vulkan" || backend_name() == "glsl-compute") {
    const std::string d = rill::backend(backend_name()).description();
    const std::string tag = "lane groups: subgroups of ";
    if (const size_t at = d.find(tag); at != std::string::npos) {
      expected = std::stoi(d.substr(at + tag.size()));
      lanes = true;
    }
  }
  for (int32_t x : s) EXPECT_EQ(x, expected);
  if (lanes) {
    EXPECT_GE(expected, 2);
    EXPECT_EQ(expected & (expected - 1), 0) << "a power of two";
  }
}

// Group operations used so that no output depends on the group: a group-wide early out
// whose two sides compute the same thing, a broadcast from the element's own lane, and a
// sum that subtracts everyone else's part again. Every backend must give the host's bits.
TEST_P(GroupTest, GroupSizeIndependentProgramGivesTheSameBitsEverywhere) {
  Program p = program("group_independent", [] {
    Input<Int> v("v");
    Output<Float> y("y");
    Output<Int> z("z");
    Float r = 0.0f;
    RILL_IF(group_all(v <= 0)) {
      r = 0.0f;
    }
    RILL_ELSE {
      r = select(v > 0, to_float(v) * 0.37f + 1.0f, 0.0f);
    }
    RILL_ENDIF;
    y = group_broadcast(r, lane_index());
    Int mine = v * 3 + 1;
    Bool positive = group_broadcast(v > 0, lane_index());
    z = group_sum(mine) - (group_sum(mine) - mine) + select(positive, Int(1000000), Int(0));
  });
  const std::vector<int32_t> v = small_ints(5, 777, -50, 50);
  auto [y, z] = run<Float, Int>(p, v);
  for (size_t i = 0; i < v.size(); ++i) {
    const float r = v[i] > 0 ? static_cast<float>(v[i]) * 0.37f + 1.0f : 0.0f;
    ASSERT_EQ(std::bit_cast<uint32_t>(y[i]), std::bit_cast<uint32_t>(r)) << "at " << i;
    ASSERT_EQ(z[i], v[i] * 3 + 1 + (v[i] > 0 ? 1000000 : 0)) << "at " << i;
  }
}

// Kernels that use no group op keep their source: the lockstep group helpers (rill_g_*) and
// the group's lane masks are emitted only into kernels that use them.
TEST_P(GroupTest, GroupCodeOnlyInKernelsThatUseIt) {
  Program plain = program("no_group", [] {
    Input<Int> v("v");
    Output<Int> y("y");
    y = v * 2;
  });
  EXPECT_EQ(compile(plain).source().find("rill_g_"), std::string::npos);
  EXPECT_EQ(compile(plain).source().find("rill_live"), std::string::npos);
  if (backend_name() == "simd") {
    EXPECT_NE(compile(group_program()).source().find("rill_g_sum"), std::string::npos);
  }
}

RILL_BACKEND_TEST_SUITE(GroupTest);

}  // namespace
}  // namespace rill::testing
