// Picking a branch under the mouse: a ray against the bark tubes of the tree at a step.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "generators/skeleton.h"

namespace sylva {

struct pick_hit {
  int32_t node = -1;   // the internode parent[node] → node; -1: nothing hit
  float distance = 0;  // along the ray, metres
};

// The internode whose tube (a capsule of the larger of its two radii) the ray meets first, among
// the nodes alive at `step`. `radii` holds the radii at that step (radii_at_step). `slack` widens
// every tube by slack·distance, so that a twig a pixel wide can still be clicked (pass the angle of
// a few pixels in radians). `dir` need not be unit length. O(n): ~1 ms for 100,000 nodes.
pick_hit pick_branch(const tree_skeleton& t, const std::vector<float>& radii, int step, const glm::vec3& origin,
                     const glm::vec3& dir, float slack = 0);

}  // namespace sylva
