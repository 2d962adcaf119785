// The memory bound of one mesh_tree call, known before meshing: the rings, vertices, triangles and
// leaves the mesher can make from a skeleton (or, before growth, from a node count alone), and the
// peak bytes that take with the mesher's own per-node work arrays. mesh_tree allocates its vertex
// arrays once at the ring count it counts the same way, so the estimate is an upper bound with no
// vector slack in it (tests/render/io/mesh_bound_test.cpp checks it against real meshes of every preset and
// extreme settings). Over the mesh budget (mesh_params::mesh_budget, MB) nothing is meshed: the
// CLI stops with mesh_budget_refusal's message, the editor asks (docs/DESIGN-NOTES.md "Mesh bound").
#pragma once

#include <algorithm>
#include <string>

#include "generators/skeleton.h"
#include "generators/tree_spec.h"
#include "render/mesh/mesh.h"

namespace sylva {

struct mesh_estimate {
  double nodes = 0;
  double rings = 0;        // bark rings: node rings, lateral base rings, curve/collar/flare rings, cap apices
  double vertices = 0;     // rings × (radial_segments + 1)
  double triangles = 0;    // bark triangles
  double leaves = 0;       // leaf instances (at most the leaf cap)
  double mesh_bytes = 0;   // the tree_mesh mesh_tree returns
  double peak_bytes = 0;   // mesh_tree's peak: the mesh, its per-node work arrays and the leaves being placed
  // What is made from the mesh next (an exporter's buffers, the renderer's upload), per bark
  // triangle and per leaf (render/io/export.h's table): its bytes sit beside the mesh, not its work arrays.
  double writer_triangle_bytes = 0, writer_leaf_bytes = 0;
  double writer_bytes() const { return triangles * writer_triangle_bytes + leaves * writer_leaf_bytes; }
  // The bound the budget holds: mesh_tree's peak, or the mesh with what is made from it.
  double total_bytes() const { return std::max(peak_bytes, mesh_bytes + writer_bytes()); }
};
// `e` with the writer of `format` (nullptr: the editor's viewport, as the GL render) counted.
struct export_format;
mesh_estimate with_writer(mesh_estimate e, const export_format* format);

// Bytes the bound counts per unit (mesh_bound.cpp), for the printed text and the tests.
inline constexpr double mesh_vertex_bytes = 40;   // position, normal, uv, node, occlusion
inline constexpr double mesh_work_bytes_per_node = 320;   // the mesher's per-node arrays (frames, curves, budget, index sort)

// Upper bound of mesh_tree(t, p): O(nodes), allocates two bytes per node.
mesh_estimate mesh_bound(const tree_skeleton& t, const mesh_params& p);
// Upper bound for any tree of `nodes` nodes over `steps` growth steps (the worst shape: every node
// also a lateral and a tip), with at most `leaves` leaves (the leaf cap when < 0).
mesh_estimate mesh_bound_for_nodes(double nodes, const mesh_params& p, int steps = 1000, double leaves = -1);
// An estimate for a tree of `nodes` nodes shaped like `sample` (a trial growth of the same request):
// the sample's bound scaled by the node count. Not an upper bound: for refusing before growth.
mesh_estimate mesh_estimate_like(const tree_skeleton& sample, double nodes, const mesh_params& p);

// The mesh budget in bytes.
inline double mesh_budget_bytes(const mesh_params& p) { return double(p.mesh_budget) * 1e6; }
// The most radial segments (3 up to p's own, less one) at which `e`'s tree fits p's budget; 0 when none.
int mesh_fit_segments(const mesh_estimate& e, const mesh_params& p);
// "" when `e` is within p's mesh budget, else one line naming the estimate, the budget and the
// settings to lower (`estimated`: the node count is extrapolated from a trial, not counted).
std::string mesh_budget_refusal(const mesh_estimate& e, const mesh_params& p, bool estimated = false);

// For `sylva params` and the README: "peak mesh memory <= mesh_budget (...)" with the per-node and
// per-leaf costs at default settings and at the settings that cost most.
std::string mesh_bound_text();

// A growth for a mesh under `mesh` and its budget. Before growth, when the worst mesh of the node
// cap is over the budget, a trial growth (generators/estimate.h, about a second at most) estimates
// the tree, its mesh and what `format`'s writer makes of it (mesh_estimate::total_bytes): an estimate over the budget stops there; a trial that is the whole tree is
// the tree. After growth the skeleton's own bound decides. `refusal` is "" when the mesh may be
// made, else mesh_budget_refusal's line (`tree` is empty when refused before growth).
struct budgeted_growth {
  tree_skeleton tree;
  grow_report report;
  std::string refusal;
  bool estimated = false;   // refused on the trial's estimate, before growing
};
budgeted_growth grow_for_mesh(const tree_spec& spec, const mesh_params& mesh, const export_format* format,
                              const grow_options& o = {});

}  // namespace sylva
