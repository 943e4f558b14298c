// The camera's rays in the kernels (docs/camera.md): the camera frame in uniforms, and the
// ray through a pixel as a DSL function, in float32 and in the documented order.
#pragma once

#include <rill/rill.h>

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
  // The image's pixels whose rays may meet the scene, [first, end) (pixels_seeing_box): the
  // whole image until set_bounds() says otherwise.
  rill::Uniform<Int2> seeing_first{glm::ivec2(0), "seeing_first"},
      seeing_end{glm::ivec2(1 << 30), "seeing_end"};

  // The camera for an image of width x height pixels, launched from pixel origin on.
  // Sees the whole image: set_bounds() narrows that.
  void set(const Camera& camera, int width, int height, glm::ivec2 origin = glm::ivec2(0));
  // The box that holds everything a ray can hit (an empty one: lo > hi), for the camera of
  // the last set().
  void set_bounds(const glm::vec3& lo, const glm::vec3& hi);
  // The unit direction through the launch's pixel pix (the image's pixel pix + origin) at the
  // sample offset.
  Float3 direction(const Int2& pix) const;
  // Whether the launch's pixel pix may see anything: false only where its camera rays, at
  // every sample offset, miss the box of set_bounds().
  Bool may_see_scene(const Int2& pix) const;

 private:
  CameraFrame frame_;
};

}  // namespace rt
