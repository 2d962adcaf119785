// The memory bound of one mesh_tree call (mesh_bound.h). Every count below follows mesh_tree
// (render/mesh/mesh.cpp) step by step; where the mesher decides on geometry (the continuing child, the
// curve rings the detail budget keeps) the count takes the most it can decide.
#include "render/io/mesh_bound.h"

#include "generators/memory_bound.h"
#include "render/io/export.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace sylva {
namespace {

// The shape of a tree as the mesher counts it.
struct mesh_counts {
  double nodes = 0, tubes = 0, roots = 0;
  double laterals = 0;        // children other than the one continuing their parent's axis
  double tips = 0;            // tube ends: childless nodes and roots with a trunk
  double curve_wants = 0;     // curve rings every internode could take (before the detail budget)
  double leaves = 0;          // leaves placed before the cap
  double placed = 0;          // leaves held while placing (tips mode holds them all before the cap)
  double leaf_work_nodes = 0; // nodes the foliage model keeps per-node arrays for
  int steps = 0;
};

int segments_of(const mesh_params& p) { return std::clamp(p.radial_segments, 3, 256); }

// Bytes of everything mesh_tree allocates for a tree of shape c under p.
mesh_estimate bytes_of(const mesh_counts& c, const mesh_params& p) {
  mesh_estimate e;
  const int seg = segments_of(p);
  const double budget = std::isfinite(p.detail_budget) ? std::clamp(double(p.detail_budget), 1.0, 16.0) : 1.5;
  const float collar = std::isfinite(p.collar) ? std::clamp(p.collar, 0.0f, 4.0f) : 0.0f;
  // Curve and collar rings: at most what the detail budget spares, at most what is asked for.
  const double asked = c.curve_wants + (collar > 0 ? c.laterals : 0.0);
  const double inserted = std::min(std::floor((budget - 1.0) * c.tubes) + 1, asked);   // (+1: the mesher rounds in its own order)
  // The flare's rings: four heights on each root's trunk, each inside one internode.
  const float flare = std::isfinite(p.flare_strength) ? std::clamp(p.flare_strength, 0.0f, 4.0f) : 0.0f;
  const double flare_rings = flare > 0 ? 4 * c.roots : 0.0;
  const double caps = p.caps ? c.tips : 0.0;
  e.nodes = c.nodes;
  e.rings = c.nodes + c.laterals + inserted + flare_rings + caps;
  e.vertices = e.rings * double(seg + 1);
  e.triangles = 2.0 * seg * (c.tubes + inserted + flare_rings) + double(seg) * caps;
  const double leaf_cap = double(std::clamp(p.leaves.cap, 1, 2000000));
  e.leaves = p.leaves_enabled ? std::min(c.leaves, leaf_cap) : 0.0;
  const double placed = p.leaves_enabled ? c.placed : 0.0;
  const double steps = double(std::max(c.steps, 0)) + 1;
  e.mesh_bytes = e.vertices * mesh_vertex_bytes + e.triangles * 12 + c.nodes * 4 /* final_radius */ +
                 e.leaves * double(sizeof(leaf_instance)) + steps * 8 /* index_end, leaf_end */;
  // The work arrays: per node (mesh_work_bytes_per_node), the ring chain (one index per ring), the
  // detail budget's scores (one per ring asked for), the leaves being placed with their slots and
  // the foliage model's own per-node arrays, the crown occlusion's grid (about 40 cells a side).
  const double work = c.nodes * mesh_work_bytes_per_node + e.rings * 4 + asked * 4 +
                      placed * double(sizeof(leaf) + 4) + (p.leaves_enabled ? c.leaf_work_nodes * 80 : 0.0) +
                      8e6;
  e.peak_bytes = e.mesh_bytes + work;
  return e;
}

// Leaf counts of the foliage model (generators/leaves.cpp) without placing any leaf.
void count_leaves(const tree_skeleton& t, const mesh_params& p, mesh_counts& c) {
  const leaf_params& lp = p.leaves;
  const size_t n = t.size();
  if (!p.leaves_enabled) return;
  if (lp.mode == leaf_mode::generator && !t.leaves.empty()) {
    c.leaves = double(t.leaves.size());   // taken uncopied
    return;
  }
  const double cap = double(std::clamp(lp.cap, 1, 2000000));
  if (lp.mode == leaf_mode::tips) {
    // Every node that is a tip at some step carries floor(density) or one more; all are placed
    // before the cap cuts them.
    const double per = std::floor(std::clamp(double(lp.density), 0.0, 1e6)) + 1;
    double carriers = 0;
    for (size_t i = 0; i < n; ++i) carriers += t.parent[i] >= 0 && t.order[i] >= lp.min_order;
    c.leaves = carriers * per;
    c.placed = c.leaves;
    c.leaf_work_nodes = double(n) * 0.25;   // first_child: two bytes a node
    return;
  }
  // Shoots: floor(len / spacing / cluster × density) leaf nodes per internode or one more, with
  // 1, 2 or whorl leaves each, each leaf 1-3 crossed cards; the clumping density is at most 4
  // (leaf_clumps.cpp).
  const int per_node = leaves_per_node(lp);
  const double spacing = std::isfinite(lp.spacing) ? std::clamp(double(lp.spacing), 0.001, 100.0) : 0.06;
  const double cluster = lp.clusters ? std::clamp(lp.cluster_size, 2, 32) : 1;
  const double dmax = std::isfinite(lp.clumping) && lp.clumping > 0 ? 4.0 : 1.0;
  double leaf_nodes = 0;
  for (size_t i = 0; i < n; ++i) {
    const int32_t par = t.parent[i];
    if (par < 0 || t.order[i] < lp.min_order || !(t.died[i] > t.born[i])) continue;
    const double len = glm::length(t.position[i] - t.position[par]);
    if (!(len > 1e-6) || !std::isfinite(len)) continue;
    leaf_nodes += std::floor(len / spacing / cluster * dmax * (1 + 1e-5)) + 1;
  }
  const double planes = card_planes(lp);
  c.leaves = std::min(leaf_nodes * per_node * planes, 1e15);
  c.placed = std::min(c.leaves, cap);
  c.leaf_work_nodes = double(n);
}

mesh_counts counts_of(const tree_skeleton& t, const mesh_params& p) {
  mesh_counts c;
  const size_t n = t.size();
  c.steps = t.steps;
  if (!structurally_sound(t)) return c;
  std::vector<uint8_t> has_child(n, 0);
  for (size_t i = 0; i < n; ++i)
    if (t.parent[i] >= 0) has_child[size_t(t.parent[i])] = 1;
  double parents = 0;
  for (size_t i = 0; i < n; ++i) {
    parents += has_child[i];
    if (t.parent[i] < 0) {
      c.roots += 1;
      c.tips += has_child[i];   // the trunk's foot
    } else {
      c.tubes += 1;
      c.tips += !has_child[i];
    }
  }
  c.nodes = double(n);
  // Every parent has exactly one continuing child (mesh_tree's `cont`); the others are laterals.
  c.laterals = c.tubes - parents;
  c.curve_wants = c.tubes * std::clamp(p.curve_rings, 0, 16);
  count_leaves(t, p, c);
  if (p.leaves_enabled && p.fruits.count > 0) {   // fruit cards (generators/fruits.h), copied with the leaves
    const double fruit = std::min(double(std::clamp(p.fruits.count, 0, 100000)), c.tips) * std::clamp(p.fruits.cards, 1, 3);
    c.leaves += fruit;
    c.placed += fruit;
  }
  return c;
}

std::string count_text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.0f", v);
  std::string s = buf, out;
  for (size_t i = 0; i < s.size(); ++i) {
    if (i > 0 && (s.size() - i) % 3 == 0) out += ',';
    out += s[i];
  }
  return out;
}

