// Foliage clumping: leaves gather on the outer shoots of each limb mass, so a crown
// breaks into clumps with gaps between them instead of an even fill.
#pragma once

#include <cstdint>
#include <vector>

#include "generators/skeleton.h"

namespace sylva {

struct clump_settings {
  float clumping = 0;      // 0: even (the result is all ones); 1: only the clumps' outer shells
  float size = 1.2f;       // metres: a subtree whose box is at most this far from its centre is one limb mass
  float variation = 0.3f;  // relative, seeded density difference between limb masses
};

// Per node, the factor on its internode's leaf count. `weight[i]` is the leaf-bearing length of
// node i's internode (0: it carries none). The limb masses are the largest subtrees whose box
// half-extent is at most `size`; within each, a leaf-bearing internode's factor follows its place
// in the mass: high in a shell near the mass's rim (more on the side facing out of the crown), low
// in the mass's interior and past its rim (the gaps between masses), times a seeded factor per
// mass. Internodes outside every mass (old limbs) get 0. The factors are normalised so the
// weighted mean is 1 (the leaf count stays about the same), then blended with 1 by `clumping`.
// O(n). With clumping 0 every factor is exactly 1.
std::vector<float> clump_density(const tree_skeleton& t, const std::vector<float>& weight, const clump_settings& s,
                                 uint64_t seed);

// The limb mass of every node (the index of its root node), or -1 for nodes outside every mass;
// what clump_density groups by.
std::vector<int32_t> limb_masses(const tree_skeleton& t, float size);

}  // namespace sylva
