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

// A rotation vector rv (axis * angle) as Rodrigues' formula uses it: the unit axis k and the
// angle's cosine and sine, worked out once for a rotation applied to many vectors.
struct rotation_terms {
  glm::vec3 k{0};
  float c = 1, s = 0;
  bool turns = false;   // false: rv shorter than 1e-12, which leaves every vector as it is
  rotation_terms inverse() const { return {-k, c, s, turns}; }   // rotation_terms_of(-rv), bit for bit
};
inline rotation_terms rotation_terms_of(const glm::vec3& rv) {
  const float a = glm::length(rv);
  if (!(a > 1e-12f)) return {};
  return {rv / a, std::cos(a), std::sin(a), true};
}
// Rodrigues' rotation of v by the rotation r.
inline glm::vec3 rotate_by(const glm::vec3& v, const rotation_terms& r) {
  if (!r.turns) return v;
  return v * r.c + glm::cross(r.k, v) * r.s + r.k * glm::dot(r.k, v) * (1 - r.c);
}
inline glm::vec3 rotate_by(const glm::vec3& v, const glm::vec3& rv) { return rotate_by(v, rotation_terms_of(rv)); }

// The bytes a vector's contents take (what a copy of it allocates), for memory accounting.
template <class T>
size_t vec_bytes(const std::vector<T>& v) {
  return v.size() * sizeof(T);
}

}  // namespace sylva
