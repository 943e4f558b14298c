// rill-trace render's camera options (--eye, --look-at, --up, --fov, --camera, --up-axis) and
// the framing camera of a scene without one, measured in the --prim AOV (docs/camera.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "RunCommand.h"
#include "TestUtil.h"
#include "rill/rt/scene/Image.h"

namespace rt {
namespace {

#ifdef RILL_TRACE_EXE

using testing::run_command;

testing::Run camera_trace(const std::string& args, const testing::TempDir& dir) {
  return run_command("'" RILL_TRACE_EXE "' render " + args + " --quiet", dir);
}

std::vector<float> camera_prim(const testing::TempDir& dir, const std::string& name, int& w,
                               int& h) {
  int ch = 0;
  std::vector<float> p = read_pfm(dir.path(name), w, h, ch);
  EXPECT_EQ(ch, 1);
  return p;
}

// A box [-e, e] as six quads, one per face in the order -x, +x, -y, +y, -z, +z (primitives
// 2f and 2f + 1), wound counterclockwise seen from outside, or from inside when inward.
std::string camera_box_obj(float ex, float ey, float ez, bool inward) {
  std::string s;
  const float e[3] = {ex, ey, ez};
  int n = 0;
  for (int k = 0; k < 3; ++k)
    for (int sign : {-1, 1}) {
      const int u = (k + 1) % 3, v = (k + 2) % 3;
      const float ab[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
      for (const auto& c : ab) {
        float p[3];
        p[k] = sign * e[k], p[u] = c[0] * e[u], p[v] = c[1] * e[v];
        s += "v " + std::to_string(p[0]) + " " + std::to_string(p[1]) + " " + std::to_string(p[2]) +
             "\n";
      }
      // e_u x e_v = e_k: this order faces +k.
      const bool out_is_ccw = (sign > 0) != inward;
      s += out_is_ccw ? "f " + std::to_string(n + 1) + " " + std::to_string(n + 2) + " " +
                            std::to_string(n + 3) + " " + std::to_string(n + 4) + "\n"
                      : "f " + std::to_string(n + 4) + " " + std::to_string(n + 3) + " " +
                            std::to_string(n + 2) + " " + std::to_string(n + 1) + "\n";
      n += 4;
    }
  return s;
}

// The columns and rows that see the object (prim >= 0): {width, height} in pixels.
std::pair<int, int> object_extent(const std::vector<float>& p, int w, int h) {
  int x0 = w, x1 = -1, y0 = h, y1 = -1;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (p[static_cast<size_t>(y) * w + x] >= 0)
        x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
  return {x1 - x0 + 1, y1 - y0 + 1};
}

// The command line's camera is the scene file's: the same bits as a JSON scene that sets
// that camera, and --camera FILE.json with the same keys too; --eye wins over the file's.
TEST(CameraCli, OptionsOverrideTheCameraBitwise) {
  testing::TempDir dir;
  dir.file("aimed.json",
           R"({"builtin": "cornell", "camera": {"eye": [0.3, 0.2, 2.5], "look_at": [0, -0.1, 0],
               "up": [0.1, 1, 0], "fov_y": 50}})");
  dir.file("cam.json", R"({"eye": [9, 9, 9], "look_at": [0, -0.1, 0], "up": [0.1, 1, 0],
                           "fov_y": 50})");
  const std::string common = " --size 40x30 --pfm ";
  ASSERT_EQ(camera_trace("aimed.json" + common + "a.pfm --prim ap.pfm", dir).status, 0);
  testing::Run r =
      camera_trace("builtin:cornell --eye 0.3,0.2,2.5 --look-at 0,-0.1,0 --up 0.1,1,0 --fov 50" +
                       common + "b.pfm --prim bp.pfm",
                   dir);
  ASSERT_EQ(r.status, 0) << r.err;
  r = camera_trace("builtin:cornell --eye 0.3,0.2,2.5 --camera cam.json" + common + "c.pfm", dir);
  ASSERT_EQ(r.status, 0) << r.err;
  ASSERT_EQ(camera_trace("builtin:cornell" + common + "d.pfm", dir).status, 0);
  const std::string a = testing::read_text(dir.path("a.pfm"));
  EXPECT_EQ(a, testing::read_text(dir.path("b.pfm")));
  EXPECT_EQ(testing::read_text(dir.path("ap.pfm")), testing::read_text(dir.path("bp.pfm")));
  EXPECT_EQ(a, testing::read_text(dir.path("c.pfm")));
  EXPECT_NE(a, testing::read_text(dir.path("d.pfm")));  // the options did move the camera
}

