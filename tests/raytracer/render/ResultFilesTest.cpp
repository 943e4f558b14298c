// A RenderResult written to files from a program (render/ResultFiles.h), as docs/raytracer.md
// ("In a program: render, then write the image") shows: the PNG holds the 8-bit image, the
// same bytes whether the render encoded it or only read back the colour; the EXR holds the
// colour and each AOV read back, bit for bit; a render without what a file needs is an error
// naming the file.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string>

#include "RunCommand.h"
#include "TestUtil.h"
#include "rill/rt/Tracer.h"
#include "rill/rt/accel/Grid.h"
#include "rill/rt/render/ResultFiles.h"
#include "rill/rt/scene/ExrImage.h"
#include "rill/rt/scene/Image.h"
#include "rill/rt/scene/Texture.h"

namespace rt {
namespace {

using testing::error_of;
using testing::TempDir;

// Thesis scene A at 12 x 8 pixels (RenderSettings' size left at 0: the scene's).
class ResultFiles : public ::testing::Test {
 protected:
  ResultFiles() : scene_(builtin_scene("thesis-a")) {
    scene_.width = 12;
    scene_.height = 8;
    grid_ = build_grid_for(scene_);
    tracer_ = std::make_unique<Tracer>(scene_, grid_);
  }
  Scene scene_;
  Grid grid_;
  std::unique_ptr<Tracer> tracer_;
  TempDir dir_;
};

TEST_F(ResultFiles, ThePngIsThe8BitImageEitherWay) {
  RenderSettings rs;
  rs.outputs.rgb8 = true;
  const RenderResult r = tracer_->render(rs, scene_.camera);
  ASSERT_EQ(r.rgb8.size(), 12u * 8u * 3u);
  write_png(dir_.path("device.png"), r);
  // The pixels read back as data (no sRGB decoding): the render's bytes.
  const Texture t = load_png_texture(dir_.path("device.png"), /*srgb=*/false);
  ASSERT_EQ(t.width, 12);
  ASSERT_EQ(t.height, 8);
  for (size_t i = 0; i < t.texels.size(); ++i)
    for (int c = 0; c < 3; ++c)
      ASSERT_EQ(std::lround(t.texels[i][c] * 255.0f), r.rgb8[3 * i + static_cast<size_t>(c)])
          << "pixel " << i;
  // Only the colour read back: encoded on the host, the same file.
  RenderSettings colour_only;
  colour_only.outputs = {.color = true, .depth = false, .prim = false, .normal = false};
  const RenderResult c = tracer_->render(colour_only, scene_.camera);
  ASSERT_TRUE(c.rgb8.empty());
  write_png(dir_.path("host.png"), c);
  EXPECT_EQ(testing::read_text(dir_.path("host.png")), testing::read_text(dir_.path("device.png")));
}

TEST_F(ResultFiles, TheExrHoldsTheColourAndEveryAovReadBack) {
  RenderSettings aovs;
  aovs.outputs = {.color = true, .depth = true, .prim = true, .normal = true};
  const RenderResult r = tracer_->render(aovs, scene_.camera);
  write_exr(dir_.path("all.exr"), r);
  const ExrImage e = read_exr(dir_.path("all.exr"));
  ASSERT_EQ(e.width, 12);
  ASSERT_EQ(e.height, 8);
  ASSERT_EQ(e.channels.size(), 8u);  // B G N.X N.Y N.Z R Z prim
  auto same = [](float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; };
  for (size_t p = 0; p < r.color.size(); ++p) {
    for (int c = 0; c < 3; ++c) {
      ASSERT_TRUE(same(e.find(std::string(1, "RGB"[c]))->floats[p], r.color[p][c])) << p;
      ASSERT_TRUE(same(e.find(std::string("N.") + "XYZ"[c])->floats[p], r.normal[p][c])) << p;
    }
    ASSERT_TRUE(same(e.find("Z")->floats[p], r.depth[p])) << p;
    ASSERT_EQ(e.find("prim")->uints[p], static_cast<uint32_t>(r.prim[p])) << p;
  }
  // The colour alone: R, G and B.
  RenderSettings colour_only;
  colour_only.outputs = {.color = true, .depth = false, .prim = false, .normal = false};
  write_exr(dir_.path("rgb.exr"), tracer_->render(colour_only, scene_.camera));
  EXPECT_EQ(read_exr(dir_.path("rgb.exr")).channels.size(), 3u);
}

TEST_F(ResultFiles, ARenderWithoutWhatTheFileNeedsIsAnError) {
  RenderSettings depth_only;
  depth_only.outputs = {.color = false, .depth = true, .prim = false, .normal = false};
  const RenderResult r = tracer_->render(depth_only, scene_.camera);
  EXPECT_EQ(error_of([&] { write_png(dir_.path("x.png"), r); }),
            "cannot write " + dir_.path("x.png") +
                ": the render read back neither its colour nor its 8-bit image "
                "(RenderSettings::outputs.color or .rgb8)");
  EXPECT_EQ(error_of([&] { write_exr(dir_.path("x.exr"), r); }),
            "cannot write " + dir_.path("x.exr") +
                ": the render read back no colour (RenderSettings::outputs.color)");
  EXPECT_FALSE(std::filesystem::exists(dir_.path("x.png")));
  EXPECT_FALSE(std::filesystem::exists(dir_.path("x.exr")));
}

// rt::save picks the writer by the extension, in any case: the same bytes as write_png,
// write_pfm (the colour) and write_exr; the default outputs (the colour alone) are enough for
// each of the three.
TEST_F(ResultFiles, SaveChoosesTheFormatByTheExtension) {
  const RenderResult r = tracer_->render(RenderSettings{}, scene_.camera);
  save(r, dir_.path("a.png"));
  save(r, dir_.path("b.PNG"));
  write_png(dir_.path("ref.png"), r);
  EXPECT_EQ(testing::read_text(dir_.path("a.png")), testing::read_text(dir_.path("ref.png")));
  EXPECT_EQ(testing::read_text(dir_.path("b.PNG")), testing::read_text(dir_.path("ref.png")));
  save(r, dir_.path("a.pfm"));
  write_pfm(dir_.path("ref.pfm"), r.width, r.height, r.color);
  EXPECT_EQ(testing::read_text(dir_.path("a.pfm")), testing::read_text(dir_.path("ref.pfm")));
  save(r, dir_.path("a.exr"));
  write_exr(dir_.path("ref.exr"), r);
  EXPECT_EQ(testing::read_text(dir_.path("a.exr")), testing::read_text(dir_.path("ref.exr")));
  EXPECT_EQ(read_exr(dir_.path("a.exr")).channels.size(), 3u);
}

// An extension rt::save does not write, or none, is an error naming it and the formats, and
// nothing is written; a PFM of a render without the colour names the setting.
TEST_F(ResultFiles, SaveRefusesAnUnknownExtension) {
  const RenderResult r = tracer_->render(RenderSettings{}, scene_.camera);
  EXPECT_EQ(error_of([&] { save(r, dir_.path("x.jpg")); }),
            "cannot save " + dir_.path("x.jpg") +
                ": unknown extension .jpg (rt::save writes .png 8-bit sRGB, .pfm linear colour, "
                ".exr linear colour and the AOVs read back)");
  EXPECT_EQ(error_of([&] { save(r, dir_.path("x")); }),
            "cannot save " + dir_.path("x") +
                ": no extension (rt::save writes .png 8-bit sRGB, .pfm linear colour, .exr "
                "linear colour and the AOVs read back)");
  EXPECT_FALSE(std::filesystem::exists(dir_.path("x.jpg")));
  EXPECT_FALSE(std::filesystem::exists(dir_.path("x")));
  RenderSettings png_only;
  png_only.outputs = {.color = false, .rgb8 = true};
  const RenderResult p = tracer_->render(png_only, scene_.camera);
  EXPECT_EQ(error_of([&] { save(p, dir_.path("x.pfm")); }),
            "cannot write " + dir_.path("x.pfm") +
                ": the render read back no colour (RenderSettings::outputs.color)");
  EXPECT_FALSE(std::filesystem::exists(dir_.path("x.pfm")));
}

}  // namespace
}  // namespace rt
