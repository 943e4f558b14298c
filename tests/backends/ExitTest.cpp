// Exit with device data still alive: streams and arrays in statics hold device copies (GL
// textures, OpenCL buffers) and the kernel cache holds compiled kernels when the process
// exits. Static destructors then run after the backends are destroyed and after the GLSL
// backend has shut its context down (GLSLBackend.cpp, Session); none of them may call into a
// backend or a context that is gone. The test passes when the process exits with status 0
// (and, in a sanitized build, without a use-after-free report).
#include <rill/rill.h>

#include <cstdio>
#include <exception>
#include <string>
#include <vector>

namespace {

// Constructed before main, so destroyed after the backend registry and the kernel cache.
rill::Stream<rill::Float> g_values(std::vector<float>{1.0f, 2.0f, 3.0f, 4.0f});
rill::Array<rill::Float> g_table(std::vector<float>{10.0f, 20.0f, 30.0f, 40.0f}, "table");

}  // namespace

int main() try {
  using namespace rill;
  Program add = program("add_table", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    y = x + g_table[element_index()];
  });
  int ran = 0;
  for (Backend* b : backends()) {
    if (!b->unavailable_reason().empty()) {
      std::printf("%s: unavailable, skipped\n", b->name().c_str());
      continue;
    }
    // Runs on this backend: the static stream's freshest copy (and the array's upload) stay
    // on its device, kept in a static until exit. The next backend reads it back first.
    Kernel k = compile(add, b->name());
    k.inputs(g_values).outputs(g_values);
    k.execute();
    ++ran;
    std::printf("%s: ran\n", b->name().c_str());
  }
  // A stream made in main, left in a static with its freshest copy on a device.
  static Stream<Float> late(4);
  std::string last = "cpu";
  for (Backend* b : backends())
    if (b->name() == "glsl" && b->unavailable_reason().empty()) last = "glsl";
  Kernel k = compile(add, last);
  k.inputs(g_values).outputs(late);
  k.execute();
  // Each launch added the table once, on whichever device held the freshest copy.
  const std::vector<float> table{10.0f, 20.0f, 30.0f, 40.0f};
  const std::vector<float> got = late.download();
  for (size_t i = 0; i < got.size(); ++i) {
    const float expect = (1.0f + static_cast<float>(i)) + table[i] * static_cast<float>(ran + 1);
    if (got[i] != expect) {
      std::fprintf(stderr, "exit test: element %zu is %g, expected %g\n", i, got[i], expect);
      return 1;
    }
  }
  return ran > 0 ? 0 : 1;
} catch (const std::exception& e) {
  std::fprintf(stderr, "exit test: %s\n", e.what());
  return 1;
}
