// Animation (scene/Animation.h, AnimationJson.h, Pose.h): keyframe interpolation at the keys,
// between them and outside the time range; the time range's frames; the JSON reader's
// errors, each naming the file and the key; posing and baking.
#include <gtest/gtest.h>

#include <cmath>

#include "TestUtil.h"
#include "rill/rt/accel/Grid.h"
#include "rill/rt/load/SceneFile.h"
#include "rill/rt/scene/Pose.h"

namespace rt {
namespace {
using testing::error_of;
using testing::wave_obj;

PoseTrack two_keys(Interpolation how) {
  PoseTrack t;
  t.interpolation = how;
  PoseKey a, b;
  a.time = 1.0;
  a.pose.translate = glm::dvec3(0.0, 0.0, 0.0);
  b.time = 3.0;
  b.pose.translate = glm::dvec3(4.0, -2.0, 8.0);
  b.pose.scale = glm::dvec3(3.0);
  b.pose.rotation = glm::angleAxis(glm::radians(90.0), glm::dvec3(0, 1, 0));
  t.keys = {a, b};
  return t;
}

TEST(Animation, TracksHoldTheirKeysAndInterpolateBetween) {
  const PoseTrack lin = two_keys(Interpolation::Linear);
  // At the keys: exactly the keys.
  EXPECT_EQ(lin.at(1.0).translate, glm::dvec3(0.0));
  EXPECT_EQ(lin.at(3.0).translate, glm::dvec3(4.0, -2.0, 8.0));
  EXPECT_EQ(lin.at(3.0).scale, glm::dvec3(3.0));
  // Outside the range: the nearest key holds.
  EXPECT_EQ(lin.at(-5.0).translate, glm::dvec3(0.0));
  EXPECT_EQ(lin.at(100.0).translate, glm::dvec3(4.0, -2.0, 8.0));
  // Between: a quarter of the way, linearly; rotation a quarter of 90 degrees about y.
  const Pose q = lin.at(1.5);
  EXPECT_NEAR(q.translate.x, 1.0, 1e-12);
  EXPECT_NEAR(q.translate.z, 2.0, 1e-12);
  EXPECT_NEAR(q.scale.x, 1.5, 1e-12);
  EXPECT_NEAR(glm::degrees(glm::angle(q.rotation)), 22.5, 1e-9);
  const glm::vec3 p = q.apply_point(glm::vec3(1.0f, 0.0f, 0.0f));
  // scale 1.5, then 22.5 degrees about y (x goes towards -z), then the translation.
  EXPECT_NEAR(p.x, 1.0 + 1.5 * std::cos(glm::radians(22.5)), 1e-6);
  EXPECT_NEAR(p.z, 2.0 - 1.5 * std::sin(glm::radians(22.5)), 1e-6);
  // Smooth: the same at the keys and halfway, eased elsewhere (3u^2 - 2u^3 at u = 1/4).
  const PoseTrack smooth = two_keys(Interpolation::Smooth);
  EXPECT_EQ(smooth.at(1.0).translate, glm::dvec3(0.0));
  EXPECT_EQ(smooth.at(3.0).translate, glm::dvec3(4.0, -2.0, 8.0));
  EXPECT_NEAR(smooth.at(2.0).translate.x, 2.0, 1e-12);
  EXPECT_NEAR(smooth.at(1.5).translate.x, 4.0 * (3 * 0.0625 - 2 * 0.015625), 1e-12);
}

TEST(Animation, RotationsTakeTheShorterArc) {
  PoseTrack t;
  PoseKey a, b;
  a.time = 0.0;
  a.pose.rotation = glm::angleAxis(glm::radians(170.0), glm::dvec3(0, 0, 1));
  b.time = 1.0;
  b.pose.rotation = glm::angleAxis(glm::radians(-170.0), glm::dvec3(0, 0, 1));
  t.keys = {a, b};
  // 170 to -170 degrees is 20 degrees through 180, not 340 through 0.
  const glm::vec3 mid = t.at(0.5).apply_point(glm::vec3(1.0f, 0.0f, 0.0f));
  EXPECT_NEAR(mid.x, -1.0, 1e-6);
  EXPECT_NEAR(mid.y, 0.0, 1e-6);
}

TEST(Animation, TimeRangeFrames) {
  TimeRange r{0.0, 2.0, 24.0};
  EXPECT_EQ(r.frame_count(), 49);
  EXPECT_DOUBLE_EQ(r.time_of(0), 0.0);
  EXPECT_DOUBLE_EQ(r.time_of(48), 2.0);
  TimeRange s{0.1, 1.1, 30.0};  // (1.1 - 0.1) * 30 rounds below 30
  EXPECT_EQ(s.frame_count(), 31);
  EXPECT_EQ((TimeRange{1.0, 1.0, 24.0}).frame_count(), 1);
}

const char* kAnimatedScene = R"({
  "animation": {"start": 0, "end": 2, "fps": 10},
  "meshes": [
    {"shape": "box", "min": [-4, -1, -4], "max": [4, -0.5, 4]},
    {"name": "cube", "shape": "box", "min": [-0.5, 0, -0.5], "max": [0.5, 1, 0.5],
     "animate": {"interpolation": "smooth", "keys": [
       {"time": 0, "translate": [-2, 0, 0]},
       {"time": 2, "translate": [2, 0, 0], "rotate": {"axis": [0, 1, 0], "degrees": 90}}]}}
  ],
  "instances": [
    {"mesh": "cube", "name": "second", "transform": {"translate": [0, 2, 0]},
     "animate": {"keys": [{"time": 0, "scale": 1}, {"time": 1, "scale": 0.5}]}},
    {"mesh": "cube", "transform": {"translate": [0, 0, -3]}}
  ],
  "lights": [{"position": [0, 5, 5]}],
  "camera": {"eye": [0, 2, 8], "look_at": [0, 0, 0], "keys": [{"time": 0}, {"time": 2, "eye": [4, 2, 8]}]}
})";

