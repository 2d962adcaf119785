// The orbit camera and its maths (render/camera.h).
#include "render/camera.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace sylva {

void orbit_camera_rotate(orbit_camera& c, float dx, float dy) {
  c.yaw -= dx * 0.3f;
  c.pitch = std::clamp(c.pitch + dy * 0.3f, -89.0f, 89.0f);
}

void orbit_camera_pan(orbit_camera& c, float dx, float dy, int viewport_height) {
  const camera_basis b = camera_basis_of(c);
  float per_pixel = 2.0f * c.distance * camera_tan_half_fov(c) / float(std::max(viewport_height, 1));
  c.target += (-dx * b.right + dy * b.up) * per_pixel;
}

void orbit_camera_zoom(orbit_camera& c, float wheel) {
  c.distance = std::clamp(c.distance * std::pow(0.88f, wheel), 0.01f, 1e5f);
}

void frame_camera(orbit_camera& c, const glm::vec3& lo, const glm::vec3& hi, float aspect) {
  // Keeps the direction; moves the target and the distance until the box's projection spans 75% of
  // the view height (or 90% of its width, if that is tighter) and sits in the middle.
  aspect = std::isfinite(aspect) && aspect > 0.05f ? std::min(aspect, 20.0f) : 1.6f;
  const glm::vec3 center = 0.5f * (lo + hi);
  const float radius = std::max(glm::length(hi - lo) * 0.5f, 0.05f);
  c.target = center;
  c.distance = radius / std::sin(glm::radians(c.fov) * 0.5f) * 1.05f;
  const float tan_half = camera_tan_half_fov(c);
  for (int it = 0; it < 12; ++it) {
    const camera_basis f = camera_basis_of(c);
    glm::vec2 a(1e30f), b(-1e30f);
    bool behind = false;
    for (int i = 0; i < 8; ++i) {
      const glm::vec3 p((i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z);
      const float z = glm::dot(p - f.eye, f.forward);
      if (z < 1e-3f * radius) { behind = true; break; }
      const glm::vec2 ndc(glm::dot(p - f.eye, f.right) / (z * tan_half * aspect), glm::dot(p - f.eye, f.up) / (z * tan_half));
      a = glm::min(a, ndc), b = glm::max(b, ndc);
    }
    if (behind) { c.distance *= 1.5f; continue; }
    const glm::vec2 mid = 0.5f * (a + b);
    c.target += f.right * (mid.x * tan_half * aspect * c.distance) + f.up * (mid.y * tan_half * c.distance);
    const float scale = std::max((b.y - a.y) / 1.7f, (b.x - a.x) / 1.9f);
    c.distance = std::clamp(c.distance * std::clamp(scale, 0.5f, 2.0f), 0.01f, 1e5f);
  }
}

glm::vec3 camera_eye(const orbit_camera& c) {
  float y = glm::radians(c.yaw), p = glm::radians(c.pitch);
  return c.target + c.distance * glm::vec3(std::sin(y) * std::cos(p), std::sin(p), std::cos(y) * std::cos(p));
}

camera_basis camera_basis_of(const orbit_camera& c) {
  camera_basis b;
  b.eye = camera_eye(c);
  b.forward = glm::normalize(c.target - b.eye);
  b.right = glm::normalize(glm::cross(b.forward, glm::vec3(0, 1, 0)));
  b.up = glm::cross(b.right, b.forward);
  return b;
}

float camera_tan_half_fov(const orbit_camera& c) { return std::tan(glm::radians(c.fov) * 0.5f); }

glm::mat4 camera_view(const orbit_camera& c) { return glm::lookAt(camera_eye(c), c.target, glm::vec3(0, 1, 0)); }

glm::mat4 camera_projection(const orbit_camera& c, float aspect, float near_plane, float far_plane) {
  return glm::perspective(glm::radians(c.fov), aspect, near_plane, far_plane);
}

void view_ray(const orbit_camera& cam, const view_rect& v, float mx, float my, glm::vec3& origin, glm::vec3& dir) {
  const camera_basis f = camera_basis_of(cam);
  const float t = camera_tan_half_fov(cam), aspect = v.w / std::max(v.h, 1.0f);
  const float x = 2 * (mx - v.x) / std::max(v.w, 1.0f) - 1, y = 1 - 2 * (my - v.y) / std::max(v.h, 1.0f);
  origin = f.eye;
  dir = glm::normalize(f.forward + x * t * aspect * f.right + y * t * f.up);
}

bool view_pixel(const orbit_camera& cam, const camera_basis& f, const view_rect& v, const glm::vec3& p, glm::vec2& out) {
  const glm::vec3 d = p - f.eye;
  const float z = glm::dot(d, f.forward);
  if (z < 1e-3f) return false;
  const float t = camera_tan_half_fov(cam), aspect = v.w / v.h;
  const float x = glm::dot(d, f.right) / (z * t * aspect), y = glm::dot(d, f.up) / (z * t);
  out = glm::vec2(v.x + (x + 1) * 0.5f * v.w, v.y + (1 - y) * 0.5f * v.h);
  return true;
}

float view_pixel_angle(const orbit_camera& cam, const view_rect& v) { return 2 * camera_tan_half_fov(cam) / std::max(v.h, 1.0f); }

}  // namespace sylva