// The worst shape for a node count: one root whose every other node is a lateral and a tip.
mesh_counts worst_counts(double nodes, const mesh_params& p, int steps, double leaves) {
  mesh_counts c;
  c.nodes = std::max(nodes, 0.0);
  c.roots = c.nodes > 0 ? 1 : 0;
  c.tubes = std::max(c.nodes - 1, 0.0);
  c.laterals = std::max(c.tubes - 1, 0.0);
  c.tips = c.nodes;
  c.curve_wants = c.tubes * std::clamp(p.curve_rings, 0, 16);
  c.steps = steps;
  const double cap = double(std::clamp(p.leaves.cap, 1, 2000000));
  c.leaves = leaves >= 0 ? leaves : cap;
  c.placed = p.leaves.mode == leaf_mode::tips ? c.tubes * (std::floor(std::clamp(double(p.leaves.density), 0.0, 1e6)) + 1)
                                                : std::min(c.leaves, cap);
  c.leaf_work_nodes = c.nodes;
  return c;
}

}  // namespace

mesh_estimate mesh_bound(const tree_skeleton& t, const mesh_params& p) { return bytes_of(counts_of(t, p), p); }

mesh_estimate mesh_bound_for_nodes(double nodes, const mesh_params& p, int steps, double leaves) {
  return bytes_of(worst_counts(nodes, p, steps, leaves), p);
}

