// Writes the generated C (Kernel::source()) of Mandelbrot and a 400-RILL_IF kernel for cpu and simd.
// Build: g++ -std=c++20 -O1 -Idsl/include -Ibench kdump.cpp -o kdump build/librill.a -ltbb -lOpenCL -ldl
#include <rill/rill.h>
#include <fstream>
#include "MandelbrotKernel.h"  // bench/, on the include path
using namespace rill;
int main(int argc, char** argv) {
  std::string dir = argc > 1 ? argv[1] : ".";
  Uniform<Float> x0(0.f, "x0"), y0(0.f, "y0"), step(0.01f, "step");
  Uniform<Int> it(256, "max_iter");
  Program mandel = bench::mandelbrot_program(x0, y0, step, it);
  Program ifs = program("ifs400", [&] {
    Input<Float> x("x");
    Output<Float> y("y");
    Float acc = x;
    Int n = 0;
    for (int i = 0; i < 400; ++i) {
      RILL_IF(acc > float(i % 7) * 0.25f) {
        acc = acc * 0.5f + float(i) * 0.01f;
        n += 1;
      }
      RILL_ELSE {
        acc = acc + 0.75f;
      }
      RILL_ENDIF;
    }
    y = acc + to_float(n);
  });
  for (auto* p : {&mandel, &ifs})
    for (const char* b : {"cpu", "simd"}) {
      Kernel k = compile(*p, b);
      std::ofstream(dir + "/" + (p == &mandel ? "mandel" : "ifs400") + "_" + b + ".c") << k.source();
    }
}
