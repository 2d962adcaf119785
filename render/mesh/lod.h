// Level of detail: LOD1-LOD3 built from the final tree's LOD0 mesh at triangle budgets,
// the screen coverage at which each level takes over, and the choice of level for a view.
#pragma once

#include <array>
#include <cstddef>
#include <string>

#include "render/mesh/lod_params.h"
#include "generators/skeleton.h"
#include "render/mesh/mesh.h"

namespace sylva {

inline constexpr int lod_levels = 4;   // LOD0 (the full mesh) .. LOD3; the impostor comes after

struct lod_chain {
  std::array<tree_mesh, lod_levels - 1> level;        // LOD1..LOD3 (LOD0 is the caller's mesh)
  std::array<size_t, lod_levels> triangles{};         // LOD0..LOD3, final tree
  std::array<size_t, lod_levels> target{};            // the budgets in triangles (target[0] = LOD0's)
  std::array<float, lod_levels> budget{};             // percent actually used (after clamping)
  // Screen coverage (projected bounding-sphere diameter over the view height) down to which each
  // level is shown; below coverage[3] the impostor stands in.
  std::array<float, lod_levels> coverage{};
  float impostor_coverage = 0;                        // shown down to this (MSFT_screencoverage's last)
  bool reduced = false;       // false: the tree was too small, every level is a copy of LOD0
  std::string message;        // clamped budgets, a tree too small to reduce ("" when none)
};

// Builds LOD1..LOD3 of the final tree. `m` is LOD0, meshed from `t` with `mp`. Node ids of the
// levels stay those of `t`, and their final_radius is LOD0's, so the renderer draws them as is.
// Bark: axes keep fewer rings and fewer radial segments by radius, and branches thinner than the
// level's tolerance go; leaves are merged into bigger cards. O(n log n) in nodes + leaves.
lod_chain build_lods(const tree_skeleton& t, const tree_mesh& m, const mesh_params& mp, const lod_params& p);

// Triangles of the final tree's mesh (bark alive at the last step + two per live leaf card).
size_t final_triangles(const tree_mesh& m);

// Screen coverage of a bounding sphere of `radius` at `distance` for a vertical field of view.
float screen_coverage(float radius, float distance, float fov_degrees);
// The level for a coverage: 0..3, or lod_levels for the impostor. bias as lod_params::bias.
int pick_lod(const lod_chain& c, float coverage, float bias);

}  // namespace sylva