TEST(Animation, JsonSceneReadsObjectsInstancesAndCameraKeys) {
  const Scene s = parse_json_scene(kAnimatedScene, ".", "anim.json");
  ASSERT_EQ(s.animation.objects.size(), 2u);
  EXPECT_EQ(s.triangle_count(), 48u);  // floor, cube, two instances: 12 each
  EXPECT_EQ(s.animation.objects[0].name, "cube");
  EXPECT_EQ(s.animation.objects[0].first, 12u);
  EXPECT_EQ(s.animation.objects[1].name, "second");
  EXPECT_EQ(s.animation.objects[1].first, 24u);
  EXPECT_EQ(s.animation.time.frame_count(), 21);
  // The camera moves; the static instance (the last 12) does not.
  EXPECT_EQ(camera_at(s, 1.0).eye, glm::vec3(2.0f, 2.0f, 8.0f));
  const Scene mid = bake(s, 1.0);
  EXPECT_FALSE(mid.animation.animated());
  EXPECT_EQ(mid.camera.eye, glm::vec3(2.0f, 2.0f, 8.0f));
  for (size_t i = 0; i < 3 * 12; ++i) EXPECT_EQ(mid.positions[i], s.positions[i]);
  for (size_t i = 36 * 3; i < 48 * 3; ++i) EXPECT_EQ(mid.positions[i], s.positions[i]);
  // The cube halfway: x moved from -2 to 0 (smooth is linear at u = 1/2).
  glm::vec3 lo(1e9f), hi(-1e9f);
  for (size_t i = 12 * 3; i < 24 * 3; ++i) {
    lo = glm::min(lo, mid.positions[i]);
    hi = glm::max(hi, mid.positions[i]);
  }
  EXPECT_NEAR((lo.x + hi.x) * 0.5f, 0.0f, 1e-5f);
  // The grid holds only what does not move.
  const Grid g = build_grid(s);
  EXPECT_EQ(g.moving, 24u);
  EXPECT_EQ(g.usable, 24u);
  EXPECT_EQ(build_grid(mid).usable, 48u);
}

TEST(Animation, PosingIsDeterministicAndLeavesTheRestAlone) {
  const Scene s = parse_json_scene(kAnimatedScene, ".", "anim.json");
  Scene a = s, b = s;
  pose_objects(s, 0.73, a);
  pose_objects(s, 1.9, b);
  pose_objects(s, 0.73, b);  // posing again from the rest pose: no drift
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.normals, b.normals);
  EXPECT_EQ(a.material, s.material);
}

