// Small vector helpers shared by the generators and the mesher.
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace sylva {

// Every component is finite (no NaN, no infinity).
inline bool finite3(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// A unit vector perpendicular to the unit vector t: t's own plane with the x axis (the z axis when
// t is near x), so the same t always gives the same vector (a branch frame's start, a fallback side).
inline glm::vec3 any_perpendicular(const glm::vec3& t) {
  const glm::vec3 a = std::abs(t.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 0, 1);
  return glm::normalize(glm::cross(glm::cross(t, a), t));
}

// Rodrigues' rotation of v by the rotation vector rv (axis * angle).
inline glm::vec3 rotate_by(const glm::vec3& v, const glm::vec3& rv) {
  const float a = glm::length(rv);
  if (!(a > 1e-12f)) return v;
  const glm::vec3 k = rv / a;
  const float c = std::cos(a), s = std::sin(a);
  return v * c + glm::cross(k, v) * s + k * glm::dot(k, v) * (1 - c);
}

// The bytes a vector's contents take (what a copy of it allocates), for memory accounting.
template <class T>
size_t vec_bytes(const std::vector<T>& v) {
  return v.size() * sizeof(T);
}

}  // namespace sylva