// The orthographic and thin-lens options are the scene file's keys: the same bits.
TEST(CameraCli, ProjectionAndLensOptionsAreTheSceneFilesKeys) {
  testing::TempDir dir;
  dir.file("ortho.json", R"({"builtin": "cornell", "camera": {"eye": [0.3, 0.2, 2.5],
               "look_at": [0, -0.1, 0], "type": "orthographic", "height": 1.7}})");
  dir.file("lens.json", R"({"builtin": "cornell", "camera": {"eye": [0.3, 0.2, 2.5],
               "look_at": [0, -0.1, 0], "aperture": 0.05, "focus_distance": 2.2}})");
  dir.file("cam.json", R"({"type": "orthographic", "height": 1.7})");
  const std::string common = " --size 40x30 --spp 2 --pfm ";
  const std::string aim = "builtin:cornell --eye 0.3,0.2,2.5 --look-at 0,-0.1,0";
  ASSERT_EQ(camera_trace("ortho.json" + common + "a.pfm", dir).status, 0);
  testing::Run r = camera_trace(aim + " --ortho-height 1.7" + common + "b.pfm", dir);
  ASSERT_EQ(r.status, 0) << r.err;
  r = camera_trace(aim + " --camera cam.json" + common + "c.pfm", dir);
  ASSERT_EQ(r.status, 0) << r.err;
  ASSERT_EQ(camera_trace("lens.json" + common + "d.pfm", dir).status, 0);
  r = camera_trace(aim + " --aperture 0.05 --focus-distance 2.2" + common + "e.pfm", dir);
  ASSERT_EQ(r.status, 0) << r.err;
  ASSERT_EQ(camera_trace(aim + common + "f.pfm", dir).status, 0);
  const std::string a = testing::read_text(dir.path("a.pfm"));
  EXPECT_EQ(a, testing::read_text(dir.path("b.pfm")));
  EXPECT_EQ(a, testing::read_text(dir.path("c.pfm")));
  const std::string d = testing::read_text(dir.path("d.pfm"));
  EXPECT_EQ(d, testing::read_text(dir.path("e.pfm")));
  const std::string f = testing::read_text(dir.path("f.pfm"));
  EXPECT_NE(a, f);  // the options did change the camera
  EXPECT_NE(d, f);
}

TEST(CameraCli, BadValuesNameTheOption) {
  testing::TempDir dir;
  dir.file("odd.json", R"({"eye": [0, 0, 5], "zoom": 2})");
  dir.file("list.json", R"([0, 0, 5])");
  dir.file("fisheye.json", R"({"type": "fisheye"})");
  dir.file("ortho.json", R"({"type": "orthographic"})");
  dir.file("negative.json", R"({"aperture": -1})");
  const std::pair<std::string, std::string> cases[] = {
      {"--eye 1,2", "--eye expects X,Y,Z"},
      {"--eye 1,2,nan", "--eye expects X,Y,Z"},
      {"--look-at 1,2,3,4", "--look-at expects X,Y,Z"},
      {"--up x,y,z", "--up expects X,Y,Z"},
      {"--fov 180", "--fov is the vertical field of view in degrees, in (0, 180)"},
      {"--fov 0", "--fov is the vertical field of view"},
      {"--fov wide", "--fov expects a number of degrees"},
      {"--camera none.json", "--camera"},
      {"--camera odd.json",
       "unknown key 'zoom' (valid: eye, look_at, up, fov_y, type, height, aperture, "
       "focus_distance)"},
      {"--camera fisheye.json", "type expects \"perspective\" or \"orthographic\""},
      {"--camera ortho.json", "an orthographic camera (--camera's type) needs its view's height"},
      {"--camera negative.json", "--camera negative.json: aperture is the lens's radius"},
      {"--aperture -0.5",
       "--aperture is the lens's radius in scene units (0: a pinhole), a "
       "finite number >= 0"},
      {"--aperture wide", "--aperture expects a radius in scene units"},
      {"--aperture 1e39", "--aperture is the lens's radius"},
      {"--focus-distance 0",
       "--focus-distance is the distance from the eye to the plane in "
       "focus, a finite number > 0"},
      {"--focus-distance nan", "--focus-distance expects a distance"},
      {"--ortho-height 0", "--ortho-height is the orthographic view's height in scene units"},
      {"--ortho-height -1", "--ortho-height is the orthographic view's height"},
      {"--ortho-height 2 --aperture 0.1",
       "aperture is for a perspective camera, not an orthographic one"},
      {"--camera list.json", "expects a JSON object"},
      {"--up-axis w", "--up-axis expects auto, x, y or z"},
      // Degenerate views: check_camera's messages.
      {"--eye 0,0,0 --look-at 0,0,0", "eye and look_at are the same point"},
      {"--eye 0,0,5 --look-at 0,0,0 --up 0,0,2", "is parallel to the view direction"},
  };
  for (const auto& [args, needle] : cases) {
    SCOPED_TRACE(args);
    const testing::Run r = camera_trace("builtin:cornell --size 8x8 " + args, dir);
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "not one line: " << r.err;
  }
}