TEST(Animation, JsonErrorsNameTheFileAndTheKey) {
  auto err = [](const std::string& text) {
    return error_of([&] { parse_json_scene(text, ".", "anim.json"); });
  };
  const std::string box = R"("shape": "box", )";
  EXPECT_EQ(
      err(R"({"meshes": [{)" + box + R"("animate": {"keys": [{"time": 1}, {"time": 0.5}]}}]})"),
      "anim.json: meshes[0].animate.keys[1]: time 0.5 is not after keys[0]'s 1 (keys must "
      "be in time order)");
  EXPECT_EQ(err(R"({"meshes": [{)" + box + R"("animate": {"keys": [{"time": 1}, {"time": 1}]}}]})"),
            "anim.json: meshes[0].animate.keys[1]: time 1 is not after keys[0]'s 1 (keys must be "
            "in time order)");
  EXPECT_EQ(err(R"({"meshes": [{)" + box + R"("name": "a"}], "instances": [{"mesh": "b"}]})"),
            "anim.json: instances[0].mesh: unknown object 'b' (named meshes: a)");
  // Many named meshes: a few and a count (NameList.h).
  std::string many;
  for (const char* n : {"a", "b", "c", "d", "e", "f", "g"})
    many += std::string("{") + box + R"("name": ")" + n + R"("}, )";
  EXPECT_EQ(err(R"({"meshes": [)" + many + R"({)" + box +
                R"("name": "h"}], "instances": [{"mesh": "x"}]})"),
            "anim.json: instances[0].mesh: unknown object 'x' (named meshes: a, b, c, d, e and 3 "
            "more)");
  EXPECT_EQ(err(R"({"meshes": [{)" + box +
                R"("animate": {"keys": [{"time": 0}]}}], "animation": {"start": 1, "end": 1}})"),
            "anim.json: animation: the time range is empty (end 1 is not after start 1)");
  EXPECT_EQ(err(R"({"meshes": [{)" + box + R"("animate": {"keys": []}}]})"),
            "anim.json: meshes[0].animate needs \"keys\": an array of at least one key");
  EXPECT_EQ(err(R"({"meshes": [{)" + box +
                R"("animate": {"interpolation": "cubic", "keys": [{"time": 0}]}}]})"),
            "anim.json: meshes[0].animate.interpolation: unknown interpolation 'cubic' (linear, "
            "smooth)");
  EXPECT_EQ(err(R"({"meshes": [{)" + box +
                R"("animate": {"keys": [{"time": 0, "quaternion": [0, 0, 0, 0]}]}}]})"),
            "anim.json: meshes[0].animate.keys[0].quaternion must not be zero");
  EXPECT_EQ(err(R"({"meshes": [{)" + box + R"("animate": {"keys": [{"time": 0, "scale": 0}]}}]})"),
            "anim.json: meshes[0].animate.keys[0].scale must not be 0");
  EXPECT_EQ(err(R"({"meshes": [{)" + box + R"("animate": {"keys": [{"time": 0, "spin": 3}]}}]})"),
            "anim.json: meshes[0].animate.keys[0]: unknown key 'spin' (time, translate, "
            "rotate, quaternion, scale)");
  EXPECT_EQ(err(R"({"meshes": [{)" + box + R"("name": "a"}, {)" + box + R"("name": "a"}]})"),
            "anim.json: meshes[1].name 'a' is used twice");
  EXPECT_EQ(err(R"({"camera": {"keys": [{"time": 0}, {"time": 0, "fov_y": 30}]}})"),
            "anim.json: camera.keys[1]: time 0 is not after keys[0]'s 0 (keys must be in time "
            "order)");
}

TEST(Animation, SceneValidationCatchesBadObjectsBuiltInCode) {
  Scene s = builtin_scene("thesis-a");
  AnimatedObject o;
  o.name = "far";
  o.first = 30;
  o.count = 12;
  o.track.keys.push_back(PoseKey{});
  s.animation.objects.push_back(o);
  s.animation.time = TimeRange{0, 1, 24};
  EXPECT_EQ(error_of([&] { s.validate(); }),
            "animated object 'far': triangles 30..42 are not in the scene (36 triangles)");
  s.animation.objects[0].count = 6;
  s.animation.objects[0].track.keys[0].pose.scale = glm::dvec3(0.0);
  EXPECT_EQ(error_of([&] { s.validate(); }),
            "animated object 'far': key 0 needs a finite translation, a non-zero scale and a "
            "unit rotation");
}

const char* kWaveScene = R"({
  "animation": {"end": 1, "fps": 4},
  "meshes": [{"name": "wave", "file": "wave-%02d.obj", "sequence": {"last": 2, "fps": 2},
              "transform": {"translate": [0, 0, -1]}}],
  "instances": [{"mesh": "wave", "transform": {"translate": [0, 2, 0]}}],
  "lights": [{"position": [0, 5, 5]}],
  "camera": {"eye": [1, 1, 5], "look_at": [1, 1, 0]}
})";

