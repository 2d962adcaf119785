// Cones and fruit: a species' seed cones, samaras or nuts as cards on the tips of its shoots
// (render/assets/archetype_fruits.cpp draws them). They carry a species' identity in a close view
// (a spruce's hanging cones against a fir's upright ones) and are off unless a preset asks.
#pragma once

#include <cstdint>
#include <vector>

#include "generators/archetypes.h"
#include "generators/params.h"
#include "generators/skeleton.h"

namespace sylva {

// How a fruit's card sits on its shoot tip.
enum class fruit_pose : int { hanging = 0, upright };
inline constexpr const char* fruit_pose_names[] = {"hanging", "upright", nullptr};

// Where on the branch a fruit sits: on a shoot's tip (cones, samaras, nuts), or in the axil where
// a branch leaves its parent (a coconut palm's bunches hang among the bases of its fronds: the
// inflorescences are axillary; Riffle & Craft 2003).
enum class fruit_site : int { tips = 0, axils };
inline constexpr const char* fruit_site_names[] = {"tips", "axils", nullptr};

struct fruit_params {
  int count = 0;              // fruits on the tree (0: none); on as many shoot tips, at most one each
  leaf_archetype archetype = leaf_archetype::cone_hanging;
  float size = 0.15f;         // card side, metres
  float size_jitter = 0.15f;  // relative random variation of the size
  fruit_pose pose = fruit_pose::hanging;
  fruit_site site = fruit_site::tips;
  float reach = 0;            // axils: metres out along the branch from the junction
  float tilt = 15;            // degrees a fruit leans at random away from straight down (up)
  float crown_top = 1.0f;     // only tips in this top share of the tree's height
  int min_order = 1;          // only tips (branches, for axils) of at least this branch order
  int max_order = 8;          // ... and at most this one (spruce: the laterals' ends, not the hanging branchlets')
  int cards = 2;              // crossed cards per fruit, so it shows from every side
  bool operator==(const fruit_params&) const = default;
};

template <params_of<fruit_params> P, class V>
void visit_params(P& p, V&& visitor) {
  auto v = declare_class(visitor, param_remesh);   // mesh_tree places the fruit on the kept skeleton
  v(p.count, param_info{"fruit_count", "Fruit count", "", 0, 2000, "Cones or fruit on the tree, each on its own shoot tip (0: none); more keeps the ones already there", 0, "Cones and fruit"});
  v(p.archetype, param_info{"fruit_archetype", "Fruit card", "", 0, leaf_archetype_count - 1, "Card of the cones or fruit: cone_hanging (spruce), cone_upright (fir), samaras (maple), hazelnuts (hazel), cone_ovoid (pine), beechnuts (beech), coconuts (palm), ash_keys (ash), cone_barrel (cedar), acorns (oak), cypress_cones (cypress); drawn in their own colours, not the leaf tint", 0, nullptr, leaf_archetype_names});
  v(p.size, param_info{"fruit_size", "Fruit size", "", 0.01f, 1, "Card side in metres (a cone fills about 85 % of it)", param_log});
  v(p.size_jitter, param_info{"fruit_size_jitter", "Fruit size variation", "", 0, 1, "Relative random variation of the fruit size"});
  v(p.pose, param_info{"fruit_pose", "Fruit pose", "", 0, 1, "hanging: from the tip, down (spruce cones, samaras, nuts); upright: standing on the shoot (fir and cedar cones)", 0, nullptr, fruit_pose_names});
  v(p.site, param_info{"fruit_site", "Fruit site", "", 0, 1, "tips: on shoot tips (cones, samaras, nuts); axils: where a branch of the order range leaves its parent (a coconut palm's bunches among its frond bases)", 0, nullptr, fruit_site_names});
  v(p.reach, param_info{"fruit_reach", "Axil reach", "", 0, 2, "axils: how far out along the branch from where it leaves its parent the fruit hangs, in metres (a palm's bunches clear its crownshaft)"});
  v(p.tilt, param_info{"fruit_tilt", "Fruit tilt", "", 0, 60, "Degrees each fruit leans at random from straight down (hanging) or up (upright)", param_degrees});
  v(p.crown_top, param_info{"fruit_crown_top", "Fruiting crown", "", 0.05f, 1, "Only shoot tips in this top share of the tree's height bear fruit (fir cones: the top of the crown)"});
  v(p.min_order, param_info{"fruit_min_order", "Fruit order threshold", "", 0, 8, "Only tips of branches of at least this order bear fruit"});
  v(p.max_order, param_info{"fruit_max_order", "Fruit order limit", "", 0, 8, "Only tips of branches of at most this order bear fruit (a spruce's cones hang from its laterals' ends, not from the branchlets hanging below them)"});
  v(p.cards, param_info{"fruit_cards", "Cards per fruit", "", 1, 3, "Crossed cards per fruit: 2 or 3 show it from every side, 1 is cheapest", param_advanced});
}

// The editor shows the fruit sliders only once some fruit is asked for, and the axil reach only
// for fruit in the axils.
inline bool param_relevant(const fruit_params& p, const void* field, const param_info&) {
  if (field == &p.reach) return p.count > 0 && p.site == fruit_site::axils;   // tips ignore it
  return field == &p.count || p.count > 0;
}

// Appends the fruit to `out` (leaf cards with their archetype set): `p.count` sites, chosen by a
// seeded hash of each site's node so the choice does not depend on the order of the nodes and a
// higher count keeps the fruit already placed. A tip is a node alive at the last step with no
// living child; an axil is the first node of a branch (its parent has a lower order), and its
// fruit hangs `p.reach` metres out along the branch from the junction (at most to its tip). Each
// fruit appears at the last step (the mature tree bears them) and is shed with its node. Fruit
// below `ground` is dropped.
void place_fruits(const tree_skeleton& t, const fruit_params& p, uint64_t seed, float ground, std::vector<leaf>& out);

}  // namespace sylva
