// The camera's rays in the kernels (docs/camera.md): the camera frame in uniforms, and the
// ray through a pixel as a DSL function, in float32 and in the documented order.
#pragma once

#include <rill/rill.h>

#include <optional>
#include <vector>

#include "rill/rt/kernel/Records.h"
#include "rill/rt/scene/Camera.h"

namespace rt {

struct CameraRays {
  rill::Uniform<Float3> eye{glm::vec3(0.0f), "eye"}, forward{glm::vec3(0.0f), "forward"},
      right{glm::vec3(0.0f), "right"}, up{glm::vec3(0.0f), "true_up"};
  rill::Uniform<Float> tan_half{0.0f, "tan_half"}, aspect{1.0f, "aspect"};
  rill::Uniform<Float2> size{glm::vec2(1.0f), "size"}, offset{glm::vec2(0.5f), "sample_offset"};
  // Where the launch's pixel (0, 0) lies in the image: a render of a window of the image
  // (RenderSettings::window) launches over the window alone. Added to the launch coordinate
  // as integers before anything else, so a pixel's ray has the same bits in every window.
  rill::Uniform<Int2> origin{glm::ivec2(0), "pixel_origin"};
  // The image's pixels whose rays may meet the scene, [first, end), and within it the tiles
  // that may (TileMask, scene/Camera.h): tile (x >> tile_shift, y >> tile_shift) at
  // seeing_tiles[row * tile_columns + column]. The whole image until set() is given boxes.
  rill::Uniform<Int2> seeing_first{glm::ivec2(0), "seeing_first"},
      seeing_end{glm::ivec2(1 << 30), "seeing_end"};
  rill::Uniform<Int> tile_shift{30, "tile_shift"}, tile_columns{1, "tile_columns"};
  rill::Array<Int> seeing_tiles{1, "seeing_tiles"};
  // The pixels that may see the moving triangles' box (a dynamic scene's BVH), apart from the
  // tiles: that box changes from frame to frame, the tiles only with the view.
  rill::Uniform<Int2> moving_first{glm::ivec2(0), "moving_first"},
      moving_end{glm::ivec2(0), "moving_end"};
  // The thin lens (kind ThinLens): its radius R and k = R / focus_distance; the lens point's
  // Philox key (the scene's seed) and the launch's sample index within the pixel, set with the
  // sample offset. (The pinhole's kernels read none of these.)
  rill::Uniform<Float> lens_radius{0.0f, "lens_radius"}, lens_k{0.0f, "lens_k"};
  rill::Uniform<Int> lens_seed{0, "lens_seed"}, lens_sample{0, "lens_sample"};
  // A kernel that runs several samples of its pixel in one launch (the path megakernel's path
  // regeneration) sets these while it is captured: its own variables then stand for the
  // sample offset and the lens sample, the same values as those uniforms would hold. Null:
  // the uniforms (every other kernel's source stays as it was).
  const Float2* sample_offset_var = nullptr;
  const Int* lens_sample_var = nullptr;
  // The rays the kernels generate, fixed when they are captured (Features::camera).
  CameraKind kind = CameraKind::Pinhole;

  CameraRays();
  // The camera for an image of width x height pixels, launched from pixel origin on. With
  // boxes, the pixels that see none of them are marked (may_see_scene), else every pixel
  // sees.
  // A moving box adds the rectangle of pixels that may see it.
  void set(const Camera& camera, int width, int height, glm::ivec2 origin = glm::ivec2(0),
           const std::vector<Aabb>* boxes = nullptr, const Aabb* moving = nullptr);
  // The unit direction through the launch's pixel pix (the image's pixel pix + origin) at the
  // sample offset.
  Float3 direction(const Int2& pix) const;
  // The camera ray of the launch's pixel pix at the sample offset (and, for the thin lens, the
  // sample's lens point): sets ray.d, and ray.o where the kind's rays do not start at the eye
  // (the pinhole's caller has set it to eye).
  void aim(Ray& ray, const Int2& pix) const;
  // The thin lens's point on the unit disk for the image's pixel pix (docs/camera.md).
  Float2 lens_point(const Int2& pix) const;
  // Whether the launch's pixel pix may see anything: false only where its camera rays, at
  // every sample offset, miss every box given to set(). The moving box's rectangle is tested
  // only with `moving` (the kernel of a dynamic scene).
  Bool may_see_scene(const Int2& pix, bool moving) const;

 private:
  void use(TileMask mask);
  // The screen point (sx, sy) of the image's pixel pix at the sample offset.
  struct ScreenPoint {
    Float x, y;
  };
  ScreenPoint screen(const Int2& pix) const;
  TileMask mask_;  // what the uniforms and seeing_tiles hold now
  // The view and boxes mask_ was made for, if it was made from boxes.
  std::optional<CameraFrame> seen_from_;
  std::vector<Aabb> seen_boxes_;
};

}  // namespace rt
