// The orbit camera and its maths, in one place: the eye, the view and projection matrices the
// renderer draws with, the ray through a pixel (picking) and the pixel of a point (overlays drawn
// over the view). The renderer (render/gl), the editor's picking and overlays (app/) and the
// tests all use these, so what is drawn, clicked and outlined agree. CPU only.
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace sylva {

struct orbit_camera {
  glm::vec3 target{0, 2, 0};
  float distance = 8;
  float yaw = 35;      // degrees around +Y: a three-quarter view
  float pitch = 3;     // degrees above the horizon: the eye a little below the crown
  float fov = 45;      // vertical, degrees
};

// Mouse moves: rotate and pan by pixels, zoom by wheel clicks.
void orbit_camera_rotate(orbit_camera& c, float dx_pixels, float dy_pixels);
void orbit_camera_pan(orbit_camera& c, float dx_pixels, float dy_pixels, int viewport_height);
void orbit_camera_zoom(orbit_camera& c, float wheel);
// Frames the box from the current direction so that it fills ~75% of the view's height (or 90% of
// its width when that is tighter) for a view of width / height `aspect`.
void frame_camera(orbit_camera& c, const glm::vec3& bounds_min, const glm::vec3& bounds_max, float aspect = 16.0f / 9.0f);

// Yaw 0 puts the eye on +Z (the front), yaw 90 on +X (the right side).
glm::vec3 camera_eye(const orbit_camera& c);
// The eye and its unit axes: forward (toward the target), right and up (+Y stays up).
struct camera_basis {
  glm::vec3 eye, forward, right, up;
};
camera_basis camera_basis_of(const orbit_camera& c);
float camera_tan_half_fov(const orbit_camera& c);   // tan(fov / 2): the view's half height at distance 1

// The matrices the renderer draws with (right-handed, GL clip space).
glm::mat4 camera_view(const orbit_camera& c);
glm::mat4 camera_projection(const orbit_camera& c, float aspect, float near_plane, float far_plane);

// A rectangle of the window in pixels (origin top left, y down): the 3D view, or a half of it.
struct view_rect {
  float x = 0, y = 0, w = 1, h = 1;
};
// The ray through window pixel (mx, my) of the view `v` (the renderer's projection at v's aspect).
void view_ray(const orbit_camera& cam, const view_rect& v, float mx, float my, glm::vec3& origin, glm::vec3& dir);
// The window pixel where world point `p` is drawn; false when it is behind the eye. `basis` is
// camera_basis_of(cam), computed once for the many points of an outline.
bool view_pixel(const orbit_camera& cam, const camera_basis& basis, const view_rect& v, const glm::vec3& p, glm::vec2& out);
// The angle (radians at distance 1) one pixel of the view spans vertically.
float view_pixel_angle(const orbit_camera& cam, const view_rect& v);

}  // namespace sylva
