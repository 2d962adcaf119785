// The camera keys and the view gizmo: each named view puts the eye on its own side of the target.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "app/editor/view_gizmo.h"

using namespace sylva;

TEST(ViewGizmo, EachViewLooksAlongItsAxis) {
  const struct { view_axis a; glm::vec3 eye_side; } cases[] = {
      {view_axis::front, {0, 0, 1}}, {view_axis::back, {0, 0, -1}}, {view_axis::right, {1, 0, 0}},
      {view_axis::left, {-1, 0, 0}}, {view_axis::top, {0, 1, 0}},   {view_axis::bottom, {0, -1, 0}}};
  for (const auto& c : cases) {
    orbit_camera cam;
    cam.target = {1, 3, -2}, cam.distance = 11, cam.yaw = 47, cam.pitch = 21;
    snap_view(cam, c.a);
    const glm::vec3 d = (camera_eye(cam) - cam.target) / cam.distance;
    EXPECT_GT(glm::dot(d, c.eye_side), 0.999f) << view_axis_name(c.a);
    EXPECT_FLOAT_EQ(cam.distance, 11);   // the framing stays
    EXPECT_EQ(cam.target, glm::vec3(1, 3, -2));
  }
}
