// The orbit camera and the sun direction (render/gl/renderer.h).
#include "render/gl/renderer.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace sylva {

// ---------------------------------------------------------------- camera

void orbit_camera_rotate(orbit_camera& c, float dx, float dy) {
  c.yaw -= dx * 0.3f;
  c.pitch = std::clamp(c.pitch + dy * 0.3f, -89.0f, 89.0f);
}

void orbit_camera_pan(orbit_camera& c, float dx, float dy, int viewport_height) {
  glm::vec3 eye = camera_eye(c);
  glm::vec3 fwd = glm::normalize(c.target - eye);
  glm::vec3 right = glm::normalize(glm::cross(fwd, glm::vec3(0, 1, 0)));
  glm::vec3 up = glm::cross(right, fwd);
  float per_pixel = 2.0f * c.distance * std::tan(glm::radians(c.fov) * 0.5f) / float(std::max(viewport_height, 1));
  c.target += (-dx * right + dy * up) * per_pixel;
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
  const float tan_half = std::tan(glm::radians(c.fov) * 0.5f);
  for (int it = 0; it < 12; ++it) {
    const glm::vec3 eye = camera_eye(c);
    const glm::vec3 fwd = glm::normalize(c.target - eye);
    const glm::vec3 right = glm::normalize(glm::cross(fwd, glm::vec3(0, 1, 0)));
    const glm::vec3 up = glm::cross(right, fwd);
    glm::vec2 a(1e30f), b(-1e30f);
    bool behind = false;
    for (int i = 0; i < 8; ++i) {
      const glm::vec3 p((i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z);
      const float z = glm::dot(p - eye, fwd);
      if (z < 1e-3f * radius) { behind = true; break; }
      const glm::vec2 ndc(glm::dot(p - eye, right) / (z * tan_half * aspect), glm::dot(p - eye, up) / (z * tan_half));
      a = glm::min(a, ndc), b = glm::max(b, ndc);
    }
    if (behind) { c.distance *= 1.5f; continue; }
    const glm::vec2 mid = 0.5f * (a + b);
    c.target += right * (mid.x * tan_half * aspect * c.distance) + up * (mid.y * tan_half * c.distance);
    const float scale = std::max((b.y - a.y) / 1.7f, (b.x - a.x) / 1.9f);
    c.distance = std::clamp(c.distance * std::clamp(scale, 0.5f, 2.0f), 0.01f, 1e5f);
  }
}

glm::vec3 camera_eye(const orbit_camera& c) {
  float y = glm::radians(c.yaw), p = glm::radians(c.pitch);
  return c.target + c.distance * glm::vec3(std::sin(y) * std::cos(p), std::sin(p), std::cos(y) * std::cos(p));
}

glm::vec3 sun_direction(const render_params& p) {
  float a = glm::radians(p.sun_azimuth), e = glm::radians(p.sun_elevation);
  return glm::vec3(std::sin(a) * std::cos(e), std::sin(e), std::cos(a) * std::cos(e));
}

}  // namespace sylva
