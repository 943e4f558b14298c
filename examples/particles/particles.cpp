// A particle system that stays on the device between launches.
//
//   rill-particles [--backend NAME] [--steps N] [--count N]
//
// Exit status: 0 on success, 77 if the backend cannot run here, 1 on an error or a wrong
// result, 2 on bad options.
//
// Each step is two launches and two reductions, and nothing but two numbers comes back:
//   1. `field` writes a swirling force field on a 64x64 grid into a stream;
//   2. `move` updates every particle (a RILL_STRUCT record, bound by name) in place, reading
//      the force of its cell straight from the stream `field` wrote: a gather from a stream;
//   3. rill::count and rill::sum fold the per-particle outputs on the same backend.
#include <rill/rill.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <random>
#include <string>
#include <vector>

using namespace rill;

// A particle: position in the unit square (periodic), velocity, and seconds left to live.
// Records are declared at namespace scope; each field becomes its own stream ("p.pos", ...).
RILL_STRUCT(Particle, (Float2, pos), (Float2, vel), (Float, life));

int main(int argc, char** argv) try {
  std::string backend_name = "cpu";
  int steps = 10, count = 100000;
  for (int i = 1; i + 1 < argc; i += 2) {
    std::string a = argv[i], v = argv[i + 1];
    if (a == "--backend")
      backend_name = v;
    else if (a == "--steps")
      steps = std::atoi(v.c_str());
    else if (a == "--count")
      count = std::atoi(v.c_str());
    else {
      std::fprintf(stderr, "usage: rill-particles [--backend NAME] [--steps N] [--count N]\n");
      return 2;
    }
  }
  if (std::string why = backend(backend_name).unavailable_reason(); !why.empty()) {
    std::printf("backend %s cannot run here: %s\n", backend_name.c_str(), why.c_str());
    return 77;  // "skipped", for CTest
  }

  constexpr int kGrid = 64;
  Uniform<Float> time(0.0f, "time"), dt(0.02f, "dt");

  // Launch 1: the force field, one element per grid cell. A vortex around the centre whose
  // pull towards the centre breathes with time.
  Program field_prog = program("field", [&] {
    Output<Float2> force("force");
    Float2 x = (to_float(element_coord()) + 0.5f) / float(kGrid) - 0.5f;  // cell centre
    Float pull = 0.5f + 0.5f * sin(time);
    force = Float2(-x.y(), x.x()) * 4.0f - x * pull;
  });

  // The field lives in a 2D stream; `move` gathers from it as field(x, y).
  Stream<Float2> field(kGrid, kGrid, "field");

  // Launch 2: move every particle. Input and output share the name "p", so binding a
  // Stream<Particle> to "p" updates it in place, field by field.
  Program move_prog = program("move", [&] {
    Input<Particle> p("p");
    Output<Particle> next("p");
    Output<Float> energy("energy");  // kinetic energy of the living, 0 for the dead
    Output<Int> alive("alive");      // 1 or 0, for rill::count

    Int2 cell = to_int(p.pos * float(kGrid));  // indices outside the grid are clamped
    Float2 f = field(cell);                    // what launch 1 wrote, still on the device
    Float2 vel = (p.vel + f * dt) * 0.995f;
    Float life = p.life - dt;
    next = Particle{fract(p.pos + vel * dt), vel, life};

    Bool live = life > 0.0f;
    energy = select(live, 0.5f * dot(vel, vel), 0.0f);
    alive = select(live, Int(1), Int(0));
  });

  Kernel field_k = compile(field_prog, backend_name);
  Kernel move_k = compile(move_prog, backend_name);

  // Initial particles on the host, uploaded once through the record's host twin.
  std::vector<Particle::Host> init(static_cast<size_t>(count));
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (auto& q : init) {
    q.pos = glm::vec2(u(rng), u(rng));
    q.vel = glm::vec2(u(rng) - 0.5f, u(rng) - 0.5f) * 0.2f;
    q.life = 0.1f + 1.9f * u(rng);  // seconds: 5 to 100 steps
  }
  Stream<Particle> particles(init, "particles");
  Stream<Float> energy(count, "energy");
  Stream<Int> alive(count, "alive");

  // Binding by name: the record binds p.pos, p.vel and p.life (as inputs and outputs).
  field_k.bind("force", field);
  move_k.bind("p", particles).bind("energy", energy).bind("alive", alive);

  std::printf("%d particles on %s, %dx%d force field\n", count, backend_name.c_str(), kGrid, kGrid);
  int64_t last_alive = count;
  bool ok = true;  // checked for the smoke test: nobody comes back to life, energy is finite
  for (int s = 1; s <= steps; ++s) {
    time.set(static_cast<float>(s) * 0.02f);
    field_k.execute();                           // writes `field` on the device
    move_k.execute();                            // gathers from it; writes particles, energy, alive
    const int64_t n_alive = rill::count(alive);  // reductions run where the streams are
    const float total = rill::sum(energy);
    std::printf("step %3d  alive %7lld  kinetic energy %10.4f\n", s, (long long)n_alive, total);
    ok = ok && n_alive <= last_alive && std::isfinite(total);
    last_alive = n_alive;
  }

  if (!ok) std::printf("unexpected result\n");
  return ok ? 0 : 1;
} catch (const std::exception& e) {
  std::fprintf(stderr, "rill-particles: %s\n", e.what());
  return 1;
}
