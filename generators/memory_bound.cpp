// The documented peak memory of one growth (memory_bound.h).
#include "generators/memory_bound.h"

#include <algorithm>
#include <cstdio>

#include "generators/guiding_vectors.h"
#include "generators/lsystem.h"
#include "generators/self_organizing.h"
#include "generators/self_organizing_grid.h"
#include "generators/space_colonization.h"

namespace sylva {
namespace {

constexpr double MiB = 1024.0 * 1024.0;
// Allocations every growth makes whatever its size (tables, small vectors, allocator slack).
constexpr double base_bytes = 16 * MiB;
// The shadow overlay samples at most 1,000,000 voxels (centre + value).
constexpr double overlay_bytes = 1000000.0 * 16;

// Per node, worst case: the skeleton (position 12, parent 4, radius 4, born/died 4, order 1; with
// leaves and the debug fates and flows) and each generator's own per-node state, times the 3×
// of a vector that is moving to twice its capacity.
constexpr double so_node_bytes = 640;   // + main/lat links, voxel, side, Q, flow, buds, tips, optimal directions
                                        // (measured: 625 B/node on a 168,197-node runaway at the grid cap)
constexpr double sc_node_bytes = 400;   // + node grid, attraction sums, growth flags
constexpr double gv_node_bytes = 300;   // + tree vertex, node vertex maps
constexpr double ls_node_bytes = 300;   // + turtle stack, Honda apices (two generations)
// Per point.
constexpr double so_marker_bytes = 64;  // position, alive, best bud and distance, cell order, sort pairs
constexpr double sc_point_bytes = 96;   // position, alive, nearest node and distance, grid entry, sort pairs
constexpr double gv_point_bytes = 240;  // position, k-d boxes, Yao-8 edges, Dijkstra state, corridor levels
constexpr double ls_module_bytes = 64;  // module (symbol, count, born, parameter index) and parameters, two strings
// The shadow grid's cells at its chunk cap, moving to that capacity (1.5×), with its hash.
const double so_grid_bytes = 1.5 * double(shadow_grid::default_chunk_cap) * shadow_grid::chunk_cells * sizeof(float) +
                             3.0 * double(shadow_grid::default_chunk_cap) * (2 * 12 + 12);
// The guiding-vector sampler's cell grid at its cap (freed before the graph is built, counted anyway).
constexpr double gv_grid_bytes = double(gv_grid_cell_cap) * sizeof(int32_t);

memory_bound bound_of(const self_organizing_params& p) {
  memory_bound b;
  b.points_are = "markers";
  b.fixed = base_bytes;
  // The perception cone's voxel offsets (ivec3, vec3 and three floats each), twice for slack.
  const double rv = double(p.perception_distance) / double(std::max(p.voxel_size, 0.25f)) + 0.87;
  b.fixed += 4.19 * rv * rv * rv * 36 * 2;
  if (p.environment == so_environment::shadow) b.fixed += so_grid_bytes + overlay_bytes;
  else b.points = double(std::min<int64_t>(int64_t(std::max(p.marker_count, 0)) * std::max(p.tree_count, 1), so_marker_cap));
  b.per_point = so_marker_bytes;
  b.nodes = p.node_cap;
  b.per_node = so_node_bytes;
  return b;
}
memory_bound bound_of(const space_colonization_params& p) {
  memory_bound b;
  b.points_are = "attraction points";
  b.fixed = base_bytes;
  b.points = std::max(p.points, 0);
  b.per_point = sc_point_bytes;
  b.nodes = p.node_cap;
  b.per_node = sc_node_bytes;
  return b;
}
memory_bound bound_of(const guiding_vectors_params& p) {
  memory_bound b;
  b.points_are = "graph points";
  b.fixed = base_bytes + gv_grid_bytes;
  b.points = double(gv_point_cap);
  b.per_point = gv_point_bytes;
  b.nodes = p.node_cap;
  b.per_node = gv_node_bytes;
  return b;
}
memory_bound bound_of(const lsystem_params& p) {
  memory_bound b;
  b.points_are = "modules";
  b.fixed = base_bytes;
  if (p.mode == lsystem_mode::text) b.points = std::max(p.module_cap, 0);
  b.per_point = ls_module_bytes;
  b.nodes = p.node_cap;
  b.per_node = ls_node_bytes;
  return b;
}

// Each parameter at the end of its range that costs most memory.
template <class P>
P worst_params(P p) {
  visit_params(p, [](auto& value, const param_info& info) {
    using T = std::decay_t<decltype(value)>;
    const std::string key = info.key;
    if constexpr (std::is_same_v<T, int>)
      if (key == "node_cap" || key == "module_cap" || key == "points" || key == "marker_count" || key == "tree_count")
        value = int(info.max);
  });
  return p;
}

}  // namespace

std::string size_text(double bytes) {
  char buf[32];
  if (bytes >= 1e9) std::snprintf(buf, sizeof buf, "%.2f GB", bytes / 1e9);
  else std::snprintf(buf, sizeof buf, "%.0f MB", bytes / 1e6);
  return buf;
}

memory_bound growth_memory_bound(const tree_spec& spec) {
  return std::visit([](const auto& p) { return bound_of(p); }, spec.params);
}

memory_bound worst_memory_bound(int generator) {
  const generator_params d = default_params(generator);
  memory_bound worst;
  std::visit(
      [&](const auto& p) {
        auto w = worst_params(p);
        worst = bound_of(w);
        if constexpr (std::is_same_v<std::decay_t<decltype(p)>, self_organizing_params>) {
          // One bound for both environments: the shadow grid's fixed cost with the marker cap.
          w.environment = so_environment::markers;
          const double shadow_fixed = worst.fixed;
          worst = bound_of(w);
          worst.fixed = std::max(worst.fixed, shadow_fixed);
        }
        if constexpr (std::is_same_v<std::decay_t<decltype(p)>, lsystem_params>) w.mode = lsystem_mode::text, worst = bound_of(w);
      },
      d);
  return worst;
}

std::string memory_bound_text(int generator) {
  const memory_bound b = worst_memory_bound(generator);
  memory_bound at_default = b;
  std::visit([&](const auto& p) { at_default.nodes = p.node_cap; }, default_params(generator));
  char buf[320];
  std::snprintf(buf, sizeof buf,
                "peak growth memory <= %s + node_cap x %.0f B + %.0f %s x %.0f B: %s at the default node_cap "
                "(%.0f), %s at its maximum",
                size_text(b.fixed).c_str(), b.per_node, b.points, b.points_are, b.per_point,
                size_text(at_default.bytes()).c_str(), at_default.nodes, size_text(b.bytes()).c_str());
  return buf;
}

}  // namespace sylva
