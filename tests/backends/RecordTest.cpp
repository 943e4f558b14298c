// Records (RILL_STRUCT) on every backend: record inputs, outputs, uniforms, streams and
// arrays, bound by name; assignment in branches, select, DSL functions and nesting; and the
// errors for records and names that do not match.
#include "BackendTest.h"

RILL_STRUCT(Particle, (rill::Float3, pos), (rill::Float3, vel), (rill::Float, age));
RILL_STRUCT(Bounce, (rill::Float, floor), (rill::Float, restitution));
RILL_STRUCT(World, (Bounce, bounce), (rill::Float3, gravity), (rill::Float, dt));

namespace rill::testing {
namespace {

class RecordTest : public BackendTest {};

// A DSL function over records: one explicit Euler step.
Particle integrate(const Particle& p, const World& w) {
  Particle next = p;
  next.vel = p.vel + w.gravity * w.dt;
  next.pos = p.pos + next.vel * w.dt;
  next.age = p.age + w.dt;
  return next;
}

Particle::Host integrate_host(const Particle::Host& p, const World::Host& w) {
  Particle::Host next = p;
  next.vel = p.vel + w.gravity * w.dt;
  next.pos = p.pos + next.vel * w.dt;
  next.age = p.age + w.dt;
  if (next.pos.y < w.bounce.floor) {
    next.pos.y = w.bounce.floor;
    next.vel.y = -next.vel.y * w.bounce.restitution;
  }
  // Old particles restart at the origin, still moving.
  if (next.age > 1.0f) next = Particle::Host{glm::vec3(0.0f), next.vel, 0.0f};
  return next;
}

std::vector<Particle::Host> some_particles(int n) {
  std::vector<Particle::Host> ps(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    const float f = static_cast<float>(i);
    ps[static_cast<size_t>(i)] = {glm::vec3(f * 0.25f, 0.05f * static_cast<float>(i % 7), -f),
                                  glm::vec3(1.0f, -0.5f * static_cast<float>(i % 5), 0.125f),
                                  0.01f * static_cast<float>(i % 120)};
  }
  return ps;
}

TEST_P(RecordTest, ParticleStepInPlaceBoundByName) {
  const World::Host world{{0.0f, 0.75f}, glm::vec3(0.0f, -9.75f, 0.0f), 0.0625f};
  Uniform<World> w(world, "world");
  Program step = program("particle_step", [&] {
    Input<Particle> p("p");
    Output<Particle> out("p");  // the same name: bind("p", ...) binds both, in place
    Particle next = integrate(p, w);
    RILL_IF(next.pos.y() < w.bounce.floor) {
      next.pos.y() = w.bounce.floor;
      next.vel.y() = -next.vel.y() * w.bounce.restitution;
    }
    RILL_ENDIF;
    Particle restart(Float3(0.0f), next.vel, Float(0.0f));
    out = select(next.age > 1.0f, restart, next);
  });
  const int n = 200;
  std::vector<Particle::Host> host = some_particles(n);
  Stream<Particle> ps(host, "particles");
  Kernel k = compile(step);
  k.bind("p", ps);
  for (int frame = 0; frame < 3; ++frame) {
    k.execute();
    for (auto& p : host) p = integrate_host(p, world);
  }
  std::vector<Particle::Host> got = ps.download();
  ASSERT_EQ(got.size(), host.size());
  for (size_t i = 0; i < got.size(); ++i) {
    ASSERT_EQ(got[i].pos, host[i].pos) << "particle " << i;
    ASSERT_EQ(got[i].vel, host[i].vel) << "particle " << i;
    ASSERT_EQ(bits_of(got[i].age), bits_of(host[i].age)) << "particle " << i;
  }
  // Each field is a stream of its own, readable as one vector.
  std::vector<float> ages = ps.field<Float>("age").download();
  for (size_t i = 0; i < ages.size(); ++i) EXPECT_EQ(bits_of(ages[i]), bits_of(host[i].age));
}

TEST_P(RecordTest, ArraysAndStreamsGatherWholeRecords) {
  const int n = 50;
  std::vector<Particle::Host> host = some_particles(n);
  Array<Particle> table(host, "table");
  Stream<Particle> mirror(n, "mirror");
  // Writes the table reversed, then reads it back through a stream gather.
  Program reverse = program("reverse_table", [&] {
    Output<Particle> out("out");
    out = table[(n - 1) - element_index()];
  });
  Program unreverse = program("unreverse", [&] {
    Output<Float3> pos("pos");
    Output<Float> age("age");
    Particle p = mirror[(n - 1) - element_index()];
    pos = p.pos;
    age = p.age;
  });
  compile(reverse).bind("out", mirror).execute();
  Stream<Float3> pos(n);
  Stream<Float> age(n);
  compile(unreverse).bind("pos", pos).bind("age", age).execute();
  std::vector<Particle::Host> m = mirror.download();
  std::vector<glm::vec3> got_pos = pos.download();
  std::vector<float> got_age = age.download();
  for (int i = 0; i < n; ++i) {
    const auto& want = host[static_cast<size_t>(n - 1 - i)];
    EXPECT_EQ(m[static_cast<size_t>(i)].vel, want.vel) << i;
    EXPECT_EQ(got_pos[static_cast<size_t>(i)], host[static_cast<size_t>(i)].pos) << i;
    EXPECT_EQ(got_age[static_cast<size_t>(i)], host[static_cast<size_t>(i)].age) << i;
  }
}

TEST_P(RecordTest, LoopsCarryRecordState) {
  // A record as explicit loop state: the loop updates all of it in one assignment.
  Program p = program("record_loop", [] {
    Input<Float> x("x");
    Output<Bounce> out("out");
    Bounce b(x, Float(0.0f));
    Int i = 0;
    RILL_WHILE(i < 5) {
      b = Bounce(b.floor * 0.5f + 1.0f, b.restitution + b.floor);
      i += 1;
    }
    RILL_ENDWHILE;
    out = b;
  });
  std::vector<float> xs = {0.0f, 1.0f, -3.5f, 100.0f};
  Stream<Float> in(xs);
  Stream<Bounce> out(static_cast<int64_t>(xs.size()));
  compile(p).bind("x", in).bind("out", out).execute();
  std::vector<Bounce::Host> got = out.download();
  for (size_t k = 0; k < xs.size(); ++k) {
    float f = xs[k], r = 0.0f;
    for (int i = 0; i < 5; ++i) {
      const float nf = f * 0.5f + 1.0f;
      r = r + f;
      f = nf;
    }
    EXPECT_EQ(bits_of(got[k].floor), bits_of(f)) << k;
    EXPECT_EQ(bits_of(got[k].restitution), bits_of(r)) << k;
  }
}

TEST_P(RecordTest, MismatchedNamesAndTypesAreErrors) {
  Program step = program("named_step", [] {
    Input<Particle> p("p");
    Output<Float3> pos("pos");
    pos = p.pos + p.vel;
  });
  Kernel k = compile(step);
  auto message = [](auto&& f) {
    try {
      f();
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  Stream<Particle> ps(4, "ps");
  Stream<Bounce> bs(4, "bs");
  Stream<Float> floats(4, "floats");
  Stream<Float3> f3(4, "f3");
  // A name the kernel lacks: the message lists what it has.
  std::string m = message([&] { k.bind("q", f3); });
  EXPECT_NE(m.find("no input or output named 'q'"), std::string::npos) << m;
  EXPECT_NE(m.find("p.vel (float3)"), std::string::npos) << m;
  // A stream of the wrong element type.
  m = message([&] { k.bind("pos", floats); });
  EXPECT_NE(m.find("output 'pos' (float3)"), std::string::npos) << m;
  EXPECT_NE(m.find("'floats' of float"), std::string::npos) << m;
  // A record stream that does not match the record parameter.
  m = message([&] { k.bind("p", bs); });
  EXPECT_NE(m.find("record stream 'bs' does not match 'p'"), std::string::npos) << m;
  EXPECT_NE(m.find("p.floor"), std::string::npos) << m;
  // Left unbound: every missing name at once.
  m = message([&] { k.execute(); });
  EXPECT_NE(m.find("not bound"), std::string::npos) << m;
  EXPECT_NE(m.find("p.pos"), std::string::npos) << m;
  EXPECT_NE(m.find("'pos'"), std::string::npos) << m;
  // Bound properly, it runs.
  ps.fill(Particle::Host{glm::vec3(1.0f), glm::vec3(2.0f), 0.0f});
  k.bind("p", ps).bind("pos", f3).execute();
  EXPECT_EQ(f3.download()[3], glm::vec3(3.0f));
  // A field of the wrong type asked of a record stream.
  EXPECT_THROW(ps.field<Float>("pos"), Error);
  EXPECT_THROW(ps.field<Float>("mass"), Error);
}

// A kernel that reads and writes only some fields of a record stream binds them with
// bind_fields; the other fields keep their data. Declaring none of them is an error.
TEST_P(RecordTest, SomeFieldsBoundByName) {
  Program age = program("age_only", [] {
    Input<Float> a("p.age");
    Input<Float3> v("p.vel");
    Output<Float> out("p.age");
    out = a + v.x();
  });
  Stream<Particle> ps(some_particles(50), "particles");
  const std::vector<Particle::Host> before = ps.download();
  Kernel k = compile(age);
  EXPECT_THROW(k.bind("p", ps), Error);  // the strict bind wants every field declared
  k.bind_fields("p", ps).execute();
  const std::vector<Particle::Host> after = ps.download();
  for (size_t i = 0; i < after.size(); ++i) {
    EXPECT_EQ(bits_of(after[i].age), bits_of(before[i].age + before[i].vel.x)) << i;
    EXPECT_EQ(after[i].pos, before[i].pos) << i;
    EXPECT_EQ(after[i].vel, before[i].vel) << i;
  }
  Stream<Bounce> bs(50, "bs");
  try {
    k.bind_fields("b", bs);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("declares no field of record stream 'bs'"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace

RILL_BACKEND_TEST_SUITE(RecordTest);

}  // namespace rill::testing
