// Skeleton -> bark tube mesh + leaf instances, sorted by birth step for scrubbing (DESIGN §5).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "generators/leaves.h"
#include "generators/params.h"
#include "generators/skeleton.h"

namespace sylva {

struct mesh_params {
  int radial_segments = 8;      // vertices per ring
  float uv_repeat = 2.0f;       // bark texture repeats per metre along a branch
  float min_radius = 0.0005f;   // radii below this are raised to it (keeps thin twigs visible)
  bool leaves_enabled = true;
  leaf_params leaves;           // used when the generator places no leaves itself
  float leaf_scale = 1.0f;      // multiplies every leaf's size (generator-placed leaves too)
  bool operator==(const mesh_params&) const = default;
};

template <params_of<mesh_params> P, class V>
void visit_params(P& p, V&& v) {
  v(p.radial_segments, param_info{"radial_segments", "Radial segments", "", 3, 32, "Vertices around each bark ring", 0, "Bark mesh"});
  v(p.uv_repeat, param_info{"uv_repeat", "Bark UV repeat", "", 0.05f, 20, "Bark texture repeats per metre along a branch", param_log});
  v(p.min_radius, param_info{"min_radius", "Minimum radius", "", 0.00001f, 0.05f, "Thinner branches are drawn at this radius (metres)", param_log});
  v(p.leaves_enabled, param_info{"leaves", "Leaves", "", 0, 1, "Show and export leaves", 0, "Leaves"});
  v(p.leaf_scale, param_info{"leaf_scale", "Leaf scale", "", 0.05f, 10, "Multiplies every leaf's size", param_log});
  visit_params(p.leaves, v);
}

// The leaf sliders follow the leaf mode (leaves.h); the rest always show.
inline bool param_relevant(const mesh_params& p, const void* field, const param_info& info) {
  const char* lo = reinterpret_cast<const char*>(&p.leaves);
  const char* at = static_cast<const char*>(field);
  if (at >= lo && at < lo + sizeof(leaf_params)) return p.leaves_enabled && param_relevant(p.leaves, field, info);
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

struct tree_mesh {
  // Bark: one ring of radial_segments+1 vertices per node (the seam is duplicated for UVs).
  std::vector<glm::vec3> position;   // metres
  std::vector<glm::vec3> normal;     // unit, radial for tube vertices
  std::vector<glm::vec2> uv;         // u around, v along by length (metres * uv_repeat)
  std::vector<uint32_t> node;        // skeleton node of the vertex (for per-step radii/visibility)
  std::vector<float> occlusion;      // per vertex: sky visibility from the depth inside the crown (1: open)
  std::vector<uint32_t> index;       // triangles, sorted by the born step of the internode
  // index_end[s] = number of indices to draw for step s (size steps+1, monotone).
  std::vector<uint32_t> index_end;
  std::vector<leaf_instance> leaves; // sorted by born
  std::vector<uint32_t> leaf_end;    // leaf_end[s] = leaves to draw for step s
  std::vector<float> final_radius;   // per node, the radius the vertices were built with
  glm::vec3 bounds_min{0}, bounds_max{0};
  int steps = 0;
  int radial_segments = 0;           // ring stride is radial_segments + 1
  std::string message;               // for the status bar, e.g. the leaf cap was reached
  size_t triangles() const { return index.size() / 3; }
};

tree_mesh mesh_tree(const tree_skeleton& t, const mesh_params& p, uint64_t seed = 1);

// Crown ambient occlusion (issue 13): bark vertices and leaves deep inside the crown see less sky.
// The crown is the ellipsoid spanned by the leaves' box; the visibility of a point at normalised
// depth d (0 at the centre, 1 on the surface) is 0.35 + 0.65 d, and 1 outside. Fills
// m.occlusion and each leaf's occlusion; O(vertices + leaves). mesh_tree calls it.
void bake_crown_occlusion(tree_mesh& m);

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