mesh_estimate mesh_estimate_like(const tree_skeleton& sample, double nodes, const mesh_params& p) {
  mesh_counts c = counts_of(sample, p);
  if (c.nodes < 1) return mesh_bound_for_nodes(nodes, p, sample.steps);
  const double k = std::max(nodes, c.nodes) / c.nodes;
  for (double* v : {&c.nodes, &c.tubes, &c.laterals, &c.tips, &c.curve_wants, &c.leaves, &c.leaf_work_nodes}) *v *= k;
  if (p.leaves.mode == leaf_mode::tips) c.placed *= k;
  else c.placed = std::min(c.leaves, double(std::clamp(p.leaves.cap, 1, 2000000)));
  return bytes_of(c, p);
}

mesh_estimate with_writer(mesh_estimate e, const export_format* format) {
  if (!format) format = find_export_format(".png");   // the viewport uploads as the render does
  e.writer_triangle_bytes = format ? format->writer_triangle_bytes : 0;
  e.writer_leaf_bytes = format ? format->writer_leaf_bytes : 0;
  return e;
}

int mesh_fit_segments(const mesh_estimate& e, const mesh_params& p) {
  const int seg = segments_of(p);
  const double ring_part = e.vertices * mesh_vertex_bytes + e.triangles * 12;
  for (int s = seg - 1; s >= 3; --s) {
    // Vertices and triangles go with the segment count; the rest of the bound does not.
    mesh_estimate at = e;
    at.vertices = e.vertices / double(seg + 1) * double(s + 1);
    at.triangles = e.triangles / double(seg) * double(s);
    const double ring_at = at.vertices * mesh_vertex_bytes + at.triangles * 12;
    at.peak_bytes += ring_at - ring_part;
    at.mesh_bytes += ring_at - ring_part;
    if (at.total_bytes() <= mesh_budget_bytes(p)) return s;
  }
  return 0;
}

std::string mesh_budget_refusal(const mesh_estimate& e, const mesh_params& p, bool estimated) {
  if (!(e.total_bytes() > mesh_budget_bytes(p))) return "";
  const int seg = segments_of(p), fit = mesh_fit_segments(e, p);
  const std::string fix =
      fit ? "lower mesh.radial_segments (" + std::to_string(fit) + " fits), mesh.detail_budget or mesh.curve_rings, or the tree's "
            "size (node_cap, steps or derivations)"
          : "lower the tree's size (node_cap, steps or derivations: even radial_segments 3 does not fit), mesh.detail_budget "
            "or mesh.curve_rings";
  char head[400];
  std::snprintf(head, sizeof head,
                "the mesh would take %s%s (%s%s nodes%s at radial_segments %d, curve_rings %d, detail_budget %.2f; %s leaves), "
                "over mesh_budget %d MB: ",
                estimated ? "about " : "up to ", size_text(e.total_bytes()).c_str(), estimated ? "about " : "",
                count_text(e.nodes).c_str(), estimated ? " by a trial growth's estimate" : "", seg, p.curve_rings, double(p.detail_budget), count_text(e.leaves).c_str(),
                p.mesh_budget);
  return std::string(head) + fix + "; or raise mesh.mesh_budget (at most 32000)";
}

std::string mesh_bound_text() {
  const mesh_params d;
  mesh_params w;   // the settings that cost most per node
  w.radial_segments = 32;
  w.curve_rings = 8;
  w.detail_budget = 4;
  const double big = 1e6;
  const mesh_estimate at_default = mesh_bound_for_nodes(big, d, 1000, 0);
  const mesh_estimate at_worst = mesh_bound_for_nodes(big, w, 1000, 0);
  const double per_leaf = double(sizeof(leaf_instance) + sizeof(sylva::leaf) + 4);
  char buf[640];
  std::snprintf(buf, sizeof buf,
                "peak mesh memory <= mesh_budget (default %d MB, at most 32000 MB): a larger mesh bound stops before "
                "meshing; the bound is at most %.0f B a node at the default mesh settings (%.0f triangles), %.0f B at "
                "radial_segments 32, curve_rings 8, detail_budget 4 (%.0f triangles), plus %.0f B a leaf; the writer adds, "
                "per triangle and per leaf,",
                d.mesh_budget, at_default.peak_bytes / big, at_default.triangles / big, at_worst.peak_bytes / big,
                at_worst.triangles / big, per_leaf);
  std::string out = buf;
  for (const export_format& f : export_format_table) {
    if (!f.mesh) continue;
    std::snprintf(buf, sizeof buf, " %s %.0f/%.0f B", f.ext, double(f.writer_triangle_bytes), double(f.writer_leaf_bytes));
    out += buf;
  }
  return out + " (.png: also the editor's viewport); .json meshes nothing";
}

}  // namespace sylva
