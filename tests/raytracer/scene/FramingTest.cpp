// The framing camera's rules (Framing.h, docs/camera.md): the up axis from the box's extent,
// the room rule (an open side is looked through from outside, a closed room from inside), and
// the light off the view axis.
#include <gtest/gtest.h>

#include "rill/rt/scene/Framing.h"

namespace rt {
namespace {

int up_of(float x, float y, float z) {
  return resolve_up_axis(UpAxis::Auto, glm::vec3(0.0f), glm::vec3(x, y, z));
}

// The extents of the shared test meshes (shared/meshes, measured once; the tests do not read
// them): only the Nefertiti scan stands in z.
TEST(Framing, AutoUpAxisFromTheExtent) {
  EXPECT_EQ(up_of(238.686f, 362.534f, 494.605f), 2);  // nefertiti: z up
  EXPECT_EQ(up_of(0.36f, 0.303f, 0.892f), 1);         // beetle: a car, longest in z, thin in y
  EXPECT_EQ(up_of(0.943f, 1.69f, 1.718f), 1);         // spot
  EXPECT_EQ(up_of(10.444f, 6.397f, 3.403f), 1);       // cow
  EXPECT_EQ(up_of(0.473f, 0.84f, 0.273f), 1);         // homer
  EXPECT_EQ(up_of(556.0f, 548.8f, 559.2f), 1);        // cornell box
  EXPECT_EQ(resolve_up_axis(UpAxis::X, glm::vec3(0.0f), glm::vec3(1.0f)), 0);
  EXPECT_THROW(parse_up_axis("w"), std::invalid_argument);
}

// Walls of the box [0, 1]^3 as two triangles each, facing inwards; `skip` leaves one out
// (axis 2, low side: the -z wall).
Scene walls(bool inward, bool open_front) {
  Scene s;
  const int m = s.add_material(Material{});
  for (int k = 0; k < 3; ++k)
    for (int side = 0; side < 2; ++side) {
      if (open_front && k == 2 && side == 0) continue;
      const int u = (k + 1) % 3, v = (k + 2) % 3;
      glm::vec3 p[4];
      const float ab[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
      for (int c = 0; c < 4; ++c) {
        p[c][k] = static_cast<float>(side);
        p[c][u] = ab[c][0];
        p[c][v] = ab[c][1];
      }
      // Counterclockwise about +k: faces inwards on the low side.
      const bool flip = (side == 0) != inward;
      if (flip) std::swap(p[1], p[3]);
      s.add_triangle(p[0], p[1], p[2], m);
      s.add_triangle(p[0], p[2], p[3], m);
    }
  return s;
}

TEST(Framing, RoomRule) {
  EXPECT_TRUE(is_room(walls(true, false)));
  EXPECT_FALSE(is_room(walls(false, false)));
  // Open at -z (as the Cornell box's OBJ): looked into from outside the opening, along +z.
  const Camera open = framing_camera(walls(true, true), 64, 64);
  EXPECT_LT(open.eye.z, 0.0f);
  EXPECT_FLOAT_EQ(open.eye.x, 0.5f);
  EXPECT_FLOAT_EQ(open.eye.y, 0.5f);
  // Closed: from just inside the +z wall.
  const Camera closed = framing_camera(walls(true, false), 64, 64);
  EXPECT_GT(closed.eye.z, 0.5f);
  EXPECT_LT(closed.eye.z, 1.0f);
  // An object: from outside, in front and above.
  const Camera object = framing_camera(walls(false, false), 64, 64);
  EXPECT_GT(object.eye.z, 1.0f);
  EXPECT_GT(object.eye.y, 0.5f);
}

// A wider image brings the eye closer to a wide box (the fit is the image's, not a square's).
TEST(Framing, FitsTheAspect) {
  Scene s = walls(false, false);
  for (glm::vec3& p : s.positions) p.x *= 4.0f;
  const float square = framing_camera(s, 64, 64).eye.z, wide = framing_camera(s, 128, 64).eye.z;
  EXPECT_LT(wide, square);
}

// The light is off the view axis: above the eye, and to its left.
TEST(Framing, LightOffTheViewAxis) {
  Camera c;  // eye (0, 0, 5) looking at the origin, y up
  const glm::vec3 l = framing_light_position(c);
  EXPECT_FLOAT_EQ(l.y, 2.5f);
  EXPECT_FLOAT_EQ(l.x, -1.75f);
  EXPECT_FLOAT_EQ(l.z, 5.0f);
}

}  // namespace
}  // namespace rt
