// Guiding-vector graph (Xu & Mould 2015 §A): the Poisson points in an implicit k-d tree and their
// Yao-8 edges, found one at a time (yao8_edges) or all together (build_all_yao8_edges).
#include "generators/guiding_vectors.h"
#include "generators/job_pool.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <utility>

#include <glm/geometric.hpp>

namespace sylva {
namespace {

constexpr float inf = std::numeric_limits<float>::infinity();
constexpr int32_t kd_leaf = 32;


// The implicit k-d tree splits the longest side of each box at the median point; build and query
// recompute the same boxes, so the tree needs no storage beyond the point order.
int split_axis(const glm::vec3& lo, const glm::vec3& hi) {
  const glm::vec3 e = hi - lo;
  return e.x >= e.y && e.x >= e.z ? 0 : (e.y >= e.z ? 1 : 2);
}

// Node `id` (root 1, children 2id and 2id+1) gets the tight box of its points: split boxes would
// reach the domain faces, and a vertex near a face would then search every box along that face
// for points of its empty outward octants.
void build_kd(std::vector<glm::vec3>& p, std::vector<glm::vec3>& box, size_t id, int32_t b, int32_t e) {
  glm::vec3 lo = p[b], hi = p[b];
  for (int32_t i = b + 1; i < e; ++i) {
    lo = glm::min(lo, p[i]);
    hi = glm::max(hi, p[i]);
  }
  if (box.size() < 2 * id + 2) box.resize(2 * id + 2);
  box[2 * id] = lo;
  box[2 * id + 1] = hi;
  if (e - b <= kd_leaf) return;
  const int ax = split_axis(lo, hi);
  const int32_t m = b + (e - b) / 2;
  std::nth_element(p.begin() + b, p.begin() + m, p.begin() + e,
                   [ax](const glm::vec3& a, const glm::vec3& c) { return a[ax] < c[ax]; });
  build_kd(p, box, 2 * id, b, m);
  build_kd(p, box, 2 * id + 1, m, e);
}

struct yao_query {
  glm::vec3 v;
  int32_t self;
  float best_d2[8];
  int32_t best[8];
};

// Octants (bit a set: coordinate a above the query) that a box can hold points of, per axis and side.
constexpr uint8_t octants_low[3] = {0x55, 0x33, 0x0f}, octants_high[3] = {0xaa, 0xcc, 0xf0};

// Visits only boxes that overlap an octant whose best candidate they could still beat.
void query_kd(const std::vector<glm::vec3>& p, const std::vector<glm::vec3>& box, size_t id, int32_t b, int32_t e,
              yao_query& q) {
  const glm::vec3& lo = box[2 * id];
  const glm::vec3& hi = box[2 * id + 1];
  float d2 = 0;
  unsigned overlap = 0xff;
  for (int a = 0; a < 3; ++a) {
    const float below = lo[a] - q.v[a], above = q.v[a] - hi[a];
    const float gap = below > 0 ? below : (above > 0 ? above : 0);
    d2 += gap * gap;
    overlap &= (lo[a] <= q.v[a] ? octants_low[a] : 0u) | (hi[a] > q.v[a] ? octants_high[a] : 0u);
  }
  bool needed = false;
  for (unsigned m = overlap; m && !needed; m &= m - 1) needed = d2 <= q.best_d2[std::countr_zero(m)];
  if (!needed) return;
  if (e - b <= kd_leaf) {
    float best_d2[8];
    int32_t best[8];
    std::copy_n(q.best_d2, 8, best_d2);
    std::copy_n(q.best, 8, best);
    const glm::vec3 v = q.v;
    for (int32_t i = b; i < e; ++i) {
      const glm::vec3 d = p[i] - v;
      const float dd = i == q.self ? inf : glm::dot(d, d);
      const int o = (d.x > 0) | ((d.y > 0) << 1) | ((d.z > 0) << 2);  // octant_of(v, p[i])
      // Branch-free: successive points fall in random octants, so a branch would mispredict.
      // Equal distances keep the first point met (the order is fixed, so this is deterministic).
      const bool better = dd < best_d2[o];
      best_d2[o] = better ? dd : best_d2[o];
      best[o] = better ? i : best[o];
    }
    std::copy_n(best_d2, 8, q.best_d2);
    std::copy_n(best, 8, q.best);
    return;
  }
  const int ax = split_axis(lo, hi);
  const int32_t m = b + (e - b) / 2;
  if (q.v[ax] < p[m][ax]) {
    query_kd(p, box, 2 * id, b, m, q);
    query_kd(p, box, 2 * id + 1, m, e, q);
  } else {
    query_kd(p, box, 2 * id + 1, m, e, q);
    query_kd(p, box, 2 * id, b, m, q);
  }
}


// Yao 1977 / Xu & Mould 2015 §A: one directed edge to the nearest vertex of each octant.
void yao8_query(const gv_graph& g, int32_t v, int32_t out[8]) {
  yao_query q;
  q.v = g.point[v];
  q.self = v;
  std::fill(q.best, q.best + 8, -1);
  // First within a radius that holds every octant's nearest point in the interior of a
  // Poisson-disc set, which prunes hard; then unbounded for the octants still empty (faces).
  const float near2 = g.search_radius * g.search_radius;
  std::fill(q.best_d2, q.best_d2 + 8, near2 > 0 ? near2 : inf);
  const int32_t count = int32_t(g.point.size());
  query_kd(g.point, g.box, 1, 0, count, q);
  if (near2 > 0 && std::count(q.best, q.best + 8, -1) > 0) {
    for (int o = 0; o < 8; ++o)
      if (q.best[o] < 0) q.best_d2[o] = inf;
    query_kd(g.point, g.box, 1, 0, count, q);
  }
  std::copy_n(q.best, 8, out);
}


// The bounded first pass of a Yao-8 query (yao8_query) on a uniform grid instead of the k-d tree:
// cells a little wider than the search radius, so every point within the radius of a vertex lies in
// the 27 cells around the vertex's own. The points are copied in cell order; a row of three cells
// is one run of slots.
struct radius_grid {
  glm::vec3 lo{0};
  float inv_cell = 0;
  int dim[3] = {0, 0, 0};
  std::vector<uint32_t> start;   // cell c holds slots start[c] .. start[c + 1]
  std::vector<glm::vec3> pos;    // the points, in cell order
  std::vector<int32_t> id;       // their vertex indices
  int cell_of(float x, int a) const {   // x lies in the points' box, so truncation is floor
    return std::min(int(std::max((x - lo[a]) * inv_cell, 0.0f)), dim[a] - 1);
  }
};

bool make_radius_grid(const gv_graph& g, radius_grid& grid) {
  if (!(g.search_radius > 0) || !std::isfinite(g.search_radius) || g.point.empty()) return false;
  // 1% wider than the radius: a coordinate gap under the radius then spans under 0.99 of a cell, and
  // with at most 4096 cells a side the rounding of (x - lo) / cell (under 0.001 of a cell) cannot
  // carry it across two cell borders.
  const float cell = 1.01f * g.search_radius;
  grid.lo = g.lo;
  grid.inv_cell = 1 / cell;
  double cells = 1;
  for (int a = 0; a < 3; ++a) {
    const double d = std::max(1.0, std::ceil(double(g.hi[a] - g.lo[a]) / double(cell)));
    if (!(d <= 4096)) return false;
    grid.dim[a] = int(d);
    cells *= d;
  }
  if (cells > 4.0 * double(g.point.size()) + 64) return false;   // a sparse grid: the k-d tree does better
  const size_t n = g.point.size();
  std::vector<uint32_t> cell_at(n);
  grid.start.assign(size_t(cells) + 1, 0);
  for (size_t i = 0; i < n; ++i) {
    const glm::vec3& p = g.point[i];
    cell_at[i] = uint32_t((size_t(grid.cell_of(p.z, 2)) * size_t(grid.dim[1]) + size_t(grid.cell_of(p.y, 1))) *
                              size_t(grid.dim[0]) + size_t(grid.cell_of(p.x, 0)));
    ++grid.start[cell_at[i] + 1];
  }
  for (size_t c = 1; c < grid.start.size(); ++c) grid.start[c] += grid.start[c - 1];
  grid.pos.resize(n);
  grid.id.resize(n);
  std::vector<uint32_t> fill(grid.start.begin(), grid.start.end() - 1);
  for (size_t i = 0; i < n; ++i) {   // in vertex order within a cell, like the k-d leaves
    const uint32_t s = fill[cell_at[i]]++;
    grid.pos[s] = g.point[i];
    grid.id[s] = int32_t(i);
  }
  return true;
}

// yao8_query with its first pass on the grid. The first pass keeps each octant's nearest point
// within the radius; the k-d tree's keeps the first of equally near ones that it meets, so where
// two points tie for an octant's nearest the vertex is queried on the k-d tree instead, and the
// edges are those of yao8_query in every case. The second pass (octants empty within the radius)
// is the k-d tree's, from the same state.
void yao8_query_gridded(const gv_graph& g, const radius_grid& grid, int32_t v, int32_t out[8]) {
  yao_query q;
  q.v = g.point[v];
  q.self = v;
  std::fill(q.best, q.best + 8, -1);
  const float near2 = g.search_radius * g.search_radius;
  std::fill(q.best_d2, q.best_d2 + 8, near2);
  bool tie[8] = {};
  const int c[3] = {grid.cell_of(q.v.x, 0), grid.cell_of(q.v.y, 1), grid.cell_of(q.v.z, 2)};
  const int x0 = std::max(c[0] - 1, 0), x1 = std::min(c[0] + 1, grid.dim[0] - 1);
  for (int z = std::max(c[2] - 1, 0); z <= std::min(c[2] + 1, grid.dim[2] - 1); ++z)
    for (int y = std::max(c[1] - 1, 0); y <= std::min(c[1] + 1, grid.dim[1] - 1); ++y) {
      const size_t row = (size_t(z) * size_t(grid.dim[1]) + size_t(y)) * size_t(grid.dim[0]);
      const uint32_t e = grid.start[row + size_t(x1) + 1];
      for (uint32_t s = grid.start[row + size_t(x0)]; s < e; ++s) {
        const glm::vec3 d = grid.pos[s] - q.v;
        const int32_t i = grid.id[s];
        const float dd = i == v ? inf : glm::dot(d, d);
        const int o = (d.x > 0) | ((d.y > 0) << 1) | ((d.z > 0) << 2);  // octant_of(v, p[i])
        const bool better = dd < q.best_d2[o];
        tie[o] = !better && (tie[o] || (dd == q.best_d2[o] && q.best[o] >= 0));
        q.best_d2[o] = better ? dd : q.best_d2[o];
        q.best[o] = better ? i : q.best[o];
      }
    }
  if (std::find(tie, tie + 8, true) != tie + 8) return yao8_query(g, v, out);
  if (std::count(q.best, q.best + 8, -1) > 0) {
    for (int o = 0; o < 8; ++o)
      if (q.best[o] < 0) q.best_d2[o] = inf;
    query_kd(g.point, g.box, 1, 0, int32_t(g.point.size()), q);
  }
  std::copy_n(q.best, 8, out);
}

}  // namespace

gv_graph make_gv_graph(std::vector<glm::vec3> points, float spacing) {
  gv_graph g;
  g.search_radius = std::isfinite(spacing) && spacing > 0 ? 2.2f * spacing : 0;
  g.point = std::move(points);
  if (!g.point.empty()) {
    g.lo = g.hi = g.point[0];
    for (const glm::vec3& q : g.point) {
      g.lo = glm::min(g.lo, q);
      g.hi = glm::max(g.hi, q);
    }
  }
  if (!g.point.empty()) build_kd(g.point, g.box, 1, 0, int32_t(g.point.size()));
  g.edge_at.assign(g.point.size(), -1);
  return g;
}


const int32_t* yao8_edges(gv_graph& g, int32_t v) {
  if (g.edge_at[v] < 0) {
    g.edge_at[v] = int32_t(g.edges.size());
    g.edges.resize(g.edges.size() + 8);
    yao8_query(g, v, g.edges.data() + g.edge_at[v]);
  }
  return g.edges.data() + g.edge_at[v];
}

void build_all_yao8_edges(gv_graph& g) {
  // Each vertex's query reads only the points, the k-d boxes and the grid, and writes its own 8
  // entries, so the edges are the same whichever thread finds them; vertices already built keep theirs.
  const size_t n = g.point.size(), base = g.edges.size();
  std::vector<int32_t> todo;
  for (size_t v = 0; v < n; ++v)
    if (g.edge_at[v] < 0) todo.push_back(int32_t(v));
  g.edges.resize(base + 8 * todo.size());
  for (size_t i = 0; i < todo.size(); ++i) g.edge_at[size_t(todo[i])] = int32_t(base + 8 * i);
  radius_grid grid;
  const bool gridded = todo.size() >= 64 && make_radius_grid(g, grid);
  parallel_chunks(todo.size(), 256, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      int32_t* out = g.edges.data() + base + 8 * i;
      if (gridded) yao8_query_gridded(g, grid, todo[i], out);
      else yao8_query(g, todo[i], out);
    }
  });
}

}  // namespace sylva
