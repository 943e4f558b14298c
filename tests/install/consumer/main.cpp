// The smallest useful Rill program: y = 2x + 1 over a stream, on the CPU backend.
#include <rill/rill.h>

#include <cstdio>
#include <exception>
#include <vector>

int main() try {
  using namespace rill;
  Program affine = program("affine", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    y = x * 2.0f + 1.0f;
  });
  Stream<Float> in(std::vector<float>{0.0f, 1.0f, 2.5f}), out(3);
  Kernel k = compile(affine, "cpu");
  k.inputs(in).outputs(out);
  const int64_t written = k.execute();
  const std::vector<float> y = out.download();
  const bool ok = written == 3 && y == std::vector<float>{1.0f, 3.0f, 6.0f};
  std::printf("consumer: wrote %lld: %g %g %g: %s\n", static_cast<long long>(written), y[0], y[1],
              y[2], ok ? "OK" : "WRONG");
  return ok ? 0 : 1;
} catch (const std::exception& e) {
  std::fprintf(stderr, "consumer: %s\n", e.what());
  return 1;
}
