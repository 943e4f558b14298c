// The render strategy interface (strategy/RenderStrategy.h) from outside the library: a
// program registers its own strategy by name and renders with it through the Tracer, and the
// built-in ones are found by name.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <stdexcept>

#include "rill/rt/Tracer.h"
#include "rill/rt/accel/Grid.h"
#include "rill/rt/kernel/DeviceScene.h"
#include "rill/rt/strategy/RenderStrategy.h"

namespace rt {
namespace {

using namespace rill;

// A strategy that paints every pixel one colour, as a program outside the library would
// write one: its own kernel, its samples through the film, the AOVs of a miss.
class FlatStrategy final : public RenderStrategy {
 public:
  explicit FlatStrategy(DeviceScene&) {
    program_ = rill::program("test_flat_strategy", [] {
      Output<Float3> color("color");
      Output<Float> depth("depth");
      Output<Int> prim("prim");
      Output<Float3> normal("normal");
      color = Float3(0.25f, 0.5f, 0.75f);
      depth = as_float(Int(0x7f800000));
      prim = -1;
      normal = Float3(0.0f);
    });
  }
  void render(const Frame& f, RenderResult& r) override {
    const RenderSettings& rs = f.settings;
    r.backend = rs.backend;
    r.width = f.width;
    r.height = f.height;
    CompileOptions opt;
    opt.accuracy = rs.accuracy;
    Kernel k = compile(program_, rs.backend, opt);
    Stream<Float3> color(f.width, f.height), normal(f.width, f.height);
    Stream<Float> depth(f.width, f.height);
    Stream<Int> prim(f.width, f.height);
    k.outputs(color, depth, prim, normal);
    f.film.begin(rs.backend, rs.accuracy, f.width, f.height, f.spp);
    for (int s = 0; s < f.spp; ++s) {
      k.execute();
      ++r.launches;
      if (s == 0) f.film.read_aovs(AovStreams{depth, prim, normal}, rs.outputs, r);
      f.film.add_sample(color, s);
    }
    f.film.finish(rs.outputs, r);
  }

 private:
  Program program_;
};

TEST(Strategies, TheBuiltInOnesAreRegisteredByName) {
  const std::vector<std::string> names = strategy_names();
  ASSERT_GE(names.size(), 3u);
  EXPECT_EQ(names[0], "megakernel");
  EXPECT_EQ(names[1], "multipass");
  EXPECT_EQ(names[2], "wavefront");
  EXPECT_EQ(parse_strategy("multipass"), Strategy::Multipass);
  EXPECT_EQ(parse_strategy("wavefront"), Strategy::Wavefront);
  EXPECT_EQ(RenderSettings{}.strategy, Strategy::Megakernel);
  try {
    parse_strategy("quantum");
    ADD_FAILURE() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(
        std::string(e.what()).rfind("--strategy expects megakernel or multipass or wavefront", 0),
        0u)
        << e.what();
  }
}

TEST(Strategies, AProgramRegistersItsOwn) {
  register_strategy("test_flat", [](DeviceScene& s) { return std::make_unique<FlatStrategy>(s); });
  EXPECT_THROW(register_strategy("test_flat",
                                 [](DeviceScene& s) { return std::make_unique<FlatStrategy>(s); }),
               std::invalid_argument);
  EXPECT_THROW(register_strategy("", nullptr), std::invalid_argument);
  const std::vector<std::string> names = strategy_names();
  EXPECT_NE(std::find(names.begin(), names.end(), "test_flat"), names.end());

  Scene scene = builtin_scene("cornell");
  Tracer tracer(scene, build_grid_for(scene));
  RenderSettings rs;
  rs.outputs.depth = rs.outputs.prim = rs.outputs.normal = true;  // the AOVs compared
  rs.width = 12;
  rs.height = 8;
  rs.spp = 2;
  rs.strategy = parse_strategy("test_flat");
  const RenderResult flat = tracer.render(rs, scene.camera);
  ASSERT_EQ(flat.color.size(), 96u);
  for (size_t p = 0; p < flat.color.size(); ++p) {
    EXPECT_EQ(flat.color[p], glm::vec3(0.25f, 0.5f, 0.75f)) << p;  // the mean of two samples
    EXPECT_EQ(flat.prim[p], -1) << p;
  }
  EXPECT_EQ(flat.launches, 2);
  // The same tracer still renders with the built-in strategy.
  rs.strategy = Strategy::Megakernel;
  const RenderResult lit = tracer.render(rs, scene.camera);
  EXPECT_NE(lit.color, flat.color);
  // A strategy no one registered is an error naming the ones there are.
  rs.strategy = Strategy{"nope"};
  EXPECT_THROW(tracer.render(rs, scene.camera), std::invalid_argument);
}

}  // namespace
}  // namespace rt
