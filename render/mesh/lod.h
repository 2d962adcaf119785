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
// A level within this share of its budget (either way) holds it; past it the chain says why.
inline constexpr double lod_budget_tolerance = 0.10;

struct lod_chain {
  std::array<tree_mesh, lod_levels - 1> level;        // LOD1..LOD3 (LOD0 is the caller's mesh)
  std::array<size_t, lod_levels> triangles{};         // LOD0..LOD3, final tree
  std::array<size_t, lod_levels> target{};            // the budgets in triangles (target[0] = LOD0's)
  std::array<float, lod_levels> budget{};             // percent actually used (after clamping)
  // Screen coverage (projected bounding-sphere diameter over the view height) down to which each
  // level is shown; below coverage[3] the impostor stands in.
  std::array<float, lod_levels> coverage{};
  float impostor_coverage = 0;                        // shown down to this (MSFT_screencoverage's last)
  // Per level (note[0] unused): why it misses its budget by more than lod_budget_tolerance, which
  // floor kept it higher and by how much ("" when within). Also in `message`.
  std::array<std::string, lod_levels> note;
  bool reduced = false;       // false: the tree was too small, every level is a copy of LOD0
  std::string message;        // clamped budgets, a tree too small to reduce ("" when none)
};

// Builds LOD1..LOD3 of the final tree. `m` is LOD0, meshed from `t` with `mp`. Node ids of the
// levels stay those of `t`, and their final_radius is LOD0's, so the renderer draws them as is.
// Bark: axes keep fewer rings and fewer radial segments by radius, and branches thinner than the
// level's tolerance go; leaves are merged into bigger cards. O(n log n) in nodes + leaves.
lod_chain build_lods(const tree_skeleton& t, const tree_mesh& m, const mesh_params& mp, const lod_params& p);

// Triangles a leaf card costs in an exported file: a face per side, two triangles each
// (render/io/export_parts.cpp bake_leaf; the viewport draws one quad with culling off).
inline constexpr size_t exported_card_triangles = 4;

// Triangles of the final tree as a file with flat cards writes it (the plain and game export
// profiles, `--lods`): bark alive at the last step + exported_card_triangles per live leaf. The
// budgets, the chain's counts and the editor's LOD view all count this way, so that each level's
// share is the share of the file's `_LODn` mesh.
size_t final_triangles(const tree_mesh& m);

// "LOD0-3 triangles 217608 / 87042 / 32640 / 10878 (40.0 / 15.0 / 5.0 % of LOD0; budgets 40 / 15 / 5 %)":
// the counts a file's _LOD0.._LOD3 meshes hold (flat cards), for `sylva export --lods` and the
// editor's LOD view alike.
std::string lod_summary(const lod_chain& c);

// Screen coverage of a bounding sphere of `radius` at `distance` for a vertical field of view.
float screen_coverage(float radius, float distance, float fov_degrees);
// The level for a coverage: 0..3, or lod_levels for the impostor. bias as lod_params::bias.
int pick_lod(const lod_chain& c, float coverage, float bias);

}  // namespace sylva
