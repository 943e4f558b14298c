// A JSON scene file's lights (load/LightJson.h, docs/scene-format.md "lights"): the point,
// spot and directional types with their keys and defaults, and bad input, each an error that
// names the file and the key.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "RunCommand.h"
#include "TestUtil.h"
#include "rill/rt/kernel/LightShape.h"
#include "rill/rt/load/SceneFile.h"

namespace rt {
// Named: the unity build puts other test files' anonymous helpers in the same unit.
namespace light_json_test {
namespace {

using testing::error_of;

Scene with_lights(const std::string& lights) {
  return parse_json_scene(R"({"lights": [)" + lights + "]}", ".", "lights.json");
}

std::string error_with(const std::string& lights) {
  return error_of([&] { with_lights(lights); });
}

TEST(LightJson, APointLightIsTodaysWithNoFalloffByDefault) {
  const Scene s = with_lights(R"({"position": [1, 2, 3], "color": 0.5})");
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(s.lights[0].type, LightType::Point);
  EXPECT_EQ(s.lights[0].falloff, Falloff::None);
  EXPECT_EQ(s.lights[0].position, glm::vec3(1, 2, 3));
  EXPECT_EQ(s.lights[0].color, glm::vec3(0.5f));
  EXPECT_FALSE(light_shaped(s.lights[0], Integrator::Whitted));
  const Scene f =
      with_lights(R"({"type": "point", "position": [0, 1, 0], "falloff": "inverse_square"})");
  EXPECT_EQ(f.lights[0].falloff, Falloff::InverseSquare);
  // Whitted needs the falloff's code; the path integrator's point lights always fall off.
  EXPECT_TRUE(light_shaped(f.lights[0], Integrator::Whitted));
  EXPECT_FALSE(light_shaped(f.lights[0], Integrator::Path));
}

TEST(LightJson, ASpotTakesADirectionOrALookAtPointAndConeAngles) {
  const Scene s = with_lights(
      R"({"type": "spot", "position": [0, 4, 0], "direction": [0, -2, 0], "inner_angle": 10,
          "outer_angle": 20, "color": [1, 2, 3]},
         {"type": "spot", "position": [1, 4, 0], "look_at": [1, 0, 0]})");
  ASSERT_EQ(s.lights.size(), 2u);
  EXPECT_EQ(s.lights[0].type, LightType::Spot);
  EXPECT_EQ(s.lights[0].direction, glm::vec3(0, -2, 0));
  EXPECT_EQ(s.lights[0].inner_deg, 10.0f);
  EXPECT_EQ(s.lights[0].outer_deg, 20.0f);
  // look_at gives the direction; the cone defaults to 30 degrees with pbrt's 5 degree edge.
  EXPECT_EQ(s.lights[1].direction, glm::vec3(0, -4, 0));
  EXPECT_EQ(s.lights[1].outer_deg, 30.0f);
  EXPECT_EQ(s.lights[1].inner_deg, 25.0f);
  // An outer angle alone: the soft edge stays within it.
  const Scene narrow = with_lights(
      R"({"type": "spot", "position": [0, 1, 0], "direction": [0, -1, 0], "outer_angle": 3})");
  EXPECT_EQ(narrow.lights[0].inner_deg, 0.0f);
}

TEST(LightJson, ADirectionalLightHasADirectionAndNoPosition) {
  const Scene s = with_lights(R"({"type": "directional", "direction": [1, -1, 0], "color": 2})");
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(s.lights[0].type, LightType::Directional);
  EXPECT_EQ(s.lights[0].direction, glm::vec3(1, -1, 0));
  EXPECT_EQ(s.lights[0].color, glm::vec3(2.0f));
}

// Each message names the file and the key (and the values allowed, where there is a list).
TEST(LightJson, BadLightsAreErrorsNamingTheKey) {
  struct Case {
    const char* lights;
    const char* want;
  };
  const Case cases[] = {
      {R"({"type": "area", "position": [0, 1, 0]})",
       "lights.json: lights[0].type 'area' is not a light type (point, spot, directional)"},
      {R"({"type": 3, "position": [0, 1, 0]})", "lights[0].type must be a string"},
      {R"({"type": "spot", "position": [0, 1, 0], "direction": [0, 0, 0]})",
       "lights[0].direction must not be zero"},
      {R"({"type": "directional", "direction": [0, 0, 0]})",
       "lights[0].direction must not be zero"},
      {R"({"type": "spot", "position": [0, 1, 0], "look_at": [0, 1, 0]})",
       "lights[0].look_at must not be the light's position"},
      {R"({"type": "spot", "position": [0, 1, 0]})",
       "lights[0] needs a direction or a look_at point"},
      {R"({"type": "directional"})", "lights[0] needs a direction"},
      {R"({"type": "spot", "position": [0, 1, 0], "direction": [0, -1, 0], "look_at": [0, 0, 0]})",
       "lights[0] has both direction and look_at"},
      {R"({"type": "spot", "position": [0, 1, 0], "direction": [0, -1, 0], "outer_angle": 120})",
       "lights[0].outer_angle must be in [0, 90] degrees"},
      {R"({"type": "spot", "position": [0, 1, 0], "direction": [0, -1, 0], "outer_angle": 0})",
       "lights[0].outer_angle must be more than 0 degrees"},
      {R"({"type": "spot", "position": [0, 1, 0], "direction": [0, -1, 0], "inner_angle": -1})",
       "lights[0].inner_angle must be in [0, 90] degrees"},
      {R"({"type": "spot", "position": [0, 1, 0], "direction": [0, -1, 0], "inner_angle": 40,
           "outer_angle": 30})",
       "lights[0].inner_angle 40.0 must be <= outer_angle 30.0"},
      {R"({"type": "spot", "position": [0, 1, 0], "direction": [0, -1, 0], "outer_angle": "wide"})",
       "lights[0].outer_angle must be a number"},
      {R"({"position": [0, 1, 0], "falloff": "linear"})",
       "lights[0].falloff must be \"none\" or \"inverse_square\""},
      // A key of another type: a directional light's position would be ignored.
      {R"({"type": "directional", "direction": [0, -1, 0], "position": [0, 1, 0]})",
       "lights[0]: unknown key 'position' (type, direction, color)"},
      {R"({"type": "directional", "direction": [0, -1, 0], "falloff": "inverse_square"})",
       "lights[0]: unknown key 'falloff'"},
      {R"({"position": [0, 1, 0], "outer_angle": 10})", "lights[0]: unknown key 'outer_angle'"},
      {R"({"type": "spot", "direction": [0, -1, 0]})", "lights[0] needs a position"},
  };
  for (const Case& c : cases) {
    const std::string why = error_with(c.lights);
    EXPECT_NE(why.find(c.want), std::string::npos) << c.lights << "\n -> " << why;
    EXPECT_EQ(why.rfind("lights.json: ", 0), 0u) << why;
  }
}

