// LOD1-LOD3 from the final tree: a tolerance-driven bark simplifier and a leaf-card merger,
// each searched for the largest mesh within its share of the triangle budget (the leaves' octree
// groups and merged cards: render/mesh/lod_leaves.cpp).
#include "render/mesh/lod.h"
#include "render/mesh/season.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>

#include <glm/geometric.hpp>

#include "render/mesh/lod_cards.h"
#include "render/mesh/lod_leaves.h"
#include "render/assets/textures.h"
#include "generators/vec_util.h"

namespace sylva {
namespace {

using lod_detail::emit_cards;
using lod_detail::group_leaves;
using lod_detail::leaf_input;
using lod_detail::prepare_leaves;

constexpr float pi = 3.14159265f;
// Below this many triangles LOD0 is already cheap: the levels keep it (bad input).
constexpr size_t min_reducible_triangles = 200;


// Parallel transport of frame normal n from tangent t0 to t1 (Bishop 1975), as the mesher does.
glm::vec3 transport(const glm::vec3& n, const glm::vec3& t0, const glm::vec3& t1) {
  const glm::vec3 axis = glm::cross(t0, t1);
  const float s = glm::length(axis), c = glm::dot(t0, t1);
  glm::vec3 r = n;
  if (s > 1e-7f) {
    const glm::vec3 k = axis / s;
    r = n * c + glm::cross(k, n) * s + k * glm::dot(k, n) * (1 - c);
  }
  r -= t1 * glm::dot(r, t1);
  const float len = glm::length(r);
  return len > 1e-7f ? r / len : any_perpendicular(t1);
}

// Radial segments a ring of radius r needs so that the polygon strays at most e from the circle:
// the sagitta of a chord spanning 2*pi/s is r (1 - cos(pi / s)) <= e.
int segments_for(float r, float e, int most) {
  if (!(r > e)) return 3;
  const float s = pi / std::acos(1.0f - e / r);
  return std::clamp(int(std::ceil(s)), 3, most);
}

// The final tree's structure, shared by every level's search.
struct bark_input {
  const tree_skeleton* t = nullptr;
  const std::vector<float>* radius = nullptr;  // LOD0's final_radius
  std::vector<uint8_t> alive;                  // alive at the last step (and its parent too)
  std::vector<int32_t> cont;                   // the child continuing each node's axis, -1 none
  std::vector<glm::vec3> dir;                  // unit direction of the internode parent -> node
  std::vector<uint32_t> starts;                // axis starts: roots and laterals, in index order
  int most_segments = 8;
};

bark_input prepare_bark(const tree_skeleton& t, const tree_mesh& m) {
  bark_input b;
  b.t = &t;
  b.radius = &m.final_radius;
  b.most_segments = std::max(m.radial_segments, 3);
  const size_t n = t.size();
  b.alive.assign(n, 0);
  b.cont.assign(n, -1);
  b.dir.assign(n, glm::vec3(0, 1, 0));
  if (m.final_radius.size() != n || t.parent.size() != n || t.born.size() != n || t.died.size() != n ||
      t.order.size() != n)
    return b;
  const int last = std::max(t.steps, 0);
  for (size_t i = 0; i < n; ++i) {
    const int32_t par = t.parent[i];
    if (par >= int32_t(i) || par < -1) return bark_input{};  // not a skeleton the mesher accepts
    b.alive[i] = t.alive(i, last) && (par < 0 || b.alive[par]) && finite3(t.position[i]);
    if (par < 0) continue;
    const glm::vec3 d = t.position[i] - t.position[par];
    const float len = glm::length(d);
    b.dir[i] = len > 1e-12f && std::isfinite(len) ? d / len : b.dir[par];
  }
  // Same rule as the mesher: the same-order child first, then the most aligned one.
  std::vector<float> best(n, -1e30f);
  for (size_t i = 0; i < n; ++i) {
    const int32_t par = t.parent[i];
    if (par < 0 || !b.alive[i]) continue;
    const float score = (t.order[i] == t.order[par] ? 4.0f : 0.0f) + glm::dot(b.dir[par], b.dir[i]);
    if (score > best[par]) { best[par] = score; b.cont[par] = int32_t(i); }
  }
  for (size_t i = 0; i < n; ++i)
    if (b.alive[i] && (t.parent[i] < 0 || b.cont[t.parent[i]] != int32_t(i))) b.starts.push_back(uint32_t(i));
  return b;
}

// One axis as the level keeps it: the rings (node ids; the first is the base) and the segments.
struct kept_axis {
  int32_t base_parent = -1;       // lateral: its base ring sits at this node; -1 for a root
  uint32_t first = 0;             // the axis's first node (the base ring's radius and node id)
  std::vector<uint32_t> ring;     // kept nodes along the axis
  int segments = 3;
};

// The axes a tolerance e keeps: nodes thinner than e/2 go (with everything above them; a root keeps
// its first span whatever its radius, so that no level loses its trunk), rings whose
// removal moves the axis by less than e go, and each axis gets the segments its base radius needs.
// `lookahead` bounds the chord test so that the cost stays linear.
// With `out` null only the triangles are counted (the search's inner loop allocates nothing).
// `ring_e` (<= e; 0: e) is the chord test's tolerance alone, so that rings can fill a budget the
// next coarser segment count or branch cut would jump past.
void simplify_bark(const bark_input& b, float e, std::vector<kept_axis>* out, size_t& triangles, float ring_e = 0) {
  if (!(ring_e > 0)) ring_e = e;
  if (out) out->clear();
  kept_axis a;
  triangles = 0;
  const tree_skeleton& t = *b.t;
  const std::vector<float>& r = *b.radius;
  const float cut = 0.5f * e;
  constexpr int lookahead = 16;
  static thread_local std::vector<uint32_t> chain;
  for (uint32_t s : b.starts) {
    const int32_t par = t.parent[s];
    if (r[s] < cut && par >= 0) continue;   // a trunk always keeps its first span: the bark floor
    // A lateral needs its parent node kept as a ring of the parent axis or as any node with r >= cut.
    if (par >= 0 && r[par] < cut) continue;
    chain.clear();
    for (int32_t i = int32_t(s); i >= 0 && b.alive[i] && (r[i] >= cut || (par < 0 && chain.size() < 2)); i = b.cont[i])
      chain.push_back(uint32_t(i));
    a.ring.clear();
    a.base_parent = par;
    a.first = s;
    a.segments = segments_for(r[s], e, b.most_segments);
    // Greedy chord simplification: extend the span from the last kept point while every skipped
    // node stays within e of the chord, in position and in radius (within the lookahead).
    glm::vec3 from = par >= 0 ? t.position[par] : t.position[chain[0]];
    float from_r = r[s];
    size_t k = 0;
    if (par < 0) { a.ring.push_back(chain[0]); k = 1; }   // a root's first node is its base ring
    size_t first_skipped = k;
    auto keep = [&](size_t j) {
      a.ring.push_back(chain[j]);
      from = t.position[chain[j]];
      from_r = r[chain[j]];
      first_skipped = k = j + 1;
    };
    while (k < chain.size()) {
      const size_t j = k;   // can chain[first_skipped..j] be skipped by a chord to chain[j + 1]?
      if (j + 1 >= chain.size() || int(j + 1 - first_skipped) > lookahead) { keep(j); continue; }
      const glm::vec3 d = t.position[chain[j + 1]] - from;
      const float len2 = glm::dot(d, d), to_r = r[chain[j + 1]];
      bool ok = true;
      for (size_t q = first_skipped; q <= j && ok; ++q) {
        const glm::vec3 p = t.position[chain[q]];
        const float u = len2 > 0 ? std::clamp(glm::dot(p - from, d) / len2, 0.0f, 1.0f) : 0.0f;
        ok = glm::length(p - (from + u * d)) <= ring_e && std::abs(r[chain[q]] - (from_r + u * (to_r - from_r))) <= ring_e;
      }
      if (ok) ++k;
      else keep(j);
    }
    const size_t spans = par >= 0 ? a.ring.size() : (a.ring.empty() ? 0 : a.ring.size() - 1);
    triangles += spans * size_t(2 * a.segments);
    if (out && !a.ring.empty()) out->push_back(a);
  }
}

// Writes the kept axes as tube geometry into m (bark arrays, index sorted by born, index_end).
void emit_bark(const bark_input& b, const std::vector<kept_axis>& axes, const mesh_params& mp, tree_mesh& m) {
  const tree_skeleton& t = *b.t;
  const std::vector<float>& r = *b.radius;
  const float uv_repeat = std::isfinite(mp.uv_repeat) ? mp.uv_repeat : 1.0f;
  struct span { uint32_t lo, hi, born; int seg; };
  std::vector<span> spans;
  std::vector<float> vcoord(t.size(), 0.0f);   // arc length * uv_repeat along the kept rings
  auto emit_ring = [&](const glm::vec3& c, const glm::vec3& tan, const glm::vec3& nrm, float rad, float v, uint32_t node,
                       int seg, float wraps) {
    const glm::vec3 bin = glm::cross(tan, nrm);
    const uint32_t start = uint32_t(m.position.size());
    for (int k = 0; k <= seg; ++k) {
      const float a = 2 * pi * float(k % seg) / float(seg);
      const glm::vec3 d = nrm * std::cos(a) + bin * std::sin(a);
      m.position.push_back(c + d * rad);
      m.normal.push_back(d);
      m.uv.push_back({float(k) / float(seg) * wraps, v});
      m.node.push_back(node);
    }
    // Padding up to LOD0's ring stride with copies of the seam vertex, unindexed: exporters find a
    // vertex's ring neighbours by that stride (render/io/export.cpp, tangents).
    for (int k = seg + 1; k <= b.most_segments; ++k) {
      m.position.push_back(m.position[start]);
      m.normal.push_back(m.normal[start]);
      m.uv.push_back(m.uv[start + uint32_t(seg)]);
      m.node.push_back(node);
    }
    return start;
  };
  for (const kept_axis& a : axes) {
    const int seg = a.segments;
    const float wraps = std::clamp(std::round(2 * pi * r[a.first] * std::abs(uv_repeat)), 1.0f, 64.0f);
    // Points of the axis: the base (parent node for a lateral), then the kept rings.
    const size_t np = a.ring.size() + (a.base_parent >= 0 ? 1 : 0);
    auto point = [&](size_t k) {
      if (a.base_parent >= 0) return k == 0 ? t.position[a.base_parent] : t.position[a.ring[k - 1]];
      return t.position[a.ring[k]];
    };
    auto node_of = [&](size_t k) { return a.base_parent >= 0 ? (k == 0 ? a.first : a.ring[k - 1]) : a.ring[k]; };
    std::vector<glm::vec3> dir(np);
    for (size_t k = 1; k < np; ++k) {
      const glm::vec3 d = point(k) - point(k - 1);
      const float len = glm::length(d);
      dir[k] = len > 1e-12f && std::isfinite(len) ? d / len : (k > 1 ? dir[k - 1] : b.dir[node_of(k)]);
    }
    dir[0] = np > 1 ? dir[1] : b.dir[node_of(0)];
    glm::vec3 frame = any_perpendicular(dir[0]), prev_tan = dir[0];
    float v = a.base_parent >= 0 ? vcoord[a.base_parent] : 0.0f;
    uint32_t prev_ring = 0;
    for (size_t k = 0; k < np; ++k) {
      glm::vec3 tan = dir[k];
      if (k > 0 && k + 1 < np) {
        const glm::vec3 sum = dir[k] + dir[k + 1];
        if (glm::length(sum) > 1e-4f) tan = glm::normalize(sum);
      }
      frame = transport(frame, prev_tan, tan);
      prev_tan = tan;
      if (k > 0) v += glm::length(point(k) - point(k - 1)) * uv_repeat;
      const uint32_t node = node_of(k);
      vcoord[node] = v;
      // A lateral's base ring takes the lateral's radius (as the mesher's does).
      const uint32_t ring = emit_ring(point(k), tan, frame, r[node], v, node, seg, wraps);
      if (k > 0) spans.push_back({prev_ring, ring, t.born[node], seg});
      prev_ring = ring;
    }
  }
  // Sorted by born so that step s draws a prefix, as LOD0 (DESIGN §5).
  std::stable_sort(spans.begin(), spans.end(), [](const span& x, const span& y) { return x.born < y.born; });
  size_t k = 0;
  for (int s = 0; s <= m.steps; ++s) {
    for (; k < spans.size() && (int(spans[k].born) <= s || s == m.steps); ++k) {
      const span& q = spans[k];
      for (int j = 0; j < q.seg; ++j) {
        const uint32_t a = q.lo + j, b2 = q.lo + j + 1, c = q.hi + j, d = q.hi + j + 1;
        m.index.insert(m.index.end(), {a, b2, c, b2, d, c});
      }
    }
    m.index_end[size_t(s)] = uint32_t(m.index.size());
  }
}

// Why level k's `got` triangles miss its budget `target` by more than lod_budget_tolerance ("" when
// they do not): the floor that kept it higher (the coarsest bark, one card for the leaves) or what
// kept it lower, each with its triangles.
std::string budget_note(int k, size_t got, size_t target, size_t bark_floor, size_t bark_target, size_t bark_tris,
                        size_t cards, size_t leaves) {
  if (target == 0) return "";
  const double off = (double(got) - double(target)) / double(target);
  if (std::abs(off) <= lod_budget_tolerance) return "";
  char buf[320];
  if (off > 0) {
    if (bark_tris > bark_target)
      std::snprintf(buf, sizeof buf,
                    "LOD%d: %zu triangles, %.0f%% over its budget of %zu: the bark floor (trunk and limbs at their coarsest) "
                    "keeps %zu where the bark's share was %zu, and the leaf floor (at least one card) %zu",
                    k, got, 100 * off, target, bark_floor, bark_target, cards * exported_card_triangles);
    else
      std::snprintf(buf, sizeof buf, "LOD%d: %zu triangles, %.0f%% over its budget of %zu: the leaf floor (at least one card) keeps %zu",
                    k, got, 100 * off, target, cards * exported_card_triangles);
  } else if (cards >= leaves) {
    std::snprintf(buf, sizeof buf, "LOD%d: %zu triangles, %.0f%% under its budget of %zu: it keeps all %zu leaves and %zu bark triangles, "
                  "and finer bark would pass the budget", k, got, -100 * off, target, leaves, bark_tris);
  } else {
    std::snprintf(buf, sizeof buf, "LOD%d: %zu triangles, %.0f%% under its budget of %zu: the leaves' octree cells part no finer "
                  "within it (%zu cards for %zu leaves)", k, got, -100 * off, target, cards, leaves);
  }
  return buf;
}

float clamp_budget(float v, int level, std::string& message) {
  float c = std::isfinite(v) ? std::clamp(v, 1.0f, 100.0f) : 40.0f;
  if (c != v) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "LOD%d budget %g%% is outside 1-100%%: using %g%%", level, double(v), double(c));
    message += (message.empty() ? "" : "; ") + std::string(buf);
  }
  return c;
}

}  // namespace

