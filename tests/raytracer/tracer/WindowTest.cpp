// Rendering a window of the image (RenderSettings::window), per backend: every window's pixels
// are bitwise those of the whole render, whatever the tiling, for both strategies, several
// samples per pixel and the 8-bit encoding. The distributed renderer (apps/rill-trace/
// distributed/) relies on it to assemble an image identical to a single-process render.
#include <gtest/gtest.h>

#include <cstring>
#include <stdexcept>

#include "RenderCompare.h"
#include "TestUtil.h"
#include "rill/rt/Tracer.h"
#include "rill/rt/accel/Grid.h"
#include "rill/rt/scene/Camera.h"

namespace rt {
namespace {

class Window : public ::testing::TestWithParam<std::string> {};

// Renders the image in tiles of tw x th (the last row and column smaller) and checks each
// against the whole render; the tiles' ray counts add up to the whole render's.
void expect_tiles_match(Tracer& t, const Scene& s, RenderSettings rs, int tw, int th,
                        const std::string& what) {
  rs.outputs = {true, true, true, true, true};
  const RenderResult whole = t.render(rs, s.camera);
  ASSERT_EQ(whole.rgb8.size(), whole.color.size() * 3);
  int64_t rays = 0;
  for (int y = 0; y < rs.height; y += th)
    for (int x = 0; x < rs.width; x += tw) {
      rs.window = {x, y, std::min(tw, rs.width - x), std::min(th, rs.height - y)};
      const std::string tile =
          what + ", tile at (" + std::to_string(x) + ", " + std::to_string(y) + ")";
      const RenderResult part = t.render(rs, s.camera);
      ASSERT_EQ(part.width, rs.window.width) << tile;
      ASSERT_EQ(part.height, rs.window.height) << tile;
      RenderResult want = testing::crop(whole, rs.window);
      want.rays = part.rays;  // compared as a sum below
      testing::expect_identical(want, part, tile);
      EXPECT_EQ(want.rgb8, part.rgb8) << tile;
      rays += part.rays;
    }
  EXPECT_EQ(rays, whole.rays) << what;
}

TEST_P(Window, TilesEqualTheWholeRender) {
  RT_REQUIRE_BACKEND(GetParam());
  RenderSettings rs;
  rs.outputs.depth = rs.outputs.prim = rs.outputs.normal = true;  // the AOVs compared
  rs.backend = GetParam();
  rs.width = 23;
  rs.height = 17;
  {
    Scene s = builtin_scene("glass");
    Grid g = build_grid(s, 9);
    Tracer t(s, g);
    rs.max_depth = 3;
    expect_tiles_match(t, s, rs, 7, 7, "glass, tiles 7x7");
    expect_tiles_match(t, s, rs, 8, 8, "glass, tiles 8x8 (the last row one pixel high)");
    rs.spp = 3;
    expect_tiles_match(t, s, rs, 10, 6, "glass, spp 3, tiles 10x6");
  }
  {
    // The boxes cover part of the image: the megakernel skips the other pixels' camera rays,
    // by the rectangle of the whole image, in every tile.
    Scene s = builtin_scene("thesis-a");
    Grid g = build_grid(s, 0);
    Tracer t(s, g);
    RenderSettings rs;  // larger: the rectangle is conservative by a few pixels
    rs.backend = GetParam();
    rs.width = 48;
    rs.height = 36;
    rs.spp = 2;
    rs.max_depth = 1;
    const PixelRect seen =
        pixels_seeing_box(camera_frame(s.camera, rs.width, rs.height), g.lo, g.hi);
    EXPECT_LT((seen.end.x - seen.first.x) * (seen.end.y - seen.first.y),
              rs.width * rs.height * 3 / 4);  // a quarter of the pixels or more skipped
    expect_tiles_match(t, s, rs, 13, 10, "thesis-a, spp 2, tiles 13x10");
  }
  {
    Scene s = builtin_scene("cornell");
    Grid g = build_grid(s, 0);
    Tracer t(s, g);
    rs.spp = 2;
    rs.max_depth = 2;
    rs.strategy = Strategy::Multipass;
    expect_tiles_match(t, s, rs, 8, 5, "cornell, multipass, spp 2, tiles 8x5");
  }
}

TEST(WindowBad, OutsideTheImageIsAnError) {
  Scene s = builtin_scene("thesis-a");
  Grid g = build_grid(s, 0);
  Tracer t(s, g);
  RenderSettings rs;
  rs.outputs.depth = rs.outputs.prim = rs.outputs.normal = true;  // the AOVs compared
  rs.width = 8;
  rs.height = 6;
  for (RenderSettings::Window w :
       {RenderSettings::Window{4, 0, 5, 6}, RenderSettings::Window{0, 3, 8, 4},
        RenderSettings::Window{-1, 0, 2, 2}}) {
    rs.window = w;
    EXPECT_THROW(t.render(rs, s.camera), std::runtime_error);
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, Window, ::testing::ValuesIn(testing::backend_names()),
                         [](const auto& info) { return rill::testing::param_name(info.param); });

}  // namespace
}  // namespace rt
