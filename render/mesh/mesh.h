// Skeleton -> bark tube mesh + leaf instances, sorted by birth step for scrubbing (DESIGN §5).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <glm/vector_relational.hpp>

#include "generators/fruits.h"
#include "generators/leaves.h"
#include "generators/params.h"
#include "generators/skeleton.h"
#include "generators/uninit_vector.h"
#include "generators/vec_util.h"
#include "render/mesh/leaf_blade.h"

namespace sylva {

struct mesh_params {
  int radial_segments = 8;      // vertices per ring
  int mesh_budget = 4000;       // MB: a mesh whose bound (render/io/mesh_bound.h) is larger is not made
  float uv_repeat = 2.0f;       // bark texture repeats per metre along a branch
  float min_radius = 0.0005f;   // radii below this are raised to it (keeps thin twigs visible)
  // Bark shape: curved axes, gnarl, twist, collars, root flare, caps.
  float curve_angle = 12.0f;    // degrees the curve may turn between two rings of an internode
  int curve_rings = 2;          // at most this many rings inserted per internode (0: polyline)
  float detail_budget = 1.45f;  // curve and collar rings stop at this x the triangles of one ring per node
  float gnarl = 3.0f;           // degrees of seeded angular noise per internode, for old wood
  float twist = 0.0f;           // spiral grain: degrees the bark texture leans around the axis
  float collar = 0.35f;         // a lateral's base swells by this fraction of its radius
  float collar_length = 2.0f;   // ... fading over this many lateral radii beyond the parent's bark
  float collar_min_radius = 0.01f;  // thinner laterals get no collar ring (metres)
  int flare_lobes = 5;          // buttress lobes at the trunk's base
  float flare_height = 1.0f;    // metres of trunk the flare spans (at most 6 trunk radii)
  float flare_strength = 0.5f;  // extra radius at the ground, as a fraction of the trunk's (0: off)
  float root_depth = 0.1f;      // metres an upright trunk's foot reaches below the ground (y of its root)
  bool caps = true;             // close every tube end
  bool leaves_enabled = true;
  leaf_params leaves;           // used when the generator places no leaves itself
  fruit_params fruits;          // cones and fruit on shoot tips (with the leaves, by any leaf mode)
  float leaf_scale = 1.0f;      // multiplies every leaf's size (generator-placed leaves too)
  bool operator==(const mesh_params&) const = default;
};

template <params_of<mesh_params> P, class V>
void visit_params(P& p, V&& visitor) {
  auto v = declare_class(visitor, param_remesh);   // mesh_tree alone reads them
  v(p.radial_segments, param_info{"radial_segments", "Radial segments", "", 3, 32, "Vertices around each bark ring", 0, "Bark mesh"});
  v(p.mesh_budget, param_info{"mesh_budget", "Mesh budget", "MB", 50, 32000, "Most memory the mesh may take, in MB (10^6 bytes): a tree whose mesh bound (nodes x radial segments x rings, plus leaves) is larger is not meshed; the export stops and says which setting to lower, the editor asks which to change", param_log | param_on_release});
  v(p.uv_repeat, param_info{"uv_repeat", "Bark UV repeat", "", 0.05f, 20, "Bark texture repeats per metre along a branch", param_log});
  v(p.min_radius, param_info{"min_radius", "Minimum radius", "", 0.00001f, 0.05f, "Thinner branches are drawn at this radius (metres)", param_log});
  v(p.curve_angle, param_info{"curve_angle", "Curve ring angle", "", 2, 90, "A ring is inserted into an internode for every this many degrees its centripetal Catmull-Rom curve turns", param_degrees, "Bark shape"});
  v(p.curve_rings, param_info{"curve_rings", "Curve rings", "", 0, 8, "Most rings inserted into one internode where the branch curves (0: straight tubes)"});
  v(p.detail_budget, param_info{"detail_budget", "Detail budget", "", 1, 4, "Curve and collar rings go where they show most (wide branches, sharp turns) until the bark has this many times the triangles of one ring per node"});
  v(p.gnarl, param_info{"gnarl", "Gnarl", "", 0, 30, "Seeded angular noise per internode, growing with age and branch order (degrees)", param_degrees});
  v(p.twist, param_info{"twist", "Bark twist", "", -45, 45, "Spiral grain: the bark texture leans by this angle around the axis", param_degrees});
  v(p.collar, param_info{"collar", "Collar swell", "", 0, 1, "A lateral's base swells by this fraction of its radius where it leaves its parent"});
  v(p.collar_length, param_info{"collar_length", "Collar length", "", 0.5f, 8, "The collar fades over this many lateral radii beyond the parent's bark"});
  v(p.collar_min_radius, param_info{"collar_min_radius", "Collar min radius", "", 0.0001f, 0.5f, "Laterals thinner than this get no collar (metres)", param_log});
  v(p.flare_lobes, param_info{"flare_lobes", "Flare lobes", "", 3, 6, "Buttress lobes at the trunk's base (up to half the radial segments show)"});
  v(p.flare_height, param_info{"flare_height", "Flare height", "", 0.05f, 3, "Metres of trunk the root flare spans (at most 6 trunk radii)"});
  v(p.flare_strength, param_info{"flare_strength", "Flare strength", "", 0, 2, "Extra radius of the lobes at the ground, as a fraction of the trunk's (0: no flare)"});
  v(p.root_depth, param_info{"root_depth", "Root depth", "", 0, 2, "An upright trunk's foot reaches this far below the ground (metres), at the flare's full spread, so the tree stands in the ground with no flat cut showing (0: the foot lies on the ground)"});
  v(p.caps, param_info{"caps", "Tip caps", "", 0, 1, "Close every tube end with a cap"});
  v(p.leaves_enabled, param_info{"leaves", "Leaves", "", 0, 1, "Show and export leaves", 0, "Leaves"});
  v(p.leaf_scale, param_info{"leaf_scale", "Leaf scale", "", 0.05f, 10, "Multiplies every leaf's size", param_log});
  visit_params(p.leaves, v);
  visit_params(p.fruits, v);
}

// The leaf sliders follow the leaf mode (leaves.h); the rest always show.
inline bool param_relevant(const mesh_params& p, const void* field, const param_info& info) {
  const char* lo = reinterpret_cast<const char*>(&p.leaves);
  const char* at = static_cast<const char*>(field);
  if (at >= lo && at < lo + sizeof(leaf_params)) return p.leaves_enabled && param_relevant(p.leaves, field, info);
  const char* fo = reinterpret_cast<const char*>(&p.fruits);
  if (at >= fo && at < fo + sizeof(fruit_params)) return p.leaves_enabled && param_relevant(p.fruits, field, info);
  return true;
}

struct leaf_instance {
  glm::vec3 position;
  glm::vec4 orientation;   // quaternion (x, y, z, w)
  float size;
  uint16_t born, died;
  uint32_t node;
  uint8_t texture;         // leaf archetype of the card (generators/archetypes.h)
  uint8_t occlusion = 255; // sky visibility baked from the depth inside the crown (255: open sky)
};

struct baked_card_textures;   // render/mesh/lod_cards.h

struct tree_mesh {
  // Bark: rings of radial_segments+1 vertices (the seam is duplicated for UVs): one per node, a
  // base ring per lateral, rings inserted where a branch curves, collars and the root flare, and
  // a cap's apex ring (all its vertices at the apex) per tube end. An upright trunk's root ring (and
  // foot cap) lies root_depth below its root node, in the ground. Every ring belongs to the node
  // that ends its internode, so per-node radii and visibility apply to it.
  // The bark's arrays are sized first and then filled in parallel chunks: uninit_vector, so that
  // sizing them does not zero them first.
  uninit_vector<glm::vec3> position;   // metres
  uninit_vector<glm::vec3> normal;     // unit, radial for tube vertices
  uninit_vector<glm::vec2> uv;         // u around, v along by length (metres * uv_repeat)
  uninit_vector<uint32_t> node;        // skeleton node of the vertex (for per-step radii/visibility)
  std::vector<float> occlusion;      // per vertex: sky visibility from the depth inside the crown (1: open)
  uninit_vector<uint32_t> index;       // triangles, sorted by the born step of the internode
  // index_end[s] = number of indices to draw for step s (size steps+1, monotone).
  std::vector<uint32_t> index_end;
  std::vector<leaf_instance> leaves; // sorted by born
  std::vector<uint32_t> leaf_end;    // leaf_end[s] = leaves to draw for step s
  std::vector<float> final_radius;   // per node, the radius the vertices were built with
  glm::vec3 bounds_min{0}, bounds_max{0};
  int steps = 0;
  int radial_segments = 0;           // ring stride is radial_segments + 1
  std::string message;               // for the status bar, e.g. the leaf cap was reached
  leaf_blade_shape blade;            // every leaf's blade mesh (render/mesh/leaf_blade.h); off: flat cards
  // LOD levels only (render/mesh/lod_cards.h): cluster cards baked from the tree's own leaves; a leaf
  // with texture leaf_archetype_count + k uses card k. Null for LOD0.
  std::shared_ptr<const baked_card_textures> cards;
  size_t triangles() const { return index.size() / 3; }
};

// Wall milliseconds of each stage of one mesh_tree call (`sylva bench --stages`): the per-node
// frame (radii, gnarl, axes, curve velocities, flare, texture wraps), the detail budget (curve,
// collar and flare rings chosen), the bark rings, the index buffer, leaf placement (the foliage
// model, or the generator's leaves taken), the crown's sky field (bake_crown_sky), and the crown
// occlusion sampled from the field with the bounds, the leaves sorted by step with their gnarl in
// the same pass.
// Leaf placement and the sky field run on a pool helper beside the first four (the bark), so with
// a helper free the stages add up to more than the call's wall time.
struct mesh_stage_times {
  double frame = 0, budget = 0, rings = 0, index = 0, leaf_place = 0, sky = 0, occlusion = 0;
  double total() const { return frame + budget + rings + index + leaf_place + sky + occlusion; }
};

tree_mesh mesh_tree(const tree_skeleton& t, const mesh_params& p, uint64_t seed = 1, mesh_stage_times* times = nullptr);

// Crown ambient occlusion (issues 13, 23): bark vertices and leaves deep inside the crown, and
// inside each clump of it, see less sky. The crown is the ellipsoid spanned by the leaves' box (d:
// normalised depth, 0 at the centre, 1 on the surface and outside); the local sky s is the
// Beer-Lambert transmittance through the leaf area density within about a sixth of the crown's
// size, along nine upward directions (render/mesh/crown_occlusion.cpp). Visibility 0.35 + 0.65 sqrt(d) s:
// 1 under open sky. Fills m.occlusion and each leaf's occlusion; O(vertices + leaves + grid cells,
// about 40 along the crown's longest side). Same as shade_by_crown(m, bake_crown_sky(its leaves)).
void bake_crown_occlusion(tree_mesh& m);

// The crown's sky field: a box of cubic cells over the leaves (about 40 along the longest side,
// reaching a window below them) holding the share of the sky each cell sees, and the crown's
// ellipsoid (centre, 1 / half extent). Empty value: no crown.
struct crown_sky {
  glm::vec3 origin{0}, centre{0}, inv_radius{1};
  float cell = 1;
  int nx = 0, ny = 0, nz = 0;
  std::vector<float> value;
  size_t at(int x, int y, int z) const { return (size_t(y) * size_t(nz) + size_t(z)) * size_t(nx) + size_t(x); }
  float sample(const glm::vec3& p) const;   // trilinear between cell centres, clamped to the box
};
// The field from the leaves' centres (xyz) and card sizes (w). It reads only the leaves, so
// mesh_tree bakes it on a pool helper beside the bark, from the leaves before gnarl moves them
// (a few centimetres against cells of about a fortieth of the crown).
crown_sky bake_crown_sky(const std::vector<glm::vec4>& leaves);
// How much of the sky a point sees, 0.35 (deep in the crown) to 1: the crown ellipsoid's depth
// times the field's sample; 1 without a crown. A leaf's occlusion is 255 times this, rounded.
inline float crown_visibility(const crown_sky& g, const glm::vec3& p) {
  // Depth in the crown's ellipsoid (0 at the centre, 1 on its surface and outside) darkens the
  // crown's core; the local sky darkens each clump's inside.
  if (g.value.empty()) return 1.0f;   // no crown: every point sees the open sky
  const float d = glm::length((p - g.centre) * g.inv_radius);
  if (!std::isfinite(d)) return 1.0f;
  const bool near = glm::all(glm::greaterThanEqual(p, g.origin)) &&
                    glm::all(glm::lessThanEqual(p, g.origin + g.cell * glm::vec3(float(g.nx), float(g.ny), float(g.nz))));
  const float sky = near ? g.sample(p) : 1.0f;
  return 0.35f + 0.65f * std::sqrt(std::min(d, 1.0f)) * sky;
}
// A leaf's occlusion, 255 times its centre's crown_visibility, rounded; and its centre ± size
// added to the box lo, hi (shade_by_crown's leaf part, for its own chunks and mesh_tree's).
inline void shade_leaf(leaf_instance& l, const crown_sky& g, glm::vec3& lo, glm::vec3& hi) {
  l.occlusion = uint8_t(std::lround(255.0f * crown_visibility(g, l.position)));
  lo = glm::min(lo, l.position - glm::vec3(l.size));
  hi = glm::max(hi, l.position + glm::vec3(l.size));
}
// The leaves' part of shade_by_crown done by its caller as it writes them (mesh_tree's leaf sort):
// `count` jobs that run in the batch shading the bark, job j shading its own leaves with
// shade_leaf, lo and hi at ±1e30 on entry.
struct crown_leaf_jobs {
  size_t count = 0;
  std::function<void(size_t j, glm::vec3& lo, glm::vec3& hi)> run;
};
// m.occlusion for the bark's vertices and each leaf's occlusion, sampled from the field (the
// leaves' by `leaf_jobs` when given); with set_bounds also m.bounds_min/max (every bark vertex,
// every leaf's centre ± its size) from the same passes, as mesh_tree does.
void shade_by_crown(tree_mesh& m, const crown_sky& sky, bool set_bounds = false, const crown_leaf_jobs* leaf_jobs = nullptr);

// Gnarl: per node, the rotation vector (axis * angle) of its internode, from seeded noise
// scaled by age and order; those rotations' Rodrigues terms (the cosines and sines worked out once
// for the node and every leaf on it); and the offset of every node once each internode is turned
// and its subtree carried along (O(n)). mesh_tree moves bark and leaves by them.
std::vector<glm::vec3> gnarl_rotations(const tree_skeleton& t, const mesh_params& p);
std::vector<rotation_terms> gnarl_turns(const std::vector<glm::vec3>& rot);
std::vector<glm::vec3> gnarl_offsets(const tree_skeleton& t, const std::vector<rotation_terms>& turn);
// Where a point hung on node k (a leaf) goes once the gnarl has turned k's internode.
glm::vec3 gnarled_point(const tree_skeleton& t, const std::vector<rotation_terms>& turn, const std::vector<glm::vec3>& disp,
                        size_t k, const glm::vec3& at);

// FNV-1a over every byte the mesh hands on (vertex arrays, indices, step tables, leaves, radii,
// bounds): two meshes with one digest are the same bytes, for tests and `bench --stages --json`.
uint64_t mesh_digest(const tree_mesh& m);

// Checks the mesh invariants (indices in range, offsets monotone, no NaN); "" when valid.
std::string validate_mesh(const tree_mesh& m);

// The tree as it stood at `step`: only nodes alive then (born <= step < died), compacted with
// parent < i kept, radii of that step, leaves alive then. steps = step.
tree_skeleton skeleton_at_step(const tree_skeleton& t, int step);

// The mesh of the tree at `step` for export: bark re-meshed from skeleton_at_step (radii of that
// step, dead branches gone) and the leaves of `full` alive at `step`, so the foliage matches the
// editor's view of that step. step < 0 means the final step; later steps are clamped to it.
tree_mesh mesh_tree_at_step(const tree_skeleton& t, const tree_mesh& full, const mesh_params& p, int step);

}  // namespace sylva
