// Renders the Mandelbrot set to a PNG with a Rill kernel.
//
//   rill-mandelbrot [--size WxH] [--iterations N] [--out FILE.png] [--backend NAME]
//                   [--accuracy strict|fast|double] [--center X,Y] [--view-width W]
//
// Exit status: 0 on success, 77 if the backend cannot run here or lacks the accuracy mode,
// 1 on an error or a wrong result, 2 on bad options.
//
// One kernel instance per pixel: element_coord() gives the pixel, a RILL_WHILE loop with
// RILL_BREAK iterates z = z^2 + c until |z| escapes, and the colour (a smooth iteration
// count through a cosine palette) is computed in the kernel too. The view is passed as
// uniforms, so a different view or iteration limit needs no recompile.
#include <png.h>
#include <rill/rill.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

namespace {

using namespace rill;

struct Options {
  int width = 1280, height = 720;
  int iterations = 512;
  std::string out = "mandelbrot.png";
  std::string backend = "cpu";
  Accuracy accuracy = Accuracy::Strict;
  float center_x = -0.6f, center_y = 0.0f;
  float view_width = 3.2f;  // width of the view in the complex plane
};

void usage(FILE* f) {
  std::fprintf(f,
               "usage: rill-mandelbrot [--size WxH] [--iterations N] [--out FILE.png]\n"
               "                       [--backend NAME] [--accuracy strict|fast|double]\n"
               "                       [--center X,Y] [--view-width W]\n"
               "backends:");
  for (Backend* b : backends()) std::fprintf(f, " %s", b->name().c_str());
  std::fprintf(f, "\n");
}

[[noreturn]] void fail(const std::string& msg) {
  std::fprintf(stderr, "rill-mandelbrot: %s\n", msg.c_str());
  std::exit(2);
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    if (a == "-h" || a == "--help") {
      usage(stdout);
      std::exit(0);
    }
    if (i + 1 >= argc) fail("option " + a + " needs a value (see --help)");
    std::string v = argv[++i];
    if (a == "--size") {
      if (std::sscanf(v.c_str(), "%dx%d", &o.width, &o.height) != 2 || o.width < 1 || o.height < 1)
        fail("--size expects WxH, e.g. 1280x720");
    } else if (a == "--iterations") {
      o.iterations = std::atoi(v.c_str());
      if (o.iterations < 1) fail("--iterations expects a positive number");
    } else if (a == "--out") {
      o.out = v;
    } else if (a == "--backend") {
      o.backend = v;
    } else if (a == "--accuracy") {
      o.accuracy = parse_accuracy(v);
    } else if (a == "--center") {
      if (std::sscanf(v.c_str(), "%f,%f", &o.center_x, &o.center_y) != 2)
        fail("--center expects X,Y, e.g. -0.6,0");
    } else if (a == "--view-width") {
      o.view_width = std::strtof(v.c_str(), nullptr);
      if (!(o.view_width > 0)) fail("--view-width expects a positive number");
    } else {
      fail("unknown option " + a + " (see --help)");
    }
  }
  return o;
}

void write_png(const std::string& path, int w, int h, const std::vector<uint8_t>& rgb) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  image.width = static_cast<png_uint_32>(w);
  image.height = static_cast<png_uint_32>(h);
  image.format = PNG_FORMAT_RGB;
  if (!png_image_write_to_file(&image, path.c_str(), 0, rgb.data(), 0, nullptr))
    throw std::runtime_error("cannot write " + path + ": " + image.message);
}

}  // namespace

