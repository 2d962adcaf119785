// Guiding-vector shortest-path trees (Xu & Mould 2015, seed 002): graph, search and the step loop.
#include "generators/guiding_vectors.h"
#include "generators/job_pool.h"
#include "generators/vec_util.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <string>
#include <utility>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "generators/keyframes.h"
#include "generators/pruning.h"

namespace sylva {
namespace {

constexpr float inf = std::numeric_limits<float>::infinity();
constexpr glm::vec3 up(0, 1, 0);
// 64 Mi cells (256 MB of grid) is far beyond any interactive tree; past it we refuse, not crash.
constexpr uint64_t max_grid_cells = gv_grid_cell_cap;
float turn_angle(const gv_turn_rule& r, const glm::vec3& pos, int hops) {
  switch (r.mode) {
    case gv_t_mode::hop_ramp: {  // Xu & Mould 2015 §C: t(s), s = hops from the source
      const float f = std::min(float(hops) / float(std::max(r.ramp_hops, 1)), 1.0f);
      return r.t + (r.t_end - r.t) * f;
    }
    case gv_t_mode::radial: {  // Xu & Mould 2015 §C: t1(v) = t if √(vx²+vz²) < T, else −t
      const glm::vec2 d(pos.x - r.axis_origin.x, pos.z - r.axis_origin.z);
      return glm::length(d) < r.radial_T ? r.t : -r.t;
    }
    default: return r.t;
  }
}

// Xu & Mould 2015 §D.1: the step-1 endpoint volume, in the volume's own (offset, stretched) frame.
bool in_volume(const guiding_vectors_params& p, const glm::vec3& pos) {
  const glm::vec3 scale = glm::max(p.volume_scale, glm::vec3(1e-6f));
  const glm::vec3 q = (pos - p.volume_offset) / scale;
  const float R = p.volume_outer;
  const float rho = std::sqrt(q.x * q.x + q.z * q.z);
  switch (p.volume) {
    case gv_volume::annulus: {  // a torus whose cross-section spans inner..outer radius
      const float a = std::min(p.volume_inner, R), b = std::max(p.volume_inner, R);
      const float centre = 0.5f * (a + b), tube = 0.5f * (b - a);
      return (rho - centre) * (rho - centre) + q.y * q.y <= tube * tube;
    }
    case gv_volume::box: return std::abs(q.x) <= R && std::abs(q.y) <= R && std::abs(q.z) <= R;
    case gv_volume::cone:  // base radius R at y = −R narrowing to the apex at y = +R
      return std::abs(q.y) <= R && rho <= 0.5f * (R - q.y);
    default: return glm::dot(q, q) <= R * R;
  }
}

// Hop distances from the tree up to `depth`, by breadth-first search over the Yao-8 edges. Fills
// `level` (reset it through `touched`) and returns B_h, the vertices whose fewest-hop distance
// from the tree is exactly h (Xu & Mould 2015 §D.2).
std::vector<int32_t> hop_levels(gv_graph& g, const std::vector<int32_t>& tree_vertices, int h, int depth,
                                std::vector<int32_t>& level, std::vector<int32_t>& touched, const grow_options& o,
                                bool& cancelled) {
  std::vector<int32_t> frontier = tree_vertices, next, border;
  for (int32_t v : tree_vertices) {
    level[v] = 0;
    touched.push_back(v);
  }
  for (int d = 1; d <= depth && !frontier.empty(); ++d) {
    if (o.cancelled()) { cancelled = true; return {}; }
    next.clear();
    for (int32_t u : frontier) {
      int32_t out[8];
      std::copy_n(yao8_edges(g, u), 8, out);
      for (int32_t w : out)
        if (w >= 0 && level[w] < 0) {
          level[w] = d;
          touched.push_back(w);
          next.push_back(w);
        }
    }
    std::swap(frontier, next);
    if (d == h) border = frontier;
  }
  return border;
}

float schedule_at(const std::vector<float>& v, int step, float fallback) {
  if (v.empty()) return fallback;
  const float x = v[size_t(std::min<int>(step - 1, int(v.size()) - 1))];
  return std::isfinite(x) ? x : fallback;
}

void add_arrow(growth_debug& d, const glm::vec3& from, const glm::vec3& dir, float len) {
  const glm::vec3 tip = from + dir * len;
  glm::vec3 side = glm::cross(dir, up);
  side = glm::dot(side, side) > 1e-8f ? glm::normalize(side) : glm::vec3(1, 0, 0);
  const glm::vec3 colour(1.0f, 0.55f, 0.1f);
  for (const glm::vec3& end : {from, tip - dir * (0.3f * len) + side * (0.15f * len),
                               tip - dir * (0.3f * len) - side * (0.15f * len)}) {
    d.add_line(end, tip, colour, debug_kind::guide_arrow);
  }
}

}  // namespace

bool sample_poisson_disc(const glm::vec3& lo, const glm::vec3& hi, const glm::vec3& first, float r, int k,
                         uint64_t seed, const grow_options& o, std::vector<glm::vec3>& out, std::string* error,
                         int64_t point_cap) {
  out.clear();
  auto fail = [&](const std::string& why) {
    if (error) *error = why;
    return false;
  };
  if (!std::isfinite(r) || r <= 0) return fail("point spacing must be positive");
  if (!finite3(lo) || !finite3(hi) || !finite3(first) || hi.x < lo.x || hi.y < lo.y || hi.z < lo.z)
    return fail("the point domain is empty or not finite");
  k = std::max(k, 1);
  // Xu & Mould 2015 §A: cells of side c ≤ r/√3 hold at most one point (their diagonal is r).
  const float c = r / std::sqrt(3.0f);
  const glm::vec3 size = hi - lo;
  // The grid has a 2-cell empty margin on every side, so neighbour lookups need no bounds checks.
  int64_t n[3];
  uint64_t cells = 1;
  for (int a = 0; a < 3; ++a) {
    const double na = std::max(1.0, std::ceil(double(size[a]) / double(c)));
    if (na > double(max_grid_cells)) return fail("the domain is too large for the point spacing; raise the spacing or shrink the domain");
    n[a] = int64_t(na);
    cells *= uint64_t(n[a] + 4);
    if (cells > max_grid_cells)
      return fail("the domain is too large for the point spacing; raise the spacing or shrink the domain");
  }
  const int64_t sy = n[0] + 4, sz = sy * (n[1] + 4);
  std::vector<int32_t> grid(cells, -1);
  const float inv_c = 1 / c;
  auto cell_of = [&](const glm::vec3& p) {  // p lies in [lo, hi], so truncation is floor
    int64_t idx = 0;
    const int64_t stride[3] = {1, sy, sz};
    for (int a = 0; a < 3; ++a)
      idx += (std::min(int64_t(std::max((p[a] - lo[a]) * inv_c, 0.0f)), n[a] - 1) + 2) * stride[a];
    return size_t(idx);
  };
  // Neighbour cells that can hold a point closer than r = c√3, nearest first so conflicts end the
  // check early: the gap to a cell offset by d is c·max(|d|−1, 0) per axis, so only the 8 corners
  // of the 5×5×5 block are out of reach.
  std::vector<std::pair<int, int64_t>> ranked;
  for (int dz = -2; dz <= 2; ++dz)
    for (int dy = -2; dy <= 2; ++dy)
      for (int dx = -2; dx <= 2; ++dx) {
        const int m2 = (std::abs(dx) > 1) + (std::abs(dy) > 1) + (std::abs(dz) > 1);
        const int near = std::abs(dx) + std::abs(dy) + std::abs(dz);
        if (m2 < 3 && near > 0) ranked.push_back({m2 * 16 + near, dx + dy * sy + dz * sz});
      }
  std::stable_sort(ranked.begin(), ranked.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<int64_t> reach;
  for (const auto& r_off : ranked) reach.push_back(r_off.second);

  const glm::vec3 start = glm::clamp(first, lo, hi);
  grid[cell_of(start)] = 0;
  out.push_back(start);
  rng random(seed ^ 0x9015504dull);
  const float r2 = r * r;
  // Xu & Mould 2015 §A, POPULATE-GRID: a FIFO queue; k candidates at r..2r around each point.
  for (size_t head = 0; head < out.size(); ++head) {
    if ((head & 1023) == 0 && o.cancelled()) {
      out.clear();
      return fail("cancelled");
    }
    const glm::vec3 v = out[head];
    for (int j = 0; j < k; ++j) {
      // A uniform direction by rejection from the cube (cheaper than sin/cos), at r..2r.
      glm::vec3 dir;
      float len2;
      do {
        dir = glm::vec3(random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(-1, 1));
        len2 = glm::dot(dir, dir);
      } while (len2 > 1 || len2 < 1e-4f);
      const glm::vec3 cand = v + dir * (r * (1 + random.uniform()) / std::sqrt(len2));
      if (cand.x < lo.x || cand.y < lo.y || cand.z < lo.z || cand.x > hi.x || cand.y > hi.y || cand.z > hi.z)
        continue;
      const size_t own = cell_of(cand);
      if (grid[own] >= 0) continue;  // one point per cell: the cell's diagonal is r
      bool free = true;
      for (const int64_t off : reach) {
        const int32_t q = grid[size_t(int64_t(own) + off)];
        if (q < 0) continue;
        const glm::vec3 dd = out[size_t(q)] - cand;
        if (glm::dot(dd, dd) < r2) {
          free = false;
          break;
        }
      }
      if (!free) continue;
      if (int64_t(out.size()) >= point_cap) {
        out.clear();
        out.shrink_to_fit();
        return fail("the graph would pass " + std::to_string(point_cap) +
                    " points (its memory cap); raise the spacing or shrink the domain");
      }
      grid[own] = int32_t(out.size());
      out.push_back(cand);
    }
  }
  out.shrink_to_fit();
  return true;
}

float gv_edge_cost(const glm::vec3& u, const glm::vec3& v, const glm::vec3& g_u) {
  // Xu & Mould 2015 §B: c_e = ‖v−u‖(1 − ê·g_u) = ‖v−u‖ − (v−u)·g_u; never negative for unit g_u.
  const glm::vec3 d = v - u;
  return std::max(0.0f, glm::length(d) - glm::dot(d, g_u));
}

glm::vec3 turn_guiding_vector(const glm::vec3& g_parent, const glm::vec3& edge_dir, float t) {
  const float gl = glm::length(g_parent);
  if (!(gl > 1e-12f) || !std::isfinite(t)) return up;
  const glm::vec3 g = g_parent / gl;
  // Rotating g about up × g by t > 0 turns it away from up (toward −up); t < 0 turns it up.
  // Past a pole the axis up × g flips sign and g would oscillate about the pole, so it stops there.
  const float to_pole = t < 0 ? std::acos(std::clamp(g.y, -1.0f, 1.0f)) : std::acos(std::clamp(-g.y, -1.0f, 1.0f));
  if (std::abs(t) >= to_pole) return t < 0 ? up : -up;
  glm::vec3 axis = glm::cross(up, g);  // Xu & Mould 2015 §C: r = (0,1,0) × g_p
  if (glm::dot(axis, axis) < 1e-12f) {
    // g lies on a pole and t turns it away: the edge's direction picks the side it leans to.
    axis = glm::cross(up, edge_dir);
    if (glm::dot(axis, axis) < 1e-12f) return g;
  }
  axis = glm::normalize(axis);
  // Rodrigues' rotation for an axis perpendicular to g.
  return glm::normalize(g * std::cos(t) + glm::cross(axis, g) * std::sin(t));
}

bool search_gv_paths(gv_graph& g, const std::vector<int32_t>& sources, const std::vector<glm::vec3>& source_guide,
                     const gv_turn_rule& rule, const std::vector<int32_t>& targets, gv_search_state& s,
                     const grow_options& o, const std::vector<int32_t>* corridor) {
  const size_t n = g.point.size();
  if (s.dist.size() != n) {
    s.dist.assign(n, inf);
    s.parent.assign(n, -1);
    s.guide.assign(n, up);
    s.hops.assign(n, 0);
    s.settled.assign(n, 0);
    s.touched.clear();
  }
  for (int32_t v : s.touched) {
    s.dist[v] = inf;
    s.parent[v] = -1;
    s.hops[v] = 0;
    s.settled[v] = 0;
  }
  s.touched.clear();
  std::vector<int32_t> goal(targets);
  std::sort(goal.begin(), goal.end());
  goal.erase(std::unique(goal.begin(), goal.end()), goal.end());
  size_t remaining = goal.size();

  // Non-negative floats order like their bit patterns, so (cost, vertex) packs into one integer key.
  auto key = [](float d, int32_t v) { return (uint64_t(std::bit_cast<uint32_t>(d)) << 32) | uint32_t(v); };
  std::priority_queue<uint64_t, std::vector<uint64_t>, std::greater<uint64_t>> heap;
  for (size_t i = 0; i < sources.size(); ++i) {
    const int32_t v = sources[i];
    if (v < 0 || size_t(v) >= n || s.dist[v] == 0) continue;
    s.dist[v] = 0;
    const glm::vec3 gv = i < source_guide.size() ? source_guide[i] : up;
    s.guide[v] = glm::dot(gv, gv) > 1e-12f ? glm::normalize(gv) : up;
    s.touched.push_back(v);
    heap.push(key(0.0f, v));
  }
  uint32_t pops = 0;
  while (!heap.empty() && remaining > 0) {
    const uint64_t top = heap.top();
    heap.pop();
    const float d = std::bit_cast<float>(uint32_t(top >> 32));
    const int32_t u = int32_t(uint32_t(top));
    if (s.settled[u] || d > s.dist[u]) continue;
    s.settled[u] = 1;
    if ((++pops & 4095) == 0 && o.cancelled()) return false;
    const glm::vec3 pu = g.point[u];
    if (const int32_t par = s.parent[u]; par >= 0) {
      // The guiding vector is fixed once u's parent is final (Xu & Mould 2015 §B, lazy costs).
      s.hops[u] = s.hops[par] + 1;
      const glm::vec3 e = pu - g.point[par];
      const float el = glm::length(e);
      s.guide[u] = turn_guiding_vector(s.guide[par], el > 0 ? e / el : up, turn_angle(rule, pu, s.hops[u]));
    }
    if (std::binary_search(goal.begin(), goal.end(), u) && --remaining == 0) break;
    int32_t out[8];
    std::copy_n(yao8_edges(g, u), 8, out);
    for (int32_t w : out) {
      if (w < 0 || s.settled[w] || (corridor && (*corridor)[w] < 0)) continue;
      const float nd = d + gv_edge_cost(pu, g.point[w], s.guide[u]);
      if (nd < s.dist[w]) {
        if (s.dist[w] == inf) s.touched.push_back(w);
        s.dist[w] = nd;
        s.parent[w] = u;
        heap.push(key(nd, w));
      }
    }
  }
  return true;
}

tree_skeleton grow_guiding_vectors(const guiding_vectors_params& p_in, const grow_options& o, grow_report* report,
                                   growth_debug* debug) {
  guiding_vectors_params p = p_in;   // growth phases change it from a keyed step on
  grow_report local;
  grow_report& rep = report ? *report : local;
  const int steps = o.steps >= 0 ? o.steps : p.steps;
  tree_skeleton t;
  auto finish = [&](tree_skeleton& tree) -> tree_skeleton& {
    apply_pipe_radii(tree, std::max(p.pipe_exponent, 0.1f), std::max(p.tip_radius, 0.0f), p.pipe_taper);
    if (rep.stop_reason.empty()) {
      rep.stop = rep.hit_node_cap ? grow_stop::node_cap : rep.cancelled ? grow_stop::cancelled : grow_stop::finished;
      rep.stop_reason = rep.hit_node_cap ? "node cap" : rep.cancelled ? "cancelled" : "steps done";
    }
    return tree;
  };

  // The domain stands on the ground, centred on the trunk; the first Poisson point is the root.
  const glm::vec3 size = p.domain_size;
  const glm::vec3 lo(-0.5f * size.x, 0, -0.5f * size.z), hi(0.5f * size.x, size.y, 0.5f * size.z);
  std::vector<glm::vec3> pts;
  std::string why;
  if (!sample_poisson_disc(lo, hi, glm::vec3(0), p.spacing, p.candidates, o.seed, o, pts, &why)) {
    t.add_node(glm::vec3(0), -1, 0, 0, 0);
    if (o.cancelled()) {
      rep.cancelled = true;
    } else {
      rep.error = true;
      rep.message = "guiding vectors: " + why;
      rep.stop = grow_stop::bad_input;
      rep.stop_reason = "no graph";
    }
    return finish(t);
  }
  // Sylva's ground rule: drop the vertices under a cone opening upward from the base, so paths
  // from the root rise at least at slope ground_rise (the root itself is the first point).
  if (p.ground_rise > 0 && pts.size() > 1) {
    const float rise = p.ground_rise, base = std::max(p.ground_base, 0.0f);
    std::erase_if(pts, [&](const glm::vec3& q) {
      const float rho = std::sqrt(q.x * q.x + q.z * q.z);
      return glm::dot(q, q) > 0 && q.y < rise * (rho - base);
    });
  }
  gv_graph g = make_gv_graph(std::move(pts), p.spacing);
  // The searches of the first steps already reach nearly every vertex (7,393 of 7,395 on the
  // default), so the edges are found up front on the job pool rather than one by one in Dijkstra.
  build_all_yao8_edges(g);
  const size_t n = g.point.size();
  int32_t root = 0;
  for (size_t i = 0; i < n; ++i)
    if (glm::dot(g.point[i], g.point[i]) < glm::dot(g.point[root], g.point[root])) root = int32_t(i);

  std::vector<int32_t> tree_node(n, -1), level(n, -1), level_touched;
  std::vector<int32_t> node_vertex;     // graph vertex of each skeleton node
  std::vector<uint8_t> node_has_child;
  std::vector<glm::vec3> node_guide;    // its guiding vector when it joined (overlay arrows)
  t.add_node(g.point[root], -1, 0, 0, 0);
  tree_node[root] = 0;
  node_vertex.push_back(root);
  node_has_child.push_back(0);
  node_guide.push_back(up);

  rng random(o.seed);
  gv_search_state search;
  std::vector<int32_t> sources{root};
  std::vector<glm::vec3> source_guide{up};
  std::vector<int32_t> candidates, endpoints, path, fresh;
  const int node_cap = std::max(p.node_cap, 1);
  bool pruned = false;                  // a cut removed nodes: the tree's vertices are the live ones
  std::vector<int32_t> live_vertices;

  for (int k = 1; k <= steps; ++k) {
    if (o.cancelled()) { rep.cancelled = true; break; }
    if (apply_keyframes(p, o.keyframes, k)) clamp_all_params(p);
    // Pruning: the cut branch's vertices leave the tree, so later searches, border sets and paths
    // can take them again; sources on the cut branch go (the root stands in when none is left).
    if (const std::vector<int32_t> cut = apply_cuts(t, o.cuts, k, rep); !cut.empty()) {
      for (int32_t c : cut) tree_node[node_vertex[size_t(c)]] = -1;
      std::vector<int32_t> kept_sources;
      std::vector<glm::vec3> kept_guides;
      for (size_t i = 0; i < sources.size(); ++i)
        if (tree_node[sources[i]] >= 0) kept_sources.push_back(sources[i]), kept_guides.push_back(source_guide[i]);
      if (kept_sources.empty()) kept_sources.push_back(root), kept_guides.push_back(up);
      sources = std::move(kept_sources);
      source_guide = std::move(kept_guides);
      pruned = true;
    }
    const std::vector<int32_t>* tree_vertices = &node_vertex;
    if (pruned) {
      live_vertices.clear();
      for (size_t j = 0; j < t.size(); ++j)
        if (t.died[j] == never_died) live_vertices.push_back(node_vertex[j]);
      tree_vertices = &live_vertices;
    }
    // Xu & Mould 2015 §D: step 1 samples the volume, later steps the border set B_h.
    candidates.clear();
    for (int32_t v : level_touched) level[v] = -1;
    level_touched.clear();
    const std::vector<int32_t>* corridor = nullptr;
    if (k == 1) {
      for (size_t i = 0; i < n; ++i)
        if (tree_node[i] < 0 && in_volume(p, g.point[i])) candidates.push_back(int32_t(i));
      if (candidates.empty()) {
        // A volume smaller than the point spacing can fall between vertices: it then stands for
        // the vertex nearest its centre, so every published volume size grows a tree.
        int32_t best = -1;
        float best_d2 = 0;
        for (size_t i = 0; i < n; ++i) {
          const glm::vec3 d = g.point[i] - p.volume_offset;
          const float d2 = glm::dot(d, d);
          if (tree_node[i] < 0 && (best < 0 || d2 < best_d2)) best = int32_t(i), best_d2 = d2;
        }
        const float reach = p.volume_outer * std::max({p.volume_scale.x, p.volume_scale.y, p.volume_scale.z});
        if (best >= 0 && std::sqrt(best_d2) <= reach + 2 * p.spacing) candidates.push_back(best);
      }
      if (candidates.empty()) {
        rep.error = true;
        rep.message = "guiding vectors: the endpoint volume contains no graph vertex; move it inside the domain or enlarge it";
        rep.stop = grow_stop::bad_input;
        rep.stop_reason = "empty endpoint volume";
        break;
      }
    } else {
      const int h = std::max(1, int(std::lround(std::clamp(schedule_at(p.step_hops, k, 3), 1.0f, 1e6f))));
      bool stop = false;
      // The search of a later step keeps to the vertices within search_corridor·h hops of the tree
      // (default 2h). Moving along a guiding vector is nearly free, so an unbounded search sweeps
      // the whole domain every step to reach the one costly endpoint; shortest paths to B_h rarely
      // stray that far. search_corridor = 0 is the paper's exact, unbounded search.
      const bool bounded = p.search_corridor > 0;
      const int depth = bounded ? std::max(h, int(std::lround(std::min(p.search_corridor * float(h), 1e6f)))) : h;
      candidates = hop_levels(g, *tree_vertices, h, depth, level, level_touched, o, stop);
      corridor = bounded ? &level : nullptr;
      if (stop) { rep.cancelled = true; break; }
      const float floor_y = g.point[root].y + p.clear_trunk;
      std::erase_if(candidates, [&](int32_t v) { return g.point[v].y < floor_y; });
    }
    const float want_f = std::clamp(schedule_at(p.step_endpoints, k, 0), 0.0f, float(candidates.size()));
    const size_t want = size_t(std::lround(want_f));
    for (size_t i = 0; i < want; ++i)  // partial Fisher–Yates: `want` distinct endpoints
      std::swap(candidates[i], candidates[i + size_t(random.uniform_int(int(candidates.size() - i)))]);
    endpoints.assign(candidates.begin(), candidates.begin() + ptrdiff_t(want));

    gv_turn_rule rule;
    rule.mode = p.t_mode;
    rule.t = glm::radians(schedule_at(p.step_t, k, 0));
    rule.t_end = glm::radians(p.t_end);
    rule.ramp_hops = p.ramp_hops;
    rule.radial_T = p.radial_T;
    rule.axis_origin = g.point[root];
    if (debug)
      for (int32_t v : sources) debug->add_point(g.point[v], 0, debug_kind::source);
    if (!search_gv_paths(g, sources, source_guide, rule, endpoints, search, o, corridor)) {
      rep.cancelled = true;
      break;
    }

    // The union of the paths is a tree: each path is traced back only to the first vertex the tree
    // already holds, so shared prefixes are merged.
    fresh.clear();
    for (int32_t e : endpoints) {
      if (debug) debug->add_point(g.point[e], float(k), debug_kind::endpoint);
      if (!search.settled[e] || tree_node[e] >= 0) continue;
      path.clear();
      int32_t v = e;
      while (v >= 0 && tree_node[v] < 0) {
        path.push_back(v);
        v = search.parent[v];
      }
      if (v < 0) continue;  // cannot happen: every search path starts at a source in the tree
      int32_t attach = tree_node[v];
      const int ord = std::min(255, t.order[attach] + (node_has_child[attach] ? 1 : 0));
      for (size_t j = path.size(); j-- > 0;) {
        if (int64_t(t.size()) >= node_cap) {
          rep.hit_node_cap = true;
          break;
        }
        const int32_t w = path[j];
        const int32_t node = t.add_node(g.point[w], attach, 0, uint16_t(std::min(k, 65534)), uint8_t(ord));
        tree_node[w] = node;
        node_vertex.push_back(w);
        node_has_child.push_back(0);
        node_guide.push_back(search.guide[w]);
        node_has_child[attach] = 1;
        attach = node;
        fresh.push_back(w);
      }
      if (rep.hit_node_cap) break;
    }
    t.steps = k;

    // Xu & Mould 2015 §III: S ← P, here a chosen share of the new path vertices.
    if (!fresh.empty()) {
      sources.clear();
      source_guide.clear();
      for (int32_t w : fresh)
        if (random.uniform() < p.source_fraction) sources.push_back(w);
      if (sources.empty()) sources.push_back(fresh[size_t(random.uniform_int(int(fresh.size())))]);
      for (int32_t w : sources) source_guide.push_back(search.guide[w]);
    }
    if (o.progress) o.progress(float(k) / float(std::max(steps, 1)));
    if (rep.hit_node_cap) break;
  }
  if (rep.hit_node_cap)
    rep.message = "node cap reached (" + std::to_string(node_cap) + " nodes) at step " + std::to_string(t.steps) +
                  "; raise node_cap or use fewer endpoints";

  if (debug) {
    const float arrow = 0.6f * p.spacing;
    const size_t shown = std::min<size_t>(node_vertex.size(), 50000);  // overlays stay drawable
    for (size_t i = 0; i < shown; ++i) {
      const int32_t v = node_vertex[i];
      int32_t out[8];
      std::copy_n(yao8_edges(g, v), 8, out);
      for (int32_t w : out)
        if (w >= 0) debug->add_line(g.point[v], g.point[w], glm::vec3(0.45f), debug_kind::graph_edge);
      add_arrow(*debug, g.point[v], node_guide[i], arrow);
    }
  }
  return finish(t);
}

}  // namespace sylva