TEST(Animation, ObjSequencesDeformAndKeepTheirTopology) {
  testing::TempDir dir;
  for (int k = 0; k < 3; ++k)
    dir.file("wave-0" + std::to_string(k) + ".obj", wave_obj(0.5f * static_cast<float>(k)));
  const std::string path = dir.file("wave.json", kWaveScene);
  const Scene s = load_json(path);
  ASSERT_EQ(s.animation.objects.size(), 2u);  // the mesh and its copy, which deforms too
  for (const AnimatedObject& o : s.animation.objects) {
    EXPECT_EQ(o.count, 4u);
    EXPECT_EQ(o.shapes.size(), 3u);
  }
  // At 2 files per second: t = 0.5 shows file 1, whose middle vertex is at z = 0.5 - 1.
  // t = 0.25 still shows file 0; after the last file it holds.
  auto middle_z = [](const Scene& b, size_t first) {
    float z = -10.0f;
    for (size_t i = 3 * first; i < 3 * (first + 4); ++i) z = std::max(z, b.positions[i].z);
    return z;
  };
  EXPECT_EQ(middle_z(bake(s, 0.0), 0), -1.0f);
  EXPECT_EQ(middle_z(bake(s, 0.25), 0), -1.0f);
  EXPECT_EQ(middle_z(bake(s, 0.5), 0), -0.5f);
  EXPECT_EQ(middle_z(bake(s, 1.0), 0), 0.0f);
  EXPECT_EQ(middle_z(bake(s, 9.0), 4), 0.0f);        // the copy, held at the last file
  EXPECT_EQ(bake(s, 0.5).positions[3 * 4].y, 2.0f);  // the copy's first corner, 2 up

  // Another topology, another triangle count, no frame number, a missing file.
  dir.file("wave-02.obj", wave_obj(1.0f, true));
  EXPECT_EQ(error_of([&] { load_json(path); }),
            path +
                ": meshes[0].sequence: wave-02.obj: triangle 2 uses other vertices than in "
                "the first file (the files of a sequence keep their topology)");
  dir.file("wave-02.obj", wave_obj(1.0f) + "f 1 2 4\n");
  EXPECT_EQ(error_of([&] { load_json(path); }),
            path +
                ": meshes[0].sequence: wave-02.obj has 5 triangles where wave-00.obj has 4 "
                "(the files of a sequence keep their topology)");
  const std::string no_number =
      dir.file("n.json", R"({"meshes": [{"file": "wave.obj", "sequence": {"last": 2}}]})");
  EXPECT_EQ(error_of([&] { load_json(no_number); }),
            no_number +
                ": meshes[0].file 'wave.obj' needs one frame number, %d or %03d (a width of at "
                "most 20), for its \"sequence\"");
  const std::string too_wide =
      dir.file("w.json", R"({"meshes": [{"file": "wave-%40d.obj", "sequence": {"last": 2}}]})");
  EXPECT_NE(error_of([&] { load_json(too_wide); }).find("a width of at most 20"),
            std::string::npos);
  const std::string missing =
      dir.file("m.json", R"({"meshes": [{"file": "wave-%02d.obj", "sequence": {"last": 5}}]})");
  dir.file("wave-02.obj", wave_obj(1.0f));
  // The missing file names the scene, the mesh and which file of the sequence it is.
  EXPECT_NE(error_of([&] {
              load_json(missing);
            }).find(missing + ": meshes[0].sequence: file 3 of 0..5: "),
            std::string::npos)
      << error_of([&] { load_json(missing); });
  EXPECT_NE(error_of([&] { load_json(missing); }).find("wave-03.obj"), std::string::npos);
}

TEST(Animation, BuiltinBounceScene) {
  const Scene s = builtin_scene("bounce");
  EXPECT_EQ(s.animation.objects.size(), 9u);
  EXPECT_EQ(s.animation.time.frame_count(), 97);
  EXPECT_EQ(s.animation.camera.keys.size(), 2u);
  // The balls leave the floor and come back: frame 0 and a later frame differ.
  EXPECT_NE(bake(s, 0.0).positions, bake(s, 0.5).positions);
  EXPECT_EQ(build_grid(s).usable, 40u);  // thesis A's boxes, the floor and the wall
}

}  // namespace
}  // namespace rt