size_t final_triangles(const tree_mesh& m) {
  if (m.index_end.empty()) return exported_card_triangles * m.leaves.size() + m.index.size() / 3;
  const size_t s = m.index_end.size() - 1;
  size_t leaves = 0;
  for (const leaf_instance& l : m.leaves) leaves += int(l.born) <= m.steps && m.steps < int(l.died);
  return m.index_end[s] / 3 + exported_card_triangles * leaves;
}

lod_chain build_lods(const tree_skeleton& t, const tree_mesh& m, const mesh_params& mp, const lod_params& p) {
  lod_chain c;
  c.budget = {100, clamp_budget(p.lod1_budget, 1, c.message), clamp_budget(p.lod2_budget, 2, c.message),
              clamp_budget(p.lod3_budget, 3, c.message)};
  // Coverage: a level with a budget of b (fraction of LOD0) has b times LOD0's triangles per
  // pixel of screen when its coverage is sqrt(b), LOD0 being meant to fill the view's height
  // (triangles per pixel constant, pixels growing as coverage squared).
  for (int k = 0; k + 1 < lod_levels; ++k) c.coverage[size_t(k)] = std::sqrt(c.budget[size_t(k) + 1] / 100.0f);
  c.coverage[3] = 0.5f * c.coverage[2];
  c.impostor_coverage = 0.1f * c.coverage[3];   // the impostor down to a few pixels, then culled

  const size_t t0 = final_triangles(m);
  c.triangles[0] = c.target[0] = t0;
  const size_t bark0 = m.index_end.empty() ? 0 : m.index_end.back() / 3;
  auto keep_lod0 = [&](const std::string& why) {
    for (int k = 1; k < lod_levels; ++k) {
      c.level[size_t(k) - 1] = m;
      c.triangles[size_t(k)] = t0;
      c.target[size_t(k)] = size_t(double(t0) * c.budget[size_t(k)] / 100.0);
      c.note[size_t(k)] = "LOD" + std::to_string(k) + ": " + why;
    }
    c.reduced = false;
    c.message += (c.message.empty() ? "" : "; ") + why;
    return c;
  };
  if (t0 < min_reducible_triangles)
    return keep_lod0("tree too small to reduce (" + std::to_string(t0) + " triangles): LOD1-LOD3 keep LOD0");

  const bark_input bark = prepare_bark(t, m);
  if (bark.alive.empty() || bark.starts.empty())
    return keep_lod0("tree has no bark the levels can reduce: LOD1-LOD3 keep LOD0");
  const leaf_input leaves = prepare_leaves(m);
  const glm::vec3 extent = m.bounds_max - m.bounds_min;
  const float size = std::max({extent.x, extent.y, extent.z, 1e-3f});
  const uint8_t card_texture = uint8_t(std::clamp(int(mp.leaves.cluster_archetype), 0, leaf_archetype_count - 1));

  c.reduced = true;
  std::vector<kept_axis> axes;
  // Merged cards get textures baked from the tree's own leaves (render/mesh/lod_cards.h), shared by the
  // three levels (every level's mesh points at the same set).
  auto baked = std::make_shared<baked_card_textures>();
  for (int k = 1; k < lod_levels; ++k) {
    const float b = c.budget[size_t(k)] / 100.0f;
    const size_t target = size_t(double(t0) * b);
    c.target[size_t(k)] = target;
    // The bark gets 0.3 of its share of LOD0 (most of it hides inside the crown) and the leaves what
    // it leaves: measured on the oak, LOD1's silhouette IoU goes from 0.83 (full share) to 0.97; pine
    // LOD1 from 0.96 (half share) to 0.97 (docs/LOD.md).
    // When every leaf fits anyway, the bark takes the rest.
    const size_t all_leaves = exported_card_triangles * leaves.leaves.size();
    const size_t bark_target = std::max(size_t(0.3 * double(bark0) * b), target > all_leaves ? target - all_leaves : 0);
    // Largest mesh within budget: bisect the tolerance (log scale) between 1e-6 and 1x the tree.
    float lo = std::log(1e-6f * size), hi = std::log(size);
    size_t tris = 0;
    simplify_bark(bark, std::exp(hi), nullptr, tris);
    const size_t bark_floor = tris;   // the coarsest bark: the trunk's 3 sides, the limbs thicker than half the tree
    const bool reachable = tris <= bark_target;
    for (int it = 0; it < 16 && reachable; ++it) {   // 2^-16 of the log range: within 0.03 % in e
      const float mid = 0.5f * (lo + hi);
      simplify_bark(bark, std::exp(mid), nullptr, tris);
      if (tris <= bark_target) hi = mid; else lo = mid;
    }
    // The finer tolerance passes the bark's share, often by a whole step of segments or cut branches:
    // more rings at the chosen segments and cut fill what is left (log bisection of the ring
    // tolerance alone).
    float ring = hi;
    if (reachable && lo > std::log(1e-6f * size)) {
      float rlo = std::log(1e-6f * size), rhi = hi;
      for (int it = 0; it < 16; ++it) {
        const float mid = 0.5f * (rlo + rhi);
        simplify_bark(bark, std::exp(hi), nullptr, tris, std::exp(mid));
        if (tris <= bark_target) rhi = mid; else rlo = mid;
      }
      ring = rhi;
    }
    simplify_bark(bark, std::exp(hi), &axes, tris, std::exp(ring));
    tree_mesh& out = c.level[size_t(k) - 1];
    out.steps = m.steps;
    out.radial_segments = m.radial_segments;
    out.final_radius = m.final_radius;
    out.index_end.assign(size_t(m.steps) + 1, 0);
    out.leaf_end.assign(size_t(m.steps) + 1, 0);
    out.position.reserve(tris * 2);
    emit_bark(bark, axes, mp, out);
    const size_t bark_tris = out.index.size() / 3;
    const size_t cards = (target > bark_tris ? target - bark_tris : 0) / exported_card_triangles;
    // A merged card stands for its leaves' area; 1.0 keeps the total card area of LOD0.
    emit_cards(leaves, group_leaves(leaves, std::max<size_t>(cards, leaves.leaves.empty() ? 0 : 1)), card_texture, 1.0f,
               *baked, out);
    out.cards = baked;
    out.bounds_min = m.bounds_min;
    out.bounds_max = m.bounds_max;
    bake_crown_occlusion(out);
    c.triangles[size_t(k)] = final_triangles(out);
    c.note[size_t(k)] = budget_note(k, c.triangles[size_t(k)], target, bark_floor, bark_target, bark_tris,
                                    out.leaves.size(), leaves.leaves.size());
    if (!c.note[size_t(k)].empty()) c.message += (c.message.empty() ? "" : "; ") + c.note[size_t(k)];
  }
  return c;
}