// A wide mesh in a wide image: the framing camera fits the image's aspect, so the box spans
// 95% of the width (the fit's margin), to within a pixel each side.
TEST(CameraCli, FramingFitsTheImageWidth) {
  testing::TempDir dir;
  dir.file("wide.obj", camera_box_obj(2.0f, 0.5f, 0.5f, false));
  const testing::Run r = camera_trace("wide.obj --size 160x80 --prim p.pfm", dir);
  ASSERT_EQ(r.status, 0) << r.err;
  int w = 0, h = 0;
  const std::vector<float> p = camera_prim(dir, "p.pfm", w, h);
  const auto [ew, eh] = object_extent(p, w, h);
  EXPECT_GE(ew, 0.95 * w - 2) << ew;
  EXPECT_LE(ew, 0.95 * w + 2) << ew;
  EXPECT_LT(eh, h);
}

// A z-up mesh standing tall in z renders upright with --up-axis z (and with auto, which picks
// z for it), lying down (seen from its end) with --up-axis y.
TEST(CameraCli, UpAxisZRendersUpright) {
  testing::TempDir dir;
  dir.file("tower.obj", camera_box_obj(0.5f, 0.5f, 2.0f, false));
  ASSERT_EQ(camera_trace("tower.obj --size 64x64 --up-axis z --prim z.pfm", dir).status, 0);
  ASSERT_EQ(camera_trace("tower.obj --size 64x64 --prim auto.pfm", dir).status, 0);
  ASSERT_EQ(camera_trace("tower.obj --size 64x64 --up-axis y --prim y.pfm", dir).status, 0);
  int w = 0, h = 0;
  const std::vector<float> z = camera_prim(dir, "z.pfm", w, h);
  const auto [zw, zh] = object_extent(z, w, h);
  EXPECT_GT(zh, 3 * zw) << zw << "x" << zh;
  const std::vector<float> y = camera_prim(dir, "y.pfm", w, h);
  const auto [yw, yh] = object_extent(y, w, h);
  EXPECT_LT(yh, 3 * yw) << yw << "x" << yh;
  EXPECT_EQ(testing::read_text(dir.path("z.pfm")), testing::read_text(dir.path("auto.pfm")));
}

// A closed box whose faces point inwards is a room: framed from inside, just within its +z
// wall, the centre pixel sees the -z (back) wall, primitives 8 and 9. The same box wound
// outwards is an object, seen from outside: its +z wall, primitives 10 and 11.
TEST(CameraCli, ARoomIsFramedFromInside) {
  testing::TempDir dir;
  dir.file("room.obj", camera_box_obj(1.0f, 1.0f, 1.0f, true));
  dir.file("box.obj", camera_box_obj(1.0f, 1.0f, 1.0f, false));
  ASSERT_EQ(camera_trace("room.obj --size 33x33 --prim room.pfm", dir).status, 0);
  ASSERT_EQ(camera_trace("box.obj --size 33x33 --prim box.pfm", dir).status, 0);
  int w = 0, h = 0;
  const std::vector<float> room = camera_prim(dir, "room.pfm", w, h);
  const float centre = room[static_cast<size_t>(16) * w + 16];
  EXPECT_TRUE(centre == 8 || centre == 9) << centre;
  // From inside every pixel sees a wall.
  EXPECT_EQ(std::count_if(room.begin(), room.end(), [](float v) { return v < 0; }), 0);
  const std::vector<float> box = camera_prim(dir, "box.pfm", w, h);
  const float outside = box[static_cast<size_t>(16) * w + 16];
  EXPECT_TRUE(outside == 10 || outside == 11) << outside;
}

#endif

}  // namespace
}  // namespace rt