// The scene's own check (Scene::validate) for scenes built in code: the same limits.
TEST(LightJson, ValidateRefusesBadShapesBuiltInCode) {
  Scene s;
  Light spot;
  spot.type = LightType::Spot;
  spot.direction = glm::vec3(0.0f);
  s.lights = {spot};
  EXPECT_NE(error_of([&] { s.validate(); }).find("direction [0, 0, 0] must be finite and not zero"),
            std::string::npos);
  s.lights[0].direction = glm::vec3(0, -1, 0);
  s.lights[0].inner_deg = 40.0f;
  s.lights[0].outer_deg = 30.0f;
  EXPECT_NE(error_of([&] { s.validate(); }).find("cone angles"), std::string::npos);
  s.lights[0].inner_deg = 10.0f;
  EXPECT_NO_THROW(s.validate());
  Light sun;
  sun.type = LightType::Directional;
  sun.falloff = Falloff::InverseSquare;
  s.lights = {sun};
  EXPECT_NE(error_of([&] { s.validate(); }).find("no distance falloff"), std::string::npos);
}

// The cone factor's formula (LightShape.h), which the render tests compare the kernels with:
// 1 inside the inner angle, 0 outside the outer one, pbrt's smoothstep between (1/2 halfway
// in cosine), continuous at both ends.
TEST(LightJson, TheSpotConeIsPbrtsSmoothstep) {
  Light l;
  l.type = LightType::Spot;
  l.inner_deg = 20.0f;
  l.outer_deg = 30.0f;
  const double ci = std::cos(20.0 * M_PI / 180.0), co = std::cos(30.0 * M_PI / 180.0);
  EXPECT_EQ(spot_cone_factor(l, 1.0), 1.0);
  EXPECT_EQ(spot_cone_factor(l, std::cos(25.0 * M_PI / 180.0)) > 0.0, true);
  EXPECT_EQ(spot_cone_factor(l, std::cos(31.0 * M_PI / 180.0)), 0.0);
  EXPECT_NEAR(spot_cone_factor(l, 0.5 * (ci + co)), 0.5, 1e-6);
  EXPECT_NEAR(spot_cone_factor(l, ci - 1e-9), 1.0, 1e-6);
  EXPECT_NEAR(spot_cone_factor(l, co + 1e-9), 0.0, 1e-6);
  l.inner_deg = l.outer_deg;  // a hard edge
  EXPECT_EQ(spot_cone_factor(l, co + 1e-6), 1.0);
  EXPECT_EQ(spot_cone_factor(l, co - 1e-6), 0.0);
}

#ifdef RILL_TRACE_EXE
// rill-trace takes the lights from a scene file (it has no light option of its own): a scene
// with a spot and a directional light renders; a bad one is exit status 1 (a bad scene, as
// docs/cli.md says) with the file and the key on stderr.
TEST(LightJson, RillTraceRendersTheNewLightsAndNamesABadKey) {
  testing::TempDir dir;
  const std::string good = dir.file("good.json", R"({"builtin": "thesis-a", "lights": [
      {"type": "spot", "position": [0, 6, 3], "look_at": [0, 0, 0], "outer_angle": 25},
      {"type": "directional", "direction": [1, -1, -1], "color": 0.3},
      {"position": [2, 4, 3], "falloff": "inverse_square", "color": 20}]})");
  const testing::Run ok = testing::run_command(
      "'" RILL_TRACE_EXE "' render '" + good + "' --size 16x12 --quiet --out good.png", dir);
  EXPECT_EQ(ok.status, 0) << ok.err;
  EXPECT_TRUE(std::filesystem::exists(dir.path("good.png")));
  const std::string bad = dir.file("bad.json", R"({"builtin": "thesis-a", "lights": [
      {"type": "spot", "position": [0, 6, 3], "direction": [0, -1, 0], "inner_angle": 40,
       "outer_angle": 30}]})");
  const testing::Run r = testing::run_command(
      "'" RILL_TRACE_EXE "' render '" + bad + "' --size 16x12 --quiet --out bad.png", dir);
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("bad.json: lights[0].inner_angle 40.0 must be <= outer_angle 30.0"),
            std::string::npos)
      << r.err;
}
#endif

}  // namespace
}  // namespace light_json_test
}  // namespace rt