int main(int argc, char** argv) try {
  const Options o = parse(argc, argv);

  // The view, as uniforms: pixel (i, j) samples c = origin + (i + 0.5, j + 0.5) * step.
  const float step = o.view_width / static_cast<float>(o.width);
  Uniform<Float2> origin(glm::vec2(o.center_x - step * static_cast<float>(o.width) * 0.5f,
                                   o.center_y + step * static_cast<float>(o.height) * 0.5f),
                         "origin");
  Uniform<Float> pixel_step(step, "step");
  Uniform<Int> max_iter(o.iterations, "max_iter");

  Program mandelbrot = program("mandelbrot", [&] {
    Output<Int> iters("iters");
    Output<Float3> color("color");

    Int2 pixel = element_coord();  // (column, row), row 0 at the top
    Float cx = origin.x() + (to_float(pixel.x()) + 0.5f) * pixel_step;
    Float cy = origin.y() - (to_float(pixel.y()) + 0.5f) * pixel_step;

    Float zx = 0.0f, zy = 0.0f, r2 = 0.0f;
    Int i = 0;
    RILL_WHILE(i < max_iter) {
      Float x2 = zx * zx, y2 = zy * zy;
      r2 = x2 + y2;
      RILL_IF(r2 > 256.0f) {  // escaped (a large radius gives smoother colours)
        RILL_BREAK;
      }
      RILL_ENDIF;
      zy = 2.0f * zx * zy + cy;
      zx = x2 - y2 + cx;
      i += 1;
    }
    RILL_ENDWHILE;
    iters = i;

    RILL_IF(i >= max_iter) {
      color = Float3(0.0f);  // inside the set
    }
    RILL_ELSE {
      // Continuous iteration count, then a cosine palette.
      Float smooth = to_float(i) + 1.0f - log2(0.5f * log2(r2));
      Float t = sqrt(smooth) * 0.25f;
      color = 0.5f + 0.5f * cos(6.2831853f * (t + Float3(0.0f, 0.15f, 0.3f)));
    }
    RILL_ENDIF;
  });

  // Exit status 77 (the usual "skipped" code, which the CTest tests use) when the backend is
  // built in but cannot run on this machine, or lacks the accuracy mode.
  Backend& be = backend(o.backend);
  if (std::string why = be.unavailable_reason(); !why.empty()) {
    std::fprintf(stderr, "rill-mandelbrot: backend %s cannot run here: %s\n", o.backend.c_str(),
                 why.c_str());
    return 77;
  }
  if (!be.supports(o.accuracy)) {
    std::fprintf(stderr, "rill-mandelbrot: backend %s has no %s accuracy mode\n", o.backend.c_str(),
                 accuracy_name(o.accuracy));
    return 77;
  }
  CompileOptions options;
  options.accuracy = o.accuracy;
  Kernel kernel = compile(mandelbrot, o.backend, options);

  Stream<Int> iters(o.width, o.height);
  Stream<Float3> color(o.width, o.height);
  kernel.outputs(iters, color);
  auto start = std::chrono::steady_clock::now();
  kernel.execute();
  std::vector<glm::vec3> pixels = color.download();
  double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();

  // Self-check: the centre of the default view, c = (-0.6, 0), lies inside the set, and the
  // top-left corner escapes within a few iterations.
  std::vector<int32_t> n = iters.download();
  const size_t centre = static_cast<size_t>(o.height / 2) * static_cast<size_t>(o.width) +
                        static_cast<size_t>(o.width / 2);
  bool default_view = o.center_x == -0.6f && o.center_y == 0.0f && o.view_width == 3.2f;
  if (default_view && (n[centre] != o.iterations || n[0] > 8)) {
    std::fprintf(stderr, "rill-mandelbrot: wrong result (centre %d, corner %d iterations)\n",
                 n[centre], n[0]);
    return 1;
  }

  std::vector<uint8_t> rgb(pixels.size() * 3);
  for (size_t p = 0; p < pixels.size(); ++p)
    for (int c = 0; c < 3; ++c) {
      float v = std::fmin(std::fmax(pixels[p][c], 0.0f), 1.0f);
      rgb[p * 3 + static_cast<size_t>(c)] = static_cast<uint8_t>(std::lround(v * 255.0f));
    }
  write_png(o.out, o.width, o.height, rgb);

  std::printf("rill-mandelbrot: %dx%d, %d iterations, backend %s, accuracy %s\n", o.width, o.height,
              o.iterations, kernel.backend_name().c_str(), accuracy_name(o.accuracy));
  std::printf("  compile %.1f ms (%s), run %.1f ms\n", kernel.info().compile_ms,
              kernel.info().from_disk_cache ? "from the disk cache" : "compiled now", ms);
  std::printf("  wrote %s\n", std::filesystem::absolute(o.out).string().c_str());
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "rill-mandelbrot: %s\n", e.what());
  return 1;
}
