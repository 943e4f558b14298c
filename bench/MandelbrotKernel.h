// The Mandelbrot escape-time kernel shared by the benchmarks (mandelbrot.cpp compares it with
// hand-written C++, accuracy_cost.cpp with a double-precision reference), so both measure the
// same kernel: the Rill program, the view it samples and the same iteration written as plain
// C++ on any real type (float: statement for statement what the kernel compiles to in strict
// mode; double: the reference of the accuracy benchmark and of Rill's double mode).
#pragma once

#include <rill/rill.h>

#include <cstdint>

namespace rill::bench {

struct MandelbrotView {
  int64_t width = 1920, height = 1080;
  int32_t iterations = 256;
  float x0 = 0, y0 = 0, step = 0;  // pixel (i, j) samples (x0 + (i+.5)*step, y0 + (j+.5)*step)

  // Frames the real axis -2.1 .. 0.9, centred vertically on 0.
  void frame() {
    step = 3.0f / static_cast<float>(width);
    x0 = -2.1f;
    y0 = -0.5f * step * static_cast<float>(height);
  }
};

// The coordinate of pixel column (or row) `index`, as the kernel computes it in Real.
template <class Real>
Real pixel_centre(float origin, int32_t index, float step) {
  return static_cast<Real>(origin) +
         (static_cast<Real>(index) + static_cast<Real>(0.5f)) * static_cast<Real>(step);
}

// Escape-time iteration count of c = (cx, cy), at most max_iter.
template <class Real>
int32_t escape_iterations(Real cx, Real cy, int32_t max_iter) {
  Real zx = 0, zy = 0;
  int32_t i = 0;
  while (i < max_iter) {
    const Real x2 = zx * zx, y2 = zy * zy;
    if (x2 + y2 > static_cast<Real>(4.0f)) break;
    zy = static_cast<Real>(2.0f) * zx * zy + cy;
    zx = x2 - y2 + cx;
    i += 1;
  }
  return i;
}

// The Rill program: one Int output, the iteration count of each pixel of a 2D stream.
inline Program mandelbrot_program(const Uniform<Float>& x0, const Uniform<Float>& y0,
                                  const Uniform<Float>& step, const Uniform<Int>& max_iter) {
  return program("mandelbrot", [&] {
    Output<Int> iters("iters");
    Int2 pixel = element_coord();
    Float cx = x0 + (to_float(pixel.x()) + 0.5f) * step;
    Float cy = y0 + (to_float(pixel.y()) + 0.5f) * step;
    Float zx = 0.0f, zy = 0.0f;
    Int i = 0;
    RILL_WHILE(i < max_iter) {
      Float x2 = zx * zx, y2 = zy * zy;
      RILL_IF(x2 + y2 > 4.0f) {
        RILL_BREAK;
      }
      RILL_ENDIF;
      zy = 2.0f * zx * zy + cy;
      zx = x2 - y2 + cx;
      i += 1;
    }
    RILL_ENDWHILE;
    iters = i;
  });
}

}  // namespace rill::bench
