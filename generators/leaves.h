// Shared leaf placement: leaves on the tips of the tree, for generators without a leaf model.
#pragma once

#include <vector>

#include "generators/archetypes.h"
#include "generators/params.h"
#include "generators/skeleton.h"

namespace sylva {

struct leaf_params {
  float density = 4;        // leaves per tip node (fractional part: probability of one more)
  float size = 0.15f;       // blade length, metres
  float size_jitter = 0.3f; // relative random variation of the size
  int min_order = 1;        // only nodes of at least this branch order carry leaves
  float spread = 50;        // degrees between a leaf and its twig
  leaf_archetype archetype = leaf_archetype::ovate;  // which card every placed leaf uses
  bool operator==(const leaf_params&) const = default;
};

template <params_of<leaf_params> P, class V>
void visit_params(P& p, V&& v) {
  v(p.density, param_info{"leaf_density", "Leaf density", "", 0, 32, "Leaves per tip node", 0, "Leaves"});
  v(p.size, param_info{"leaf_size", "Leaf size", "", 0.005f, 2, "Leaf blade length in metres", param_log});
  v(p.size_jitter, param_info{"leaf_size_jitter", "Size variation", "", 0, 1, "Relative random variation of leaf size"});
  v(p.min_order, param_info{"leaf_min_order", "Leaf order threshold", "", 0, 8, "Only branches of at least this order carry leaves"});
  v(p.spread, param_info{"leaf_spread", "Leaf angle", "", 0, 90, "Angle between a leaf and its twig", param_degrees});
  v(p.archetype, param_info{"leaf_archetype", "Leaf archetype", "", 0, 8, "Procedural leaf card: ovate, lobed (oak), palmate (maple), pinnate (ash), pine needles, flat spray (spruce), scale spray (cypress), palm frond, twig cluster", 0, nullptr, leaf_archetype_names});
}

// Leaves on every node that is a tip at some step: a leaf is born with its node and dies when the
// node gets its first child (or is shed), so playback shows foliage on the growing tips.
std::vector<leaf> place_tip_leaves(const tree_skeleton& t, const leaf_params& p, uint64_t seed);

}  // namespace sylva
