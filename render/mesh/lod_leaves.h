// LOD leaves (render/mesh/lod.h): the final tree's leaves on a Morton order, grouped by octree
// cells within a card budget, and one merged card per group. Internal to build_lods.
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "render/mesh/lod_cards.h"
#include "render/mesh/mesh.h"

namespace sylva::lod_detail {

// Leaves of the final tree, sorted along a Morton curve over their box, so that the leaves of every
// octree cell are one contiguous run at every depth.
struct leaf_input {
  std::vector<leaf_instance> leaves;
  std::vector<uint32_t> code;     // 30-bit Morton code (10 bits per axis), sorted
  leaf_blade_shape blade;         // LOD0's leaves as geometry: the cards are baked from it
};

// The live leaves of `m`'s final step but cones and fruit, Morton-sorted.
leaf_input prepare_leaves(const tree_mesh& m);

// Groups of at most `cards` runs of leaves, each run one octree cell (or a single leaf).
std::vector<std::pair<size_t, size_t>> group_leaves(const leaf_input& in, size_t cards);

// One card per group into m.leaves (with its per-step table), textures baked into `baked`.
void emit_cards(const leaf_input& in, const std::vector<std::pair<size_t, size_t>>& groups, uint8_t card_texture,
                float area_gain, baked_card_textures& baked, tree_mesh& m);

}  // namespace sylva::lod_detail
