// The foliage model shared by all four generators: leaves along every young shoot, in
// the species' arrangement, kept for the species' leaf retention; the older tip-only placement and
// each generator's own leaf rule stay available as modes.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

#include "generators/archetypes.h"
#include "generators/params.h"
#include "generators/skeleton.h"

namespace sylva {

enum class leaf_mode : int { shoots = 0, tips, generator };
inline constexpr const char* leaf_mode_names[] = {"shoots", "tips", "generator", nullptr};

// How leaves sit on a leaf node of a shoot (phyllotaxis).
enum class leaf_arrangement : int { alternate = 0, opposite, whorled };
inline constexpr const char* leaf_arrangement_names[] = {"alternate", "opposite", "whorled", nullptr};

// The archetypes whose leaves are needle shoots when blades are on (render/mesh/leaf_shoot.h).
inline bool archetype_is_needle_shoot(leaf_archetype a) {
  return a == leaf_archetype::needles || a == leaf_archetype::flat_spray || a == leaf_archetype::needle_tufts;
}

struct leaf_params {
  leaf_mode mode = leaf_mode::shoots;
  int retention = 1;          // steps a node keeps its leaves: age (step - born) <= retention
  int outer_internodes = 0;   // > 0: only nodes within this many internodes of a shoot tip
  float spacing = 0.06f;      // metres between leaf nodes along a shoot
  leaf_arrangement arrangement = leaf_arrangement::alternate;
  int whorl = 3;              // leaves per node when whorled
  float divergence = 137.5f;  // degrees between successive leaf nodes around the shoot
  float spread = 50;          // degrees between a leaf and its shoot (insertion angle)
  float droop = 0.25f;        // 0: leaves follow the insertion angle; 1: they hang straight down
  float density = 4;          // tips mode: leaves per tip node (fractional part: probability of one more)
  float size = 0.15f;         // blade length (card side), metres
  float size_jitter = 0.3f;   // relative random variation of the size
  float taper = 0;            // leaves shrink by this share per branch order above min_order
  int min_order = 0;          // only nodes of at least this branch order carry leaves
  float ground = 0;           // no leaf card reaches below this height (metres; the ground is y = 0)
  leaf_archetype archetype = leaf_archetype::ovate;  // the card every leaf uses
  int cap = 300000;           // at most this many leaves; growth goes on, the status bar says so
  bool clusters = false;      // cluster cards: one card carries several leaves
  int cluster_size = 6;       // leaves one cluster card stands for
  leaf_archetype cluster_archetype = leaf_archetype::twig_cluster;
  float clumping = 0;         // 0: leaves spread evenly; 1: only on the outer shells of the limb masses
  float clump_size = 1.2f;    // metres: half the extent of one limb mass
  float clump_variation = 0.3f;  // seeded density difference between limb masses
  int planes = 1;             // cards per leaf, turned evenly about its blade axis (crossed cards)
  // Blades as geometry (render/mesh/leaf_blade.h): each card a grid cut to its picture's outline.
  bool blades = true;         // false: flat cards
  float fold = 14;            // degrees each half of the blade rises about the midrib
  float curl = 22;            // degrees the blade turns down from petiole to tip (negative: up)
  float needle_spread = 360;  // needle shoots: degrees round the shoot its needles fill (360 all round, less: two ranks)
  float shade_size = 0.3f;    // shade leaves larger, sun leaves smaller: 1 + shade_size (0.5 - sky)
  bool operator==(const leaf_params&) const = default;
};

template <params_of<leaf_params> P, class V>
void visit_params(P& p, V&& visitor) {
  auto v = declare_class(visitor, param_remesh);   // mesh_tree places the leaves on the kept skeleton
  v(p.mode, param_info{"leaf_mode", "Leaf placement", "", 0, 2, "shoots: along every young shoot (the foliage model); tips: a tuft on each current tip; generator: the generator's own leaf rule (space colonization's spiral, the L-system's L), else shoots", 0, "Leaves", leaf_mode_names});
  v(p.archetype, param_info{"leaf_archetype", "Leaf archetype", "", 0, leaf_archetype_count - 1, "Procedural leaf card: ovate (birch, beech), lobed (oak), palmate (maple), pinnate compound (ash), pine needle fascicles, flat needle spray (spruce, fir), scale spray (cypress), palm leaflets (one card per rachis side), twig cluster, needle tufts (true cedars), lanceolate (willow), beech, hazel and poplar sprays (cluster cards), horse chestnut (palmately compound: seven leaflets on a long petiole), birch (triangular-ovate, doubly serrate)", 0, nullptr, leaf_archetype_names});
  v(p.retention, param_info{"leaf_retention", "Leaf retention", "", 0, 64, "Growth steps a shoot keeps its leaves: 1 for deciduous trees (this season's and last season's shoots), 3-7 for conifers' needles"});
  v(p.outer_internodes, param_info{"leaf_outer_internodes", "Outer internodes", "", 0, 64, "Only nodes within this many internodes of a shoot tip carry leaves (0: no limit)"});
  v(p.spacing, param_info{"leaf_spacing", "Leaf spacing", "", 0.005f, 2, "Distance between leaf nodes along a shoot, metres", param_log});
  v(p.arrangement, param_info{"leaf_arrangement", "Arrangement", "", 0, 2, "Leaves per node: alternate (one), opposite (two), whorled (n)", 0, nullptr, leaf_arrangement_names});
  v(p.whorl, param_info{"leaf_whorl", "Whorl size", "n", 2, 8, "Leaves per node when whorled"});
  v(p.divergence, param_info{"leaf_divergence", "Divergence", "", 0, 180, "Angle around the shoot between successive leaf nodes (137.5° spiral, 180° two-ranked, 90° decussate)", param_degrees});
  v(p.spread, param_info{"leaf_spread", "Insertion angle", "", 0, 120, "Angle between a leaf and its shoot", param_degrees});
  v(p.droop, param_info{"leaf_droop", "Droop", "", 0, 1, "How far leaves hang toward the ground (1: straight down)"});
  v(p.density, param_info{"leaf_density", "Leaves per tip", "", 0, 32, "Tips mode: leaves on each tip node"});
  v(p.size, param_info{"leaf_size", "Leaf size", "", 0.005f, 4, "Leaf card side in metres", param_log});
  v(p.size_jitter, param_info{"leaf_size_jitter", "Size variation", "", 0, 1, "Relative random variation of leaf size"});
  v(p.taper, param_info{"leaf_taper", "Size taper", "", 0, 0.9f, "Leaves shrink by this share per branch order above the order threshold"});
  v(p.min_order, param_info{"leaf_min_order", "Leaf order threshold", "", 0, 8, "Only branches of at least this order carry leaves"});
  v(p.ground, param_info{"leaf_ground", "Ground level", "", -100, 100, "No leaf card reaches below this height (metres; the tree stands at y = 0): a blade that would is turned up, a leaf on a node below it is dropped"});
  v(p.cap, param_info{"leaf_cap", "Leaf cap", "", 1000, 2000000, "At most this many leaves; past it growth goes on and the status bar says so", param_log | param_on_release});
  v(p.clusters, param_info{"leaf_clusters", "Cluster cards", "", 0, 1, "One card carries a twig with several leaves: a dense crown for few instances (game LODs)"});
  v(p.cluster_size, param_info{"leaf_cluster_size", "Leaves per card", "", 2, 32, "How many leaves one cluster card stands for"});
  v(p.cluster_archetype, param_info{"leaf_cluster_archetype", "Cluster card", "", 0, leaf_archetype_count - 1, "Archetype of the cluster cards", 0, nullptr, leaf_archetype_names});
  v(p.clumping, param_info{"leaf_clumping", "Clumping", "", 0, 1, "Shoots mode: leaves gather on the outer shoots of each limb mass, thinning in its interior and in the gaps between masses, so the crown breaks into clumps (0: spread evenly; the leaf count stays about the same)"});
  v(p.clump_size, param_info{"leaf_clump_size", "Clump size", "", 0.2f, 8, "Half the extent of one limb mass in metres: the largest subtrees this small each form one clump", param_log});
  v(p.clump_variation, param_info{"leaf_clump_variation", "Clump variation", "", 0, 1, "Seeded difference in leaf density from one limb mass to the next"});
  v(p.blades, param_info{"leaf_blades", "Leaf blades", "", 0, 1, "Each leaf is a small mesh cut to the outline of its picture, folded along the midrib and curled, in the viewport and in every export (off: flat square cards, lighter for game budgets)"});
  v(p.fold, param_info{"leaf_fold", "Midrib fold", "", 0, 60, "Degrees each half of the blade rises about the midrib: 0 flat, 20-30 a keeled leaf", param_degrees});
  v(p.curl, param_info{"leaf_curl", "Blade curl", "", -90, 90, "Degrees the blade bends down over its length from petiole to tip (negative: up)", param_degrees});
  v(p.needle_spread, param_info{"leaf_needle_spread", "Needle spread", "", 20, 360, "Needle shoots (pine, spruce and fir, cedar archetypes with blades on): degrees round each shoot its needles stand in. 360: all round the shoot (spruce, pine); 120-200: parted into two ranks to the shoot's sides, raised into a shallow V (fir)", param_degrees});
  v(p.shade_size, param_info{"leaf_shade_size", "Shade leaf size", "", 0, 1, "Leaves deep in the crown grow larger and those under open sky smaller, as shade and sun leaves do: a leaf's size is times 1 + this x (0.5 - its sky visibility from 0 to 1), from the crown occlusion (leaves the generator placed itself keep their sizes)"});
  v(p.planes, param_info{"leaf_planes", "Card planes", "", 1, 3, "Shoots mode: cards each leaf stands as, turned evenly about its blade axis. 1: one flat card; 2 or 3: crossed cards, so a needle shoot reads as a round brush from every side instead of a flat spray (conifers). Multiplies the leaf count"});
}

// The editor shows only the sliders that matter for the current mode.
inline bool param_relevant(const leaf_params& p, const void* field, const param_info&) {
  const bool shoots = p.mode != leaf_mode::tips;
  if (field == &p.density) return p.mode == leaf_mode::tips;
  if (field == &p.retention || field == &p.outer_internodes || field == &p.spacing || field == &p.arrangement ||
      field == &p.divergence || field == &p.droop || field == &p.clusters)
    return shoots;
  if (field == &p.whorl) return shoots && p.arrangement == leaf_arrangement::whorled;
  if (field == &p.cluster_size || field == &p.cluster_archetype) return shoots && p.clusters;
  if (field == &p.clumping || field == &p.planes) return shoots;
  if (field == &p.clump_size || field == &p.clump_variation) return shoots && p.clumping > 0;
  if (field == &p.fold || field == &p.curl) return p.blades;
  if (field == &p.needle_spread) return p.blades && archetype_is_needle_shoot(p.archetype);
  return true;
}

// Leaves on one leaf node of a shoot (the arrangement), and the cards each leaf stands as
// (leaf_planes, clamped): the placement and the mesh bound (render/io/mesh_bound.cpp) share them.
inline int leaves_per_node(const leaf_params& p) {
  return p.arrangement == leaf_arrangement::alternate ? 1 : p.arrangement == leaf_arrangement::opposite ? 2 : std::clamp(p.whorl, 2, 8);
}
inline int card_planes(const leaf_params& p) { return std::clamp(p.planes, 1, 3); }

struct foliage {
  std::vector<leaf> leaves;
  bool capped = false;       // the leaf cap stopped placement
};

// Leaves along every young shoot: each internode of order >= min_order carries leaf nodes every
// `spacing` metres, each with 1, 2 or n leaves; a leaf lives from its node's birth until the node
// is older than `retention` steps or is shed.
foliage place_shoot_leaves(const tree_skeleton& t, const leaf_params& p, uint64_t seed);

// Leaves on every node that is a tip at some step: a leaf is born with its node and dies when the
// node gets its first child (or is shed), so playback shows foliage on the growing tips.
std::vector<leaf> place_tip_leaves(const tree_skeleton& t, const leaf_params& p, uint64_t seed);

// Keeps the cards above the ground (p.ground): a blade whose card would reach below it is turned
// up by mirroring its vertical part, and a leaf that still reaches below is dropped. Cards are
// the exporter's: one blade length long from the petiole, half a length wide.
void keep_leaves_above_ground(std::vector<leaf>& leaves, float ground);

// The lowest height a leaf's card reaches with its frame's axes x (across) and y (along the blade):
// its corners, ±x/2 at the petiole and one blade length along y.
float card_lowest_y(const leaf& l, const glm::vec3& x, const glm::vec3& y);

// The leaves `p.mode` asks for, capped at p.cap.
foliage place_leaves(const tree_skeleton& t, const leaf_params& p, uint64_t seed);

}  // namespace sylva