std::string lod_summary(const lod_chain& c) {
  const auto& n = c.triangles;
  auto share = [&](int k) { return n[0] ? 100.0 * double(n[size_t(k)]) / double(n[0]) : 0.0; };
  char buf[240];
  std::snprintf(buf, sizeof buf, "LOD0-3 triangles %zu / %zu / %zu / %zu (%.1f / %.1f / %.1f %% of LOD0; budgets %g / %g / %g %%)",
                n[0], n[1], n[2], n[3], share(1), share(2), share(3), double(c.budget[1]), double(c.budget[2]),
                double(c.budget[3]));
  return buf;
}

float screen_coverage(float radius, float distance, float fov_degrees) {
  const float t = std::tan(0.5f * fov_degrees * pi / 180.0f);
  if (!(distance > 0) || !(t > 0) || !std::isfinite(radius)) return 1.0f;
  return radius / (distance * t);
}

int pick_lod(const lod_chain& c, float coverage, float bias) {
  const float cov = coverage * std::exp2(-(std::isfinite(bias) ? std::clamp(bias, -8.0f, 8.0f) : 0.0f));
  for (int k = 0; k < lod_levels; ++k)
    if (cov >= c.coverage[size_t(k)]) return k;
  return lod_levels;
}

}  // namespace sylva
