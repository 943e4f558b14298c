// Bad input: every malformed, truncated or absurd input gives a clear SceneError or a
// documented behaviour, never a crash or a hang. (Rendering such scenes is checked per
// backend in tracer/RenderTest.cpp.)
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <random>

#include "MaterialValues.h"
#include "TestUtil.h"
#include "rill/rt/accel/Grid.h"
#include "rill/rt/load/SceneFile.h"
#include "rill/rt/scene/Image.h"
#include "rill/rt/scene/InputFile.h"
#include "rill/rt/scene/Scene.h"
#include "rill/rt/shaders/Registry.h"

namespace rt {
namespace {

using testing::color_of;
using testing::error_of;
using testing::TempDir;

const char* kCube =
    "mtllib cube.mtl\n"
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
    "vn 0 0 -1\nvn 0 0 1\n"
    "o cube\nusemtl red\n"
    "f 1//1 4//1 3//1 2//1\nf 5//2 6//2 7//2 8//2\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";

TEST(BadInput, MissingFiles) {
  TempDir dir;
  EXPECT_NE(error_of([&] { load_obj(dir.path("nope.obj")); }).find("no such file"),
            std::string::npos);
  EXPECT_NE(error_of([&] { load_json(dir.path("nope.json")); }).find("no such file"),
            std::string::npos);
  EXPECT_NE(error_of([&] { load_scene(dir.path("nope.json")); }).find("no such file"),
            std::string::npos);
  EXPECT_NE(error_of([&] { load_obj(dir.dir()); }).find("directory"), std::string::npos);
  EXPECT_NE(error_of([&] { load_json(dir.dir()); }).find("directory"), std::string::npos);
  std::string txt = dir.file("scene.txt", "hello");
  EXPECT_NE(error_of([&] { load_scene(txt); }).find("unknown scene type"), std::string::npos);
  // A JSON scene naming a missing OBJ.
  std::string json = dir.file("s.json", R"({"meshes": [{"file": "missing.obj"}]})");
  // The message names the scene, the key and where the relative path was looked for.
  EXPECT_EQ(error_of([&] { load_json(json); }),
            json + ": meshes[0].file: " + dir.path("missing.obj") +
                ": no such file ('missing.obj' is relative to the scene's folder)");
  // A folder given as the scene: said so, not that its extension is unknown.
  EXPECT_EQ(error_of([&] { load_scene(dir.dir()); }),
            dir.dir() + ": is a directory, not a scene (.json, .obj, .ply, .gltf or .glb)");
}

// A path naming a device or a pipe is refused before anything is read (reading /dev/zero
// grew memory without bound), and so is a file over the input limit.
// A NUL character (JSON's \u0000) in a string that names a file is an error naming the key:
// the system reads a name only up to its NUL, so "m.obj\u0000.png" loaded m.obj, another file
// than the one named, without a word.
TEST(BadInput, ANulInAFileNameIsAnErrorNamingTheKey) {
  TempDir dir;
  dir.file("m.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  write_png(dir.path("t.png"), 1, 1, {glm::vec3(1.0f)});
  const std::string tex = R"("textures": {"t": {"file": "t.png"}}, )";
  EXPECT_EQ(load_json(dir.file("fine.json", "{" + tex + R"("meshes": [{"file": "m.obj"}]})"))
                .triangle_count(),
            1u);
  const std::pair<std::string, std::string> cases[] = {
      {R"({"meshes": [{"file": "m.obj\u0000.png"}]})",
       "meshes[0].file has a NUL character (at "
       "byte 5): a file name cannot; the system "
       "would read it as 'm.obj'"},
      {R"({"textures": {"t": {"file": "t.png\u0000.jpg"}}, "meshes": [{"file": "m.obj"}]})",
       "textures.t.file has a NUL character (at byte 5)"},
      {R"({"meshes": [{"file": "m.obj\u0000%d", "sequence": {"last": 1}}]})",
       "meshes[0].file has a NUL character (at byte 5)"},
  };
  for (const auto& c : cases) {
    // (Not a structured binding: clang 14 cannot capture one in a lambda.)
    const std::string &json = c.first, &expected = c.second;
    const std::string e = error_of([&] { load_json(dir.file("nul.json", json)); });
    EXPECT_NE(e.find(expected), std::string::npos) << json << "\n" << e;
  }
  // Below the scene file's keys, any reader's: the file is not opened.
  EXPECT_NE(error_of([&] { read_input_file(std::string("m.obj\0x", 7), "an OBJ file"); })
                .find("m.obj\\x00x: a file name with a NUL character (at byte 5); the system "
                      "would read it as 'm.obj', another file"),
            std::string::npos);
}

TEST(BadInput, OnlyRegularFilesWithinTheLimitAreRead) {
  TempDir dir;
  const std::string fifo = dir.path("pipe.obj");
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  for (const std::string& device : {std::string("/dev/zero"), fifo}) {
    SCOPED_TRACE(device);
    EXPECT_NE(error_of([&] { load_obj(device); }).find("not a regular file"), std::string::npos);
    EXPECT_NE(error_of([&] { load_json(device); }).find("not a regular file"), std::string::npos);
    const std::string json =
        dir.file("mesh.json", R"({"meshes": [{"file": ")" + device + R"("}]})");
    EXPECT_NE(error_of([&] { load_json(json); }).find("not a regular file"), std::string::npos);
    // An mtllib naming one.
    const std::string obj =
        dir.file("m.obj", "mtllib " + device + "\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    EXPECT_NE(error_of([&] { load_obj(obj); }).find("not a regular file"), std::string::npos);
  }
  // Over the limit (RILL_MAX_INPUT_MB): the size and the limit are named.
  const std::string big = dir.file("big.obj", std::string(3 << 20, '#'));
  ASSERT_EQ(setenv("RILL_MAX_INPUT_MB", "2", 1), 0);
  const std::string e = error_of([&] { load_obj(big); });
  unsetenv("RILL_MAX_INPUT_MB");
  EXPECT_NE(e.find("over the input limit of 2 MiB"), std::string::npos) << e;
  EXPECT_NE(e.find("3 MiB"), std::string::npos) << e;
}

// An mtllib is found the same way however the OBJ's path is spelled: a relative name from the
// OBJ's folder, an absolute one as it is. A missing MTL is a warning that names it.
TEST(BadInput, MtllibResolvesOneWayAndMissingOnesAreWarnings) {
  TempDir dir;
  dir.file("red.mtl", "newmtl red\nKd 1 0 0\n");
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n";
  const std::string rel = dir.file("rel.obj", "mtllib red.mtl\n" + tri);
  const std::string abs = dir.file("abs.obj", "mtllib " + dir.path("red.mtl") + "\n" + tri);
  const std::string cwd = std::filesystem::current_path().string();
  for (const std::string& obj : {rel, abs}) {
    for (int spelling = 0; spelling < 3; ++spelling) {
      std::filesystem::current_path(dir.dir());
      const std::string name = std::filesystem::path(obj).filename().string();
      const std::string as_given = spelling == 0 ? name : spelling == 1 ? "./" + name : obj;
      Scene s = load_obj(as_given);
      std::filesystem::current_path(cwd);
      SCOPED_TRACE(obj + " as " + as_given);
      ASSERT_EQ(s.triangle_count(), 1u);
      EXPECT_EQ(color_of(s.materials[static_cast<size_t>(s.material[0])], "diffuse"),
                glm::vec3(1, 0, 0));
      EXPECT_TRUE(s.warnings.empty());
    }
  }
  const std::string missing = dir.file("missing.obj", "mtllib gone.mtl\n" + tri);
  Scene s = load_obj(missing);
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_EQ(s.warnings[0], missing + ": mtllib " + dir.path("gone.mtl") +
                               ": no such file (its materials are missing; faces that use them "
                               "get the default grey)");
  // They reach a JSON scene that names the OBJ.
  const std::string json = dir.file("w.json", R"({"meshes": [{"file": "missing.obj"}]})");
  EXPECT_EQ(load_json(json).warnings, s.warnings);
  // A mesh given its material by the scene file: no face is grey, and the warning says so.
  const std::string own = dir.file("own.json", R"({"materials": {"blue": {"diffuse": [0, 0, 1]}},
                      "meshes": [{"file": "missing.obj", "material": "blue"}]})");
  const Scene o = load_json(own);
  ASSERT_EQ(o.warnings.size(), 1u);
  EXPECT_EQ(o.warnings[0], missing + ": mtllib " + dir.path("gone.mtl") +
                               ": no such file (its materials are missing, but no face uses them: "
                               "the scene file gives this mesh its material)");
  EXPECT_EQ(color_of(o.materials[static_cast<size_t>(o.material[0])], "diffuse"),
            glm::vec3(0, 0, 1));
}

// Errors name the exact place (an array element, a file's line and shape), and quote long
// user strings only in part.
TEST(BadInput, ErrorsNameThePlaceAndClipLongStrings) {
  TempDir dir;
  auto json_error = [&](const std::string& text) {
    return error_of([&] { load_json(dir.file("e.json", text)); });
  };
  EXPECT_NE(
      json_error(R"({"camera": {"eye": [0, [1], 5]}})").find("camera.eye[1] must be a number"),
      std::string::npos);
  EXPECT_NE(
      json_error(R"({"lights": [{"position": [0, 1, "x"]}]})").find("position[2] must be a number"),
      std::string::npos);
  EXPECT_NE(
      json_error(R"({"meshes": [{"shape": "triangle", "vertices": [[0,0,0],[1,0,0],[0,1]]}]})")
          .find("meshes[0].vertices[2] must be an array of 3 numbers"),
      std::string::npos);
  const std::string long_name(100000, 'n');
  const std::string unknown = json_error("{\"" + long_name + "\": 1}");
  EXPECT_LT(unknown.size(), 600u) << unknown.size();
  EXPECT_NE(unknown.find("(100000 bytes)"), std::string::npos);
  const std::string obj =
      dir.file("long.obj", "o " + long_name + "\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 9\n");
  const std::string face = error_of([&] { load_obj(obj); });
  EXPECT_LT(face.size(), 600u) << face.size();
  EXPECT_NE(face.find("long.obj:6: face 2 of shape 'nnn"), std::string::npos)
      << face.substr(0, 200);
  EXPECT_NE(face.find("refers to vertex 9"), std::string::npos);
}

// An OBJ the default camera cannot frame says so, instead of blaming a camera or a light the
// user never gave: every vertex at one point, or coordinates too large to place an eye.
TEST(BadInput, ScenesTheDefaultCameraCannotFrameSaySo) {
  TempDir dir;
  const std::string point = dir.file("point.obj", "v 1 2 3\nv 1 2 3\nv 1 2 3\nf 1 2 3\n");
  const std::string e = error_of([&] { load_scene(point); });
  EXPECT_NE(e.find("the scene has no extent (every vertex is at [1, 2, 3])"), std::string::npos)
      << e;
  const std::string huge = dir.file("huge.obj", "v -3e38 0 0\nv 3e38 0 0\nv 0 3e38 0\nf 1 2 3\n");
  const std::string h = error_of([&] { load_scene(huge); });
  EXPECT_NE(h.find("too large or too far out for the default camera"), std::string::npos) << h;
  // 1e20 is framed (and renders).
  const std::string far = dir.file("far.obj", "v -1e20 0 0\nv 1e20 0 0\nv 0 1e20 0\nf 1 2 3\n");
  EXPECT_NO_THROW(load_scene(far).validate());
}

TEST(BadInput, ObjIndicesOutOfRange) {
  TempDir dir;
  EXPECT_NE(error_of([&] { load_obj(dir.file("a.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n")); })
                .find("a.obj:4: face 1 of an unnamed shape refers to vertex 4, but the file has 3 "
                      "vertices"),
            std::string::npos);
  EXPECT_FALSE(error_of([&] {
                 load_obj(dir.file("b.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -5 1 2\n"));
               }).empty());
  EXPECT_FALSE(error_of([&] {
                 load_obj(dir.file("c.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n"));
               }).empty());
  EXPECT_FALSE(error_of([&] {
                 load_obj(
                     dir.file("d.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//2 2//1 3//1\n"));
               }).empty());
  EXPECT_FALSE(error_of([&] { load_obj(dir.file("e.obj", "f 1 2 3\n")); }).empty());
}

TEST(BadInput, ObjValidButUnrenderedStatementsAreQuiet) {
  TempDir dir;
  // Lines, points, groups, smoothing groups and free-form statements are valid OBJ that a
  // triangle renderer leaves out: no warning. CRLF and lone CR line ends.
  Scene s = load_obj(dir.file("a.obj",
                              "# comment\r\no thing\r\ng part\r\ns off\r\nv 0 0 0\rv 1 0 0 1\r\n"
                              "v 0 1 0 0.5 0.5 0.5\nvt 0.5\nvn 0 0 1\nl 1 2\np 1\nvp 0.1 0.2\n"
                              "f 1 2 3\n"));
  EXPECT_EQ(s.triangle_count(), 1u);
  EXPECT_TRUE(s.warnings.empty()) << s.warnings[0];
}

TEST(BadInput, ObjMalformedLinesAreWarningsNamingFileAndLine) {
  TempDir dir;
  const std::string p = dir.file("a.obj",
                                 "v 0 0 0\nv abc def\nv 1 0 0\nv 0 1 0\nf 1 2\nfoo bar\n"
                                 "vn 1 2\nf 1/x 2 3\nf 1 3 4\n");
  Scene s = load_obj(p);
  EXPECT_EQ(s.triangle_count(), 1u);
  ASSERT_EQ(s.warnings.size(), 4u);
  EXPECT_EQ(s.warnings[0], p + ":2: 'v' expects numbers ('v abc def'); the line is skipped");
  EXPECT_EQ(s.warnings[1],
            p + ":5: a face needs at least 3 vertices (got 2) ('f 1 2'); the line is skipped");
  EXPECT_EQ(s.warnings[2], p + ":6: unknown statement 'foo' ('foo bar'); the line is skipped");
  EXPECT_EQ(s.warnings[3], p + ": 2 more malformed lines skipped (5 in all; --strict-input makes "
                               "them errors)");
  // --strict-input: the first is an error.
  ObjLoadOptions strict;
  strict.input.strict = true;
  EXPECT_EQ(error_of([&] { load_obj(p, strict); }),
            p + ":2: 'v' expects numbers ('v abc def') (an error under --strict-input)");
  // Long lines are clipped in messages.
  const std::string long_name =
      dir.file("b.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nx" + std::string(100000, 'y') + "\n");
  Scene b = load_obj(long_name);
  ASSERT_EQ(b.warnings.size(), 1u);
  EXPECT_LT(b.warnings[0].size(), 300u);
}

TEST(BadInput, FacesUsingAMalformedVertexAreSkippedAndLaterIndicesKept) {
  TempDir dir;
  // Vertex 2 is malformed: the face that uses it is skipped too, and vertex 4 is still the
  // fourth v line (the placeholder keeps the numbering), also through a negative index.
  const std::string p = dir.file(
      "m.obj", "v 0 0 0\nv 1 x 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\nf -4 -2 -1\nf 1 -3 4\n");
  Scene s = load_obj(p);
  ASSERT_EQ(s.triangle_count(), 2u);
  EXPECT_EQ(s.positions[3], glm::vec3(0, 0, 0));
  EXPECT_EQ(s.positions[5], glm::vec3(0, 1, 0));
  ASSERT_EQ(s.warnings.size(), 3u);
  EXPECT_EQ(s.warnings[1], p + ":5: face vertex '2' uses the v of malformed line 2 ('f 1 2 3'); "
                               "the line is skipped");
  EXPECT_EQ(s.warnings[2], p + ":8: face vertex '-3' uses the v of malformed line 2 ('f 1 -3 "
                               "4'); the line is skipped");
}

TEST(BadInput, MessagesEscapeControlAndNonUtf8Bytes) {
  EXPECT_EQ(clipped("a\nb\x01\xff"), "a\\x0ab\\x01\\xff");
  EXPECT_EQ(clipped("caf\xc3\xa9"), "caf\xc3\xa9");  // UTF-8 kept
  EXPECT_EQ(clipped(std::string(10, 'x'), 4), "xxxx... (10 bytes)");
  // Not UTF-8: bytes past U+10FFFF, C1 controls, overlong forms, surrogates.
  EXPECT_EQ(clipped("\xf5\x80\x80\x80"), "\\xf5\\x80\\x80\\x80");
  EXPECT_EQ(clipped("\xc2\x85"), "\\xc2\\x85");
  EXPECT_EQ(clipped("\xe0\x80\xaf"), "\\xe0\\x80\\xaf");
  EXPECT_EQ(clipped("\xed\xa0\x80"), "\\xed\\xa0\\x80");
}

// What exporters write and tinyobjloader reads is not malformed: comments after values, a
// byte order mark, usemtl's first word, Kt, negative colours Rill does not render.
TEST(BadInput, CommonExporterLinesAreAccepted) {
  TempDir dir;
  dir.file("m.mtl", "newmtl red # the red one\nKd 1 0 0 # red\nKa -0.1 0 0\nKt 1 1 1\nNs 10 #x\n");
  const std::string p = dir.file("e.obj",
                                 "\xef\xbb\xbfmtllib m.mtl\nv 0 0 0 # tip\nv 1 0 0\nv 0 1 0\t\n"
                                 "usemtl red # c\nf 1 2 3 # face\n");
  Scene s = load_obj(p);
  EXPECT_EQ(s.triangle_count(), 1u);
  EXPECT_TRUE(s.warnings.empty()) << s.warnings[0];
}

TEST(BadInput, SkippedLinesKeepColoursAndFaceLines) {
  TempDir dir;
  // A bad v line in a file with vertex colours: the others keep theirs.
  Scene c =
      load_obj(dir.file("c.obj", "v 0 0 0 1 0 0\nv x\nv 1 0 0 0 1 0\nv 0 1 0 0 0 1\nf 1 3 4\n"));
  ASSERT_EQ(c.triangle_count(), 1u);
  ASSERT_EQ(c.colors.size(), 3u);
  EXPECT_EQ(c.colors[1], glm::vec3(0, 1, 0));
  // An error after a skipped face names its own line.
  const std::string p = dir.file("f.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3/x\nf 1 2 9\n");
  EXPECT_NE(error_of([&] { load_obj(p); }).find(p + ":5: face 1"), std::string::npos);
}

TEST(BadInput, ObjFaceIndexZeroIsAnErrorNamingTheLine) {
  TempDir dir;
  const std::string p = dir.file("z.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 0 1 2\n");
  EXPECT_EQ(error_of([&] { load_obj(p); }),
            p + ":5: face vertex '0' has index 0 (OBJ indices start at 1; negative ones count "
                "back from the last) ('f 0 1 2')");
}

TEST(BadInput, FilesWithoutFacesAreErrorsUnlessAllowed) {
  TempDir dir;
  const std::string empty = dir.file("b.obj", "");
  EXPECT_EQ(error_of([&] { load_obj(empty); }),
            empty + ": the file is empty (--allow-empty loads it as no triangles)");
  const std::string comments = dir.file("c.obj", "# nothing\n\nv 0 0 0\n");
  EXPECT_EQ(error_of([&] { load_obj(comments); }),
            comments +
                ": no faces in 3 lines (1 vertices, 0 malformed lines): is it an OBJ "
                "file? (--allow-empty loads it as no triangles)");
  // Bytes of another kind (here: random ones, and a scene file named as a mesh).
  std::string noise;
  uint32_t x = 12345;
  for (int i = 0; i < 100000; ++i) {
    x = x * 1664525u + 1013904223u;
    noise.push_back(static_cast<char>(x >> 24));
  }
  const std::string random = dir.file("random.obj", noise);
  EXPECT_NE(error_of([&] { load_obj(random); }).find("is it an OBJ file?"), std::string::npos);
  const std::string json = dir.file("s.json", R"({"meshes": [{"file": "s.json"}], "lights": []})");
  EXPECT_NE(error_of([&] { load_json(json); }).find("s.json: no faces in 1 lines"),
            std::string::npos);
  // --allow-empty: no triangles, no error.
  ObjLoadOptions allow;
  allow.input.allow_empty = true;
  EXPECT_EQ(load_obj(empty, allow).triangle_count(), 0u);
  EXPECT_EQ(load_obj(comments, allow).triangle_count(), 0u);
  InputOptions in;
  in.allow_empty = true;
  EXPECT_EQ(load_json(json, in).triangle_count(), 0u);
}

TEST(BadInput, UnknownUsemtlIsAWarning) {
  TempDir dir;
  dir.file("m.mtl", "newmtl red\nKd 1 0 0\n");
  const std::string p =
      dir.file("u.obj",
               "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\nusemtl blue\n"
               "f 1 2 3\nusemtl blue\nf 1 2 3\n");
  Scene s = load_obj(p);
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_EQ(s.warnings[0], p + ":7: usemtl 'blue': no material of that name in its MTL files; its "
                               "faces get the default grey");
  // The first 3 names are warned about with their lines, the rest counted (they were dropped
  // without a word).
  std::string five = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n";
  for (const char* name : {"c1", "c2", "c3", "c4", "c5", "c4"})
    five += std::string("usemtl ") + name + "\nf 1 2 3\n";
  const std::string f = dir.file("five.obj", five);
  Scene many = load_obj(f);
  ASSERT_EQ(many.warnings.size(), 4u);
  EXPECT_EQ(many.warnings[2].rfind(f + ":9: usemtl 'c3'", 0), 0u) << many.warnings[2];
  EXPECT_EQ(many.warnings[3], f + ": 2 more usemtl names with no material (5 in all); their "
                                  "faces get the default grey too");
  // Without any mtllib.
  const std::string q = dir.file("n.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red \nf 1 2 3\n");
  Scene n = load_obj(q);
  ASSERT_EQ(n.warnings.size(), 1u);
  EXPECT_EQ(n.warnings[0], q + ":4: usemtl 'red': no material of that name in any MTL file (the "
                               "OBJ loads none); its faces get the default grey");
}

TEST(BadInput, MtllibNamingTheObjOrAFolderIsAnError) {
  TempDir dir;
  const std::string self =
      dir.file("self.obj", "mtllib self.obj\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  EXPECT_EQ(error_of([&] { load_obj(self); }),
            self + ": mtllib self.obj names this OBJ file itself, not an MTL file");
  std::filesystem::create_directories(dir.path("folder"));
  const std::string folder =
      dir.file("f.obj", "mtllib folder\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  EXPECT_NE(error_of([&] { load_obj(folder); }).find("folder: is a directory, not an MTL file"),
            std::string::npos);
}

TEST(BadInput, MtlValueErrorsNameFileLineAndField) {
  TempDir dir;
  const std::string obj = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl w\nf 1 2 3\n";
  auto error_with = [&](const std::string& mtl) {
    dir.file("m.mtl", mtl);
    return error_of([&] { load_obj(dir.file("o.obj", obj)); });
  };
  const std::string m = dir.path("m.mtl");
  EXPECT_EQ(error_with("newmtl w\nNs nan\n"),
            m + ":2: 'Ns' of material 'w' must be a finite number ('Ns nan')");
  EXPECT_EQ(error_with("newmtl w\nKd 0.5 inf 0\n"),
            m + ":2: 'Kd' of material 'w' must be finite numbers ('Kd 0.5 inf 0')");
  EXPECT_EQ(error_with("# a\nnewmtl w\nKd 0.5 0.5 0.5\nKs -1 0 0\n"),
            m + ":4: 'Ks' of material 'w' is negative; colours must be >= 0 ('Ks -1 0 0')");
  EXPECT_EQ(error_with("newmtl w\nd 2\n"), m + ":2: 'd' of material 'w' must be in 0..1 ('d 2')");
  EXPECT_EQ(error_with("newmtl w\nillum 2.5\n"),
            m + ":2: 'illum' of material 'w' must be an integer in 0..10 ('illum 2.5')");
  // Malformed: warnings (errors under --strict-input).
  dir.file("m.mtl", "newmtl w\nKd abc\nKs 0.1 0.1\n");
  Scene s = load_obj(dir.file("o.obj", obj));
  ASSERT_EQ(s.warnings.size(), 2u);
  EXPECT_EQ(s.warnings[0], m + ":2: 'Kd' expects 1 or 3 numbers ('Kd abc'); the line is skipped");
  ObjLoadOptions strict;
  strict.input.strict = true;
  EXPECT_EQ(error_of([&] { load_obj(dir.file("o.obj", obj), strict); }),
            m + ":2: 'Kd' expects 1 or 3 numbers ('Kd abc') (an error under --strict-input)");
}

// Cut a valid OBJ (and its MTL) at every byte: each prefix loads or fails with SceneError,
// and whatever loads can be gridded.
TEST(BadInput, TruncatedObjAndMtl) {
  TempDir dir;
  const std::string mtl = "newmtl red\nKd 0.9 0.1 0.1\nKs 0.5 0.5 0.5\nNs 64\nd 0.5\nillum 7\n";
  const std::string obj = kCube;
  for (size_t n = 0; n <= obj.size(); ++n) {
    dir.file("cube.mtl", mtl);
    std::string p = dir.file("cube.obj", obj.substr(0, n));
    try {
      Scene s = load_obj(p);
      s.validate();
      Grid g = build_grid(s, 0);
      EXPECT_LE(g.usable, s.triangle_count());
    } catch (const SceneError&) {
    }
  }
  for (size_t n = 0; n <= mtl.size(); ++n) {
    dir.file("cube.mtl", mtl.substr(0, n));
    std::string p = dir.file("cube.obj", obj);
    Scene s = load_obj(p);
    EXPECT_EQ(s.triangle_count(), 12u);
    EXPECT_NO_THROW(s.validate()) << "MTL cut at " << n;
  }
}

TEST(BadInput, MalformedMtlValues) {
  TempDir dir;
  dir.file("m.mtl", "newmtl x\nKd abc def\nNs -5\nNi 0\nd 7\nillum 99\nKs 1e39 1 1\nnewmtl\n");
  std::string p = dir.file("m.obj", "mtllib m.mtl\nusemtl x\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  Scene s;
  try {
    s = load_obj(p);
  } catch (const SceneError&) {
    return;  // a clear error is fine too
  }
  // Loaded: the values were sanitized or validate() says what is wrong.
  try {
    s.validate();
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("material"), std::string::npos);
  }
}

TEST(BadInput, RandomBytesAsObjAndJson) {
  TempDir dir;
  std::mt19937 rng(7);
  for (int k = 0; k < 40; ++k) {
    std::string junk(static_cast<size_t>(rng() % 400), '\0');
    for (char& c : junk) c = static_cast<char>(rng() % 256);
    if (k % 2 == 0) {  // mostly-plausible tokens
      const char* tok[] = {"v ", "f ", "vn ",  "vt ",   "1 ",      "-1 ", "/",
                           "//", "\n", "nan ", "1e40 ", "usemtl ", "o "};
      junk.clear();
      for (int i = 0; i < 200; ++i) junk += tok[rng() % 13];
    }
    std::string p = dir.file("junk.obj", junk);
    try {
      Scene s = load_obj(p);
      build_grid(s, 0);
    } catch (const SceneError&) {
    }
    std::string j = dir.file("junk.json", junk);
    EXPECT_THROW(load_json(j), SceneError);
  }
}

TEST(BadInput, NonFiniteAndDegenerateTrianglesAreLeftOut) {
  Scene s;
  s.add_material(Material{});
  const float nan = std::nanf(""), inf = INFINITY;
  s.add_triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 0);    // 0: fine
  s.add_triangle({nan, 0, 0}, {1, 0, 0}, {0, 1, 0}, 0);  // 1: NaN
  s.add_triangle({0, 0, 0}, {inf, 0, 0}, {0, 1, 0}, 0);  // 2: infinite
  s.add_triangle({0, 0, 0}, {1, 1, 1}, {2, 2, 2}, 0);    // 3: collinear
  s.add_triangle({5, 5, 5}, {5, 5, 5}, {5, 5, 5}, 0);    // 4: a point
  s.add_triangle({0, 0, 1}, {1, 0, 1}, {0, 1, 1}, 0);    // 5: fine
  EXPECT_NO_THROW(s.validate());
  Grid g = build_grid(s, 0);
  EXPECT_EQ(g.usable, 2u);
  EXPECT_EQ(g.non_finite, 2u);
  EXPECT_EQ(g.degenerate, 2u);
  for (int32_t t : g.elements) EXPECT_TRUE(t == 0 || t == 5) << t;
  // The grid box ignores the bad ones.
  EXPECT_LT(g.hi.x, 1.1f);
  EXPECT_GT(g.lo.z, -0.1f);
}

TEST(BadInput, NanFromTheObjFile) {
  TempDir dir;
  Scene s =
      load_obj(dir.file("n.obj", "v nan 0 0\nv 1 0 0\nv 0 1 0\nv 1e39 0 0\nf 1 2 3\nf 4 2 3\n"));
  EXPECT_EQ(s.triangle_count(), 2u);
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
  // Both are non-finite (never hit): "nan" is not read as 0, as tinyobjloader alone would.
  Grid g = build_grid(s, 0);
  EXPECT_EQ(g.non_finite, 2u);
  EXPECT_EQ(g.usable, 0u);
  Scene words = load_obj(dir.file("w.obj", "v 0 0 0\nv -inf 0 0\nv 0 INF 1\nf 1 2 3\n"));
  EXPECT_EQ(build_grid(words, 0).non_finite, 1u);
}

// Texture coordinates, normals and vertex colours that would render wrongly are errors naming
// the OBJ's line.
TEST(BadInput, ObjAttributeValuesAreCheckedPerLine) {
  TempDir dir;
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  auto error = [&](const std::string& name, const std::string& text) {
    const std::string p = dir.file(name, text);
    return std::make_pair(p, error_of([&] { load_obj(p); }));
  };
  auto [vt, vt_error] = error("vt.obj", tri + "vt 1e39 0\nf 1/1 2/1 3/1\n");
  EXPECT_EQ(vt_error, vt + ":4: 'vt' texture coordinates must be finite numbers ('vt 1e39 0')");
  auto [vn, vn_error] = error("vn.obj", tri + "vn inf 0 1\nf 1//1 2//1 3//1\n");
  EXPECT_EQ(vn_error, vn + ":4: 'vn' normals must be finite numbers ('vn inf 0 1')");
  auto [vc, vc_error] = error("vc.obj", "v 0 0 0 1 1 1\nv 1 0 0 -5 1 0\nv 0 1 0 1 1 1\nf 1 2 3\n");
  EXPECT_EQ(vc_error, vc + ":2: 'v' vertex colours must be finite numbers >= 0 ('v 1 0 0 -5 1 0')");
  auto [ix, ix_error] = error("ix.obj", tri + "f 1 2 2147483648\n");
  EXPECT_EQ(ix_error, ix + ":4: face vertex '2147483648' has an index out of range (the file "
                           "has 3 v lines before it) ('f 1 2 2147483648')");
  // 1e39 is a finite double but no float: an MTL value that overflows is an error too.
  const std::string mtl = dir.file("m.mtl", "newmtl x\nKd 1e39 0 0\n");
  const std::string obj = dir.file("m.obj", "mtllib m.mtl\nusemtl x\n" + tri + "f 1 2 3\n");
  const std::string kd = error_of([&] { load_obj(obj); });
  EXPECT_EQ(kd, mtl + ":2: 'Kd' of material 'x' must be finite numbers ('Kd 1e39 0 0')");
  auto [big, big_error] =
      error("big.obj", "v 0 0 0 1 1 1\nv 1 0 0 1e39 1 0\nv 0 1 0 1 1 1\nf 1 2 3\n");
  EXPECT_NE(big_error.find(":2: 'v' vertex colours must be finite"), std::string::npos)
      << big_error;
}

TEST(BadInput, AbsurdSizesAndOptions) {
  Scene s = builtin_scene("thesis-a");
  auto bad = [&](auto change, const char* what) {
    Scene c = s;
    change(c);
    EXPECT_FALSE(error_of([&] { c.validate(); }).empty()) << what;
  };
  bad([](Scene& c) { c.width = 0; }, "width 0");
  bad([](Scene& c) { c.height = -3; }, "negative height");
  bad([](Scene& c) { c.width = 100000; }, "huge width");
  bad([](Scene& c) { c.width = c.height = 16000; }, "too many pixels");
  bad([](Scene& c) { c.options.max_depth = 1000; }, "max_depth");
  bad([](Scene& c) { c.options.spp = 0; }, "spp");
  bad([](Scene& c) { c.options.grid = 100000; }, "grid");
  bad([](Scene& c) { c.camera.fov_y = 0; }, "fov 0");
  bad([](Scene& c) { c.camera.fov_y = 180; }, "fov 180");
  bad([](Scene& c) { c.camera.fov_y = std::nanf(""); }, "fov NaN");
  bad([](Scene& c) { c.camera.look_at = c.camera.eye; }, "eye == look_at");
  bad([](Scene& c) { c.camera.up = c.camera.look_at - c.camera.eye; }, "up parallel");
  bad([](Scene& c) { c.camera.eye.x = INFINITY; }, "eye inf");
  bad([](Scene& c) { c.lights[0].color.y = std::nanf(""); }, "light NaN");
  bad([](Scene& c) { c.materials[0].set("diffuse", glm::vec3(1, -1, 0)); }, "negative colour");
  bad([](Scene& c) { c.materials[0].set("shininess", std::nanf("")); }, "NaN parameter");
  bad([](Scene& c) { c.background.z = -INFINITY; }, "background");
  // What a shader asks of its own parameters is its check (SurfaceShader::check), which a
  // Tracer runs as it resolves the materials' shaders (resolve_shaders).
  auto bad_for_shader = [&](auto change, const std::string& expected) {
    Scene c = s;
    change(c);
    const std::string err = error_of([&] { resolve_shaders(c); });
    EXPECT_NE(err.find(expected), std::string::npos) << err;
  };
  bad_for_shader(
      [](Scene& c) {
        c.materials[0].shader = "glass";
        c.materials[0].set("reflect", 0.7f).set("transmit", 0.7f);
      },
      "reflect and transmit must be >= 0 with reflect + transmit <= 1");
  bad_for_shader(
      [](Scene& c) {
        c.materials[0].shader = "glass";
        c.materials[0].set("ior", 0.0f);
      },
      "ior must be in (0, 100]");
  bad_for_shader([](Scene& c) { c.materials[0].set("reflect", 1.5f); },
                 "reflect must be in [0, 1]");
  bad_for_shader([](Scene& c) { c.materials[0].set("shininess", -1.0f); },
                 "shininess must be in [0, 10000]");
  bad_for_shader([](Scene& c) { c.materials[0].shader = "nope"; }, "no shader named 'nope'");
  EXPECT_NO_THROW(resolve_shaders(s));
}

// The shapes' triangles are added up before any is made: three 4096 x 4096 spheres (100
// million triangles) are an error naming the third, before the first two are tessellated
// (which took 43 s and 3 GiB when only each shape was counted as it was made).
TEST(BadInput, ShapesOverTheTriangleLimitFailBeforeTheyAreBuilt) {
  const std::string sphere = R"({"shape": "sphere", "slices": 4096, "stacks": 4096})";
  const std::string err = error_of([&] {
    parse_json_scene(R"({"meshes": [)" + sphere + "," + sphere + "," + sphere + "]}", ".",
                     "big.json");
  });
  EXPECT_NE(err.find("big.json: meshes[2]: it would make"), std::string::npos) << err;
  EXPECT_NE(err.find("at most 67108864 are supported"), std::string::npos) << err;
}

// A key given twice in one object is an error naming it and where (JSON parsers keep the
// last one, so a typo could silently replace a setting).
TEST(BadInput, DuplicateJsonKeysAreErrors) {
  EXPECT_EQ(error_of([] {
              parse_json_scene(R"({"builtin": "thesis-a", "builtin": "cornell"})", ".", "d.json");
            }),
            "d.json: key 'builtin' appears twice in scene");
  EXPECT_EQ(error_of([] {
              parse_json_scene(R"({"materials": {"m": {"reflect": 0.1, "reflect": 0.2}}})", ".",
                               "d.json");
            }),
            "d.json: key 'reflect' appears twice in materials.m");
  EXPECT_EQ(error_of([] {
              parse_json_scene(R"({"lights": [{"position": [0, 1, 0], "position": [1, 1, 1]}]})",
                               ".", "d.json");
            }),
            "d.json: key 'position' appears twice in lights[]");
  // The same key in two objects is fine.
  EXPECT_NO_THROW(parse_json_scene(
      R"({"lights": [{"position": [0, 1, 0]}, {"position": [1, 1, 1]}]})", ".", "ok.json"));
}

// Objects and arrays nest at most kMaxJsonDepth (256) levels: a file past it is an error naming
// the file, the key it is under and the limit, raised at the 257th bracket, so that a small
// hostile file cannot make the parser build a document of millions of levels.
TEST(BadInput, JsonNestedDeeperThanTheLimitIsAnError) {
  auto meshes_nested = [](int arrays) {
    return R"({"meshes": )" + std::string(static_cast<size_t>(arrays), '[') +
           std::string(static_cast<size_t>(arrays), ']') + "}";
  };
  // 256 levels (the scene object and 255 arrays) are read, and the scene is then refused for
  // what it says.
  EXPECT_EQ(error_of([&] { parse_json_scene(meshes_nested(255), ".", "n.json"); }),
            "n.json: meshes[0] must be an object");
  const std::string limit =
      "n.json: meshes: JSON nested deeper than 256 levels (objects and arrays), the most a "
      "scene file may nest";
  EXPECT_EQ(error_of([&] { parse_json_scene(meshes_nested(256), ".", "n.json"); }), limit);
  // 200 KB of brackets: the same error, named by the file it came from.
  TempDir dir;
  const std::string path = dir.file("n.json", meshes_nested(100000));
  EXPECT_EQ(error_of([&] { load_json(path); }), path + limit.substr(std::string("n.json").size()));
  // Objects count as arrays do.
  std::string objects = "{\"options\": ";
  for (int i = 0; i < 300; ++i) objects += R"({"a": )";
  objects += "1" + std::string(301, '}');
  EXPECT_NE(error_of([&] {
              parse_json_scene(objects, ".", "o.json");
            }).find("o.json: options: JSON nested deeper than 256 levels"),
            std::string::npos);
}

// A word an option does not take is named with the words it does.
TEST(BadInput, OptionWordsAreNamed) {
  EXPECT_EQ(error_of([] { parse_json_scene(R"({"options": {"grid": "AUTO"}})", ".", "o.json"); }),
            "o.json: options.grid 'AUTO': expected \"auto\" or an integer in 1..512");
  EXPECT_NE(error_of([] {
              parse_json_scene(R"({"options": {"light_buffer": "on"}})", ".", "o.json");
            }).find("options.light_buffer 'on': expected \"auto\", \"off\" or an integer in 1.."),
            std::string::npos);
  EXPECT_NO_THROW(
      parse_json_scene(R"({"options": {"grid": "auto", "subgrids": "off"}})", ".", "o.json"));
}

// Every material the JSON defines is checked, whether a mesh uses it or not.
TEST(BadInput, UnusedMaterialsAreCheckedToo) {
  const std::string err = error_of([&] {
    parse_json_scene(R"({"materials": {"m": {"reflect": 0.6, "transmit": 0.6}}})", ".",
                     "unused.json");
  });
  EXPECT_EQ(err,
            "unused.json: material 'm': reflect and transmit must be >= 0 with reflect + "
            "transmit <= 1");
}

// Negative colours (they rendered negative radiance): an error that names the colour, from
// JSON, from an MTL file, for lights and the background.
TEST(BadInput, NegativeColoursAreErrors) {
  TempDir dir;
  auto error_for = [&](auto change) {
    Scene c = builtin_scene("thesis-a");
    change(c);
    return error_of([&] { c.validate(); });
  };
  EXPECT_NE(error_for([](Scene& c) {
              c.materials[0].set("diffuse", glm::vec3(-1, 0, 0));
            }).find("diffuse [-1, 0, 0] has a negative component"),
            std::string::npos);
  EXPECT_NE(error_for([](Scene& c) { c.lights[0].color.y = -0.5f; }).find("negative component"),
            std::string::npos);
  EXPECT_NE(error_for([](Scene& c) { c.background.x = -0.1f; }).find("background"),
            std::string::npos);
  const std::string json = dir.file("neg.json", R"({"materials": {"m": {"diffuse": [0.5, -2, 0]}},
      "meshes": [{"shape": "triangle", "vertices": [[0,0,0],[1,0,0],[0,1,0]], "material": "m"}]})");
  EXPECT_NE(error_of([&] { load_json(json).validate(); }).find("has a negative component"),
            std::string::npos);
  dir.file("neg.mtl", "newmtl n\nKd 0.5 0.5 0.5\nKs -1 0 0\n");
  const std::string obj =
      dir.file("neg.obj", "mtllib neg.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl n\nf 1 2 3\n");
  EXPECT_EQ(error_of([&] { load_scene(obj); }),
            dir.path("neg.mtl") +
                ":3: 'Ks' of material 'n' is negative; colours must be >= 0 ('Ks -1 0 0')");
}

TEST(BadInput, MalformedJson) {
  auto err = [](const std::string& text) {
    return error_of([&] { parse_json_scene(text, ".", "t.json"); });
  };
  EXPECT_NE(err("").find("invalid JSON"), std::string::npos);
  EXPECT_NE(err("{").find("invalid JSON"), std::string::npos);
  EXPECT_NE(err("{\"camera\": {\"eye\": [0, 1,").find("invalid JSON"), std::string::npos);
  EXPECT_NE(err("[]").find("must be an object"), std::string::npos);
  // Every unknown key's error lists the keys its object takes, the top level's too.
  EXPECT_NE(err("{\"camrea\": {}}").find("unknown key 'camrea' (builtin, "), std::string::npos)
      << err("{\"camrea\": {}}");
  EXPECT_NE(err("{\"camera\": {\"fov\": 30}}").find("camera: unknown key 'fov' ("),
            std::string::npos)
      << err("{\"camera\": {\"fov\": 30}}");
  EXPECT_NE(err("{\"camera\": {\"fov\": 30}}").find("fov_y"), std::string::npos);
  EXPECT_NE(err("{\"camera\": 5}").find("camera must be an object"), std::string::npos);
  EXPECT_NE(err("{\"camera\": {\"eye\": [0, 1]}}").find("array of 3 numbers"), std::string::npos);
  EXPECT_NE(err("{\"camera\": {\"eye\": [0, \"1\", 2]}}").find("must be a number"),
            std::string::npos);
  EXPECT_NE(err("{\"camera\": {\"fov_y\": 1e400}}").find("t.json"), std::string::npos);
  EXPECT_NE(err("{\"camera\": {\"fov_y\": 200}}").find("fov_y"), std::string::npos);
  EXPECT_NE(err("{\"image\": {\"width\": -5}}").find("image.width"), std::string::npos);
  EXPECT_NE(err("{\"image\": {\"width\": 1.5}}").find("integer"), std::string::npos);
  EXPECT_NE(err("{\"image\": {\"width\": 99999999999}}").find("image.width"), std::string::npos);
  EXPECT_NE(err("{\"meshes\": {}}").find("meshes must be an array"), std::string::npos);
  EXPECT_NE(err("{\"meshes\": [{}]}").find("needs \"file\""), std::string::npos);
  EXPECT_NE(err("{\"meshes\": [{\"shape\": \"cone\"}]}").find("unknown"), std::string::npos);
  EXPECT_NE(err("{\"meshes\": [{\"shape\": \"box\", \"material\": \"nope\"}]}").find("not defined"),
            std::string::npos);
  EXPECT_NE(err("{\"meshes\": [{\"shape\": \"sphere\", \"radius\": -1}]}").find("radius"),
            std::string::npos);
  EXPECT_NE(err("{\"meshes\": [{\"shape\": \"sphere\", \"slices\": 1000000}]}").find("slices"),
            std::string::npos);
  EXPECT_NE(
      err("{\"meshes\": [{\"shape\": \"box\", \"transform\": {\"scale\": 0}}]}").find("scale"),
      std::string::npos);
  EXPECT_NE(err("{\"lights\": [{}]}").find("needs a position"), std::string::npos);
  EXPECT_NE(err("{\"materials\": {\"m\": {\"reflect\": 0.8, \"transmit\": 0.8}}, "
                "\"meshes\": [{\"shape\": \"box\", \"material\": \"m\"}]}")
                .find("reflect"),
            std::string::npos);
  EXPECT_NE(err("{\"options\": {\"grid\": \"fine\"}}").find("options.grid"), std::string::npos);
  EXPECT_NE(err("{\"options\": {\"subgrids\": \"on\"}}").find("options.subgrids"),
            std::string::npos);
  EXPECT_NE(err("{\"options\": {\"subgrids\": 0}}").find("options.subgrids"), std::string::npos);
  EXPECT_NE(err("{\"options\": {\"grid_density\": 0}}").find("options.grid_density"),
            std::string::npos);
  EXPECT_NE(err("{\"options\": {\"grid_density\": \"dense\"}}").find("options.grid_density"),
            std::string::npos);
  // The one word it takes is "auto"; the message says so.
  EXPECT_NE(err("{\"options\": {\"grid_density\": \"AUTO\"}}")
                .find("options.grid_density must be \"auto\" or a number"),
            std::string::npos);
  EXPECT_NE(err("{\"options\": {\"grid_density\": 300}}").find("options.grid_density"),
            std::string::npos);
  EXPECT_NE(err("{\"options\": {\"grid_density\": true}}").find("options.grid_density"),
            std::string::npos);
  EXPECT_NE(err("{\"options\": {\"max_depth\": 65}}").find("max_depth"), std::string::npos);
  EXPECT_NE(err("{\"builtin\": \"nope\"}").find(": builtin: unknown built-in scene 'nope'"),
            std::string::npos);
  // Deep nesting: an error, not a stack overflow.
  std::string deep(100000, '[');
  EXPECT_FALSE(err(deep).empty());
  // Well-formed but past the nesting limit (JsonNestedDeeperThanTheLimitIsAnError has more).
  std::string deep_closed = "{\"x\": " + std::string(20000, '[') + std::string(20000, ']') + "}";
  EXPECT_NE(err(deep_closed).find("x: JSON nested deeper than 256 levels"), std::string::npos);
}

TEST(BadInput, TruncatedJson) {
  const std::string full = R"({"camera": {"eye": [0, 1, 5], "look_at": [0, 1, 0], "fov_y": 45},
    "image": {"width": 16, "height": 16},
    "materials": {"m": {"diffuse": [0.8, 0.2, 0.2], "reflect": 0.5}},
    "meshes": [{"shape": "box", "material": "m"}],
    "lights": [{"position": [2, 4, 3]}], "background": [0.1, 0.1, 0.15]})";
  EXPECT_NO_THROW(parse_json_scene(full, ".", "full.json"));
  for (size_t n = 0; n < full.size(); ++n)
    EXPECT_THROW(parse_json_scene(full.substr(0, n), ".", "cut.json"), SceneError) << n;
}

TEST(BadInput, EmptyScene) {
  Scene s = parse_json_scene("{}", ".", "empty.json");
  EXPECT_EQ(s.triangle_count(), 0u);
  EXPECT_NO_THROW(s.validate());
  Grid g = build_grid(s, 0);
  EXPECT_TRUE(g.empty());
  EXPECT_EQ(g.voxels.size(), 1u);
}

}  // namespace
}  // namespace rt
