// Records at capture time: the names and order of the leaves they declare, nesting, copies
// that are new variables, and host-side layout.
#include <gtest/gtest.h>
#include <rill/rill.h>

RILL_STRUCT(Hit, (rill::Float, t), (rill::Int, prim), (rill::Float2, uv));
RILL_STRUCT(Sample, (Hit, hit), (rill::Float3, weight));
RILL_STRUCT(Flagged, (rill::Float, x), (rill::Bool, on));

namespace rill {
namespace {

std::vector<std::string> names(const ir::Function& f, const std::vector<ir::VarId>& vs) {
  std::vector<std::string> out;
  for (ir::VarId v : vs) out.push_back(f.var(v).name + ":" + f.var(v).type.str());
  return out;
}

TEST(Record, LeavesAreNamedByPathInDeclarationOrder) {
  Program p = program("record_names", [] {
    Input<Sample> s("s");
    Input<Hit> unnamed;
    Output<Sample> o("o");
    o = s;
    o.hit.t = s.hit.t + unnamed.t;
  });
  const ir::Function& f = p.ir();
  EXPECT_EQ(names(f, f.inputs),
            (std::vector<std::string>{"s.hit.t:float", "s.hit.prim:int", "s.hit.uv:float2",
                                      "s.weight:float3", "t:float", "prim:int", "uv:float2"}));
  EXPECT_EQ(names(f, f.outputs), (std::vector<std::string>{"o.hit.t:float", "o.hit.prim:int",
                                                           "o.hit.uv:float2", "o.weight:float3"}));
}

TEST(Record, CopiesAreNewVariables) {
  // Writing a copy must not write the original: b = a copies, then b.t changes alone.
  Program p = program("record_copy", [] {
    Input<Hit> a("a");
    Output<Float> x("x"), y("y");
    Hit b = a;
    b.t = b.t + 1.0f;
    x = a.t;
    y = b.t;
  });
  // The inputs are never assigned; b's fields are locals of their own.
  int local_writes = 0;
  for (const ir::Stmt& s : p.ir().body)
    if (s.kind == ir::StmtKind::Assign) {
      EXPECT_NE(p.ir().var(s.dst).role, ir::VarRole::Input) << p.print();
      local_writes += p.ir().var(s.dst).role == ir::VarRole::Local;
    }
  EXPECT_GE(local_writes, 4) << p.print();  // three field copies and the write to b.t
}

TEST(Record, UniformsAreOnePerLeafAndSetFromTheHostTwin) {
  Uniform<Sample> u(Sample::Host{{2.5f, 7, glm::vec2(1.0f, 2.0f)}, glm::vec3(3.0f)}, "u");
  Program p = program("record_uniform", [&] {
    Output<Float> x("x");
    x = u.hit.t + u.weight.z() + to_float(u.hit.prim);
  });
  // Programs list the uniforms they read, in the order they first read them.
  ASSERT_EQ(p.captured().uniforms.size(), 3u);
  auto find = [&](const std::string& name) -> const detail::UniformState& {
    for (const auto& st : p.captured().uniforms)
      if (st->name == name) return *st;
    throw std::runtime_error("no uniform " + name);
  };
  EXPECT_EQ(std::bit_cast<float>(find("u.hit.t").bits[0]), 2.5f);
  EXPECT_EQ(find("u.hit.prim").bits[0], 7u);
  EXPECT_EQ(std::bit_cast<float>(find("u.weight").bits[2]), 3.0f);
  u.set(Sample::Host{{-1.0f, 9, glm::vec2(0.0f)}, glm::vec3(0.0f)});
  EXPECT_EQ(std::bit_cast<float>(find("u.hit.t").bits[0]), -1.0f);
  EXPECT_EQ(find("u.hit.prim").bits[0], 9u);
}

TEST(Record, StreamsOfRecordsRejectBoolFields) {
  try {
    Stream<Flagged> s(4, "flags");
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("field 'on' is a bool"), std::string::npos) << e.what();
  }
}

TEST(Record, HostUploadAndPerFieldViews) {
  Stream<Hit> s(
      std::vector<Hit::Host>{{1.0f, 2, glm::vec2(3.0f, 4.0f)}, {5.0f, 6, glm::vec2(7.0f)}}, "hits");
  EXPECT_EQ(s.size(), 2);
  EXPECT_EQ(s.field<Int>("prim").download(), (std::vector<int32_t>{2, 6}));
  s.field<Float>("t").upload(std::vector<float>{-1.0f, -2.0f});
  std::vector<Hit::Host> back = s.download();
  EXPECT_EQ(back[1].t, -2.0f);
  EXPECT_EQ(back[1].uv, glm::vec2(7.0f));
  EXPECT_THROW(s.upload(std::vector<Hit::Host>(3)), Error);
}

}  // namespace
}  // namespace rill
