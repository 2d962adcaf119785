// Deterministic noise for the mesher: a hash of a node's position bits and a salt.
#pragma once

#include <cstdint>
#include <cstring>

#include <glm/vec3.hpp>

#include "generators/skeleton.h"

namespace sylva {

// Noise that is deterministic from the skeleton (its seed) and follows a node whatever its index
// (skeleton_at_step renumbers nodes).
inline uint64_t position_hash(const glm::vec3& p, uint64_t salt) {
  uint32_t b[3];
  std::memcpy(b, &p, sizeof b);
  rng r(salt ^ (uint64_t(b[0]) << 32 | b[1]) ^ (uint64_t(b[2]) * 0xD1B54A32D192ED03ull));
  return r.next();
}

}  // namespace sylva
