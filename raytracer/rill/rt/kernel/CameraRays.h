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

  void set(const Camera& camera, int width, int height);
  // The unit direction through pixel pix at the sample offset.
  Float3 direction(const Int2& pix) const;
};

}  // namespace rt
