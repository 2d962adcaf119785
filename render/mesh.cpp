// Skeleton -> generalized-cylinder bark (one ring per node) and leaf instances, sorted by birth step.
#include "render/mesh.h"

#include "generators/wood.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "generators/vec_util.h"

namespace sylva {
namespace {

constexpr glm::vec3 up_axis{0, 1, 0};

// Parallel transport (Bishop 1975; Wang et al. 2008): carry normal n from unit tangent t0 to t1 by
// the smallest rotation between them, so rings along an axis do not twist.
glm::vec3 transport(const glm::vec3& n, const glm::vec3& t0, const glm::vec3& t1) {
  const glm::vec3 axis = glm::cross(t0, t1);
  const float s = glm::length(axis), c = glm::dot(t0, t1);
  glm::vec3 r = n;
  if (s > 1e-7f) {
    const glm::vec3 k = axis / s;  // Rodrigues' rotation formula
    r = n * c + glm::cross(k, n) * s + k * glm::dot(k, n) * (1 - c);
  }
  r -= t1 * glm::dot(r, t1);  // re-orthogonalise against rounding drift
  const float len = glm::length(r);
  return len > 1e-7f ? r / len : any_perpendicular(t1);
}

bool finite3(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// The minimum the mesher needs to index safely; anything else degrades the picture, not memory.
bool structurally_sound(const tree_skeleton& t) {
  const size_t n = t.position.size();
  if (t.parent.size() != n || t.radius.size() != n || t.born.size() != n || t.died.size() != n ||
      t.order.size() != n)
    return false;
  for (size_t i = 0; i < n; ++i)
    if (t.parent[i] < -1 || t.parent[i] >= int32_t(i)) return false;
  return true;
}

// Stable counting sort of `count` items by a born step clamped into 0..steps; writes the
// per-step "end" table (size steps+1) and returns the permutation (order[k] = item index).
template <class BornOf>
std::vector<uint32_t> sort_by_born(size_t count, int steps, BornOf born_of, std::vector<uint32_t>& end) {
  end.assign(size_t(steps) + 1, 0);
  for (size_t k = 0; k < count; ++k) ++end[std::min<int>(born_of(k), steps)];
  for (int s = 1; s <= steps; ++s) end[s] += end[s - 1];
  std::vector<uint32_t> cursor(size_t(steps) + 1, 0);
  for (int s = 1; s <= steps; ++s) cursor[s] = end[s - 1];
  std::vector<uint32_t> perm(count);
  for (size_t k = 0; k < count; ++k) perm[cursor[std::min<int>(born_of(k), steps)]++] = uint32_t(k);
  return perm;
}

}  // namespace

tree_mesh mesh_tree(const tree_skeleton& t, const mesh_params& p, uint64_t seed) {
  tree_mesh m;
  m.steps = std::max(t.steps, 0);
  m.radial_segments = std::clamp(p.radial_segments, 3, 256);
  m.index_end.assign(size_t(m.steps) + 1, 0);
  m.leaf_end.assign(size_t(m.steps) + 1, 0);
  if (!structurally_sound(t)) return m;

  const size_t n = t.size();
  const int seg = m.radial_segments, stride = seg + 1;
  const float min_radius = std::isfinite(p.min_radius) && p.min_radius > 0 ? p.min_radius : 1e-5f;
  const float uv_repeat = std::isfinite(p.uv_repeat) ? p.uv_repeat : 1.0f;

  // Radii of the final tree; shed nodes (radius 0 there) keep their recorded radius or the minimum.
  m.final_radius = t.pipe_exponent > 0 ? radii_at_step(t, m.steps) : t.radius;
  for (size_t i = 0; i < n; ++i) {
    float r = m.final_radius[i] > 0 ? m.final_radius[i] : t.radius[i];
    m.final_radius[i] = r >= min_radius ? r : min_radius;  // NaN lands here too
  }

  // Unit direction of each internode (parent -> node); roots and zero-length ones inherit.
  std::vector<glm::vec3> dir(n);
  for (size_t i = 0; i < n; ++i) {
    const int32_t par = t.parent[i];
    assert(par < int32_t(i) && "mesh_tree: parent[i] < i (structurally_sound lets no other skeleton in)");
    if (par < 0) { dir[i] = up_axis; continue; }
    const glm::vec3 d = t.position[i] - t.position[par];
    const float len = glm::length(d);
    dir[i] = len > 1e-12f && std::isfinite(len) ? d / len : dir[par];
  }
  // The child continuing each node's axis: same order first, then the most aligned. The others are
  // laterals and get their own base ring, sunk into the parent tube, instead of sharing its ring.
  std::vector<int32_t> cont(n, -1);
  std::vector<float> best(n, -1e30f);
  for (size_t i = 0; i < n; ++i) {
    const int32_t par = t.parent[i];
    if (par < 0) continue;
    const float score = (t.order[i] == t.order[par] ? 4.0f : 0.0f) + glm::dot(dir[par], dir[i]);
    if (score > best[par]) { best[par] = score; cont[par] = int32_t(i); }
  }
  size_t rings = n;
  for (size_t i = 0; i < n; ++i)
    if (t.parent[i] >= 0 && cont[t.parent[i]] != int32_t(i)) ++rings;

  // Sized once and written through pointers: this loop is the mesher's hot path.
  const size_t nv = rings * size_t(stride);
  m.position.resize(nv);
  m.normal.resize(nv);
  m.uv.resize(nv);
  m.node.resize(nv);
  glm::vec3* out_pos = m.position.data();
  glm::vec3* out_nrm = m.normal.data();
  glm::vec2* out_uv = m.uv.data();
  uint32_t* out_node = m.node.data();
  uint32_t emitted = 0;

  std::vector<float> cos_a(stride), sin_a(stride), u_of(stride);
  for (int k = 0; k < stride; ++k) {
    const float a = 6.2831853f * float(k % seg) / float(seg);  // k = seg repeats k = 0 exactly
    cos_a[k] = std::cos(a);
    sin_a[k] = std::sin(a);
    u_of[k] = float(k) / float(seg);
  }
  // Constant texel density from trunk to twig: the texture wraps round(circumference * uv_repeat)
  // times around each axis (at least once), counted at the axis's base so it never jumps along it.
  std::vector<float> wraps(n, 1.0f);
  for (size_t i = 0; i < n; ++i) {
    const int32_t par = t.parent[i];
    if (par >= 0 && cont[par] == int32_t(i)) { wraps[i] = wraps[par]; continue; }
    const float w = std::round(6.2831853f * m.final_radius[i] * std::abs(uv_repeat));
    wraps[i] = std::isfinite(w) ? std::clamp(w, 1.0f, 64.0f) : 1.0f;
  }
  auto emit_ring = [&](const glm::vec3& c, const glm::vec3& tan, const glm::vec3& nrm, float r, float v,
                       uint32_t node) {
    const glm::vec3 bin = glm::cross(tan, nrm);
    const float w = wraps[node];
    for (int k = 0; k < stride; ++k) {
      const glm::vec3 d = nrm * cos_a[k] + bin * sin_a[k];
      out_pos[emitted] = c + d * r;
      out_nrm[emitted] = d;
      out_uv[emitted] = {u_of[k] * w, v};
      out_node[emitted] = node;
      ++emitted;
    }
  };

  std::vector<glm::vec3> tangent(n), frame(n);
  std::vector<float> vcoord(n, 0.0f);
  std::vector<uint32_t> ring_start(n, 0), base_start(n, 0);
  for (size_t i = 0; i < n; ++i) {
    const int32_t par = t.parent[i];
    // The ring's axis bisects the incoming and the continuing internode, so joints bend smoothly.
    glm::vec3 tan = par < 0 ? (cont[i] >= 0 ? dir[cont[i]] : up_axis) : dir[i];
    if (par >= 0 && cont[i] >= 0) {
      const glm::vec3 sum = dir[i] + dir[cont[i]];
      const float len = glm::length(sum);
      if (len > 1e-4f) tan = sum / len;
    }
    tangent[i] = tan;
    if (par < 0) {
      frame[i] = any_perpendicular(tan);
    } else {
      glm::vec3 from_t = tangent[par], from_n = frame[par];
      vcoord[i] = vcoord[par] + glm::length(t.position[i] - t.position[par]) * uv_repeat;
      if (cont[par] == int32_t(i)) {
        base_start[i] = ring_start[par];
      } else {
        // Lateral: its own base ring at the parent node, along the child, with the child's radius.
        const glm::vec3 bn = transport(from_n, from_t, dir[i]);
        base_start[i] = emitted;
        emit_ring(t.position[par], dir[i], bn, m.final_radius[i], vcoord[par], uint32_t(i));
        from_t = dir[i];
        from_n = bn;
      }
      frame[i] = transport(from_n, from_t, tan);
    }
    ring_start[i] = emitted;
    emit_ring(t.position[i], tan, frame[i], m.final_radius[i], vcoord[i], uint32_t(i));
  }

  // Internodes sorted by born step so that step s draws a prefix of the index buffer (DESIGN §5).
  std::vector<uint32_t> internode;
  internode.reserve(n);
  for (size_t i = 0; i < n; ++i)
    if (t.parent[i] >= 0) internode.push_back(uint32_t(i));
  const std::vector<uint32_t> perm =
      sort_by_born(internode.size(), m.steps, [&](size_t k) { return int(t.born[internode[k]]); }, m.index_end);
  const uint32_t per = uint32_t(6 * seg);
  for (uint32_t& e : m.index_end) e *= per;
  m.index.resize(internode.size() * per);
  uint32_t* out = m.index.data();
  for (uint32_t k : perm) {
    const uint32_t i = internode[k], lo = base_start[i], hi = ring_start[i];
    for (int s = 0; s < seg; ++s) {
      const uint32_t a = lo + s, b = lo + s + 1, c = hi + s, d = hi + s + 1;  // CCW from outside
      *out++ = a; *out++ = b; *out++ = c;
      *out++ = b; *out++ = d; *out++ = c;
    }
  }

  // Leaves: the foliage model (leaves.h) or the generator's own, capped at the leaf cap.
  if (p.leaves_enabled) {
    foliage placed;
    const bool own = p.leaves.mode == leaf_mode::generator && !t.leaves.empty();
    if (!own) placed = place_leaves(t, p.leaves, seed);
    const std::vector<leaf>& src = own ? t.leaves : placed.leaves;   // the generator's, uncopied
    const size_t cap = size_t(std::clamp(p.leaves.cap, 1, 2000000));
    // Counting sort by born straight into m.leaves (no temporary copy of every leaf).
    auto usable = [&](const leaf& l) { return l.node >= 0 && size_t(l.node) < n && finite3(l.position); };
    auto step_of = [&](const leaf& l) { return std::min<int>(l.born, m.steps); };
    size_t kept = 0, end = src.size();
    for (size_t k = 0; k < src.size(); ++k) {
      if (!usable(src[k])) continue;
      if (kept == cap) { end = k; placed.capped = true; break; }
      ++kept;
      ++m.leaf_end[step_of(src[k])];
    }
    if (placed.capped)
      m.message = "leaf cap reached: " + std::to_string(kept) + " leaves placed (raise Leaf cap or Leaf spacing)";
    std::vector<uint32_t> cursor(m.leaf_end.size(), 0);
    for (size_t s = 1; s < m.leaf_end.size(); ++s) {
      m.leaf_end[s] += m.leaf_end[s - 1];
      cursor[s] = m.leaf_end[s - 1];
    }
    m.leaves.resize(m.leaf_end.back());
    const float scale = std::isfinite(p.leaf_scale) ? p.leaf_scale : 1.0f;
    const uint8_t fallback = uint8_t(std::clamp(int(p.leaves.archetype), 0, leaf_archetype_count - 1));
    for (size_t k = 0; k < end; ++k) {
      const leaf& l = src[k];
      if (!usable(l)) continue;
      const glm::quat q = l.orientation;
      const uint8_t tex = l.archetype < leaf_archetype_count ? l.archetype : fallback;  // texture = archetype
      m.leaves[cursor[step_of(l)]++] = {l.position, glm::vec4(q.x, q.y, q.z, q.w), l.size * scale, l.born, l.died,
                                        uint32_t(l.node), tex};
    }
  }

  if (!m.position.empty() || !m.leaves.empty()) {
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const glm::vec3& v : m.position) { lo = glm::min(lo, v); hi = glm::max(hi, v); }
    for (const leaf_instance& l : m.leaves) {
      lo = glm::min(lo, l.position - glm::vec3(l.size));
      hi = glm::max(hi, l.position + glm::vec3(l.size));
    }
    m.bounds_min = lo;
    m.bounds_max = hi;
  }
  bake_crown_occlusion(m);
  return m;
}

void bake_crown_occlusion(tree_mesh& m) {
  m.occlusion.assign(m.position.size(), 1.0f);
  if (m.leaves.empty()) return;   // no crown: nothing shades the sky
  glm::vec3 lo(1e30f), hi(-1e30f);
  for (const leaf_instance& l : m.leaves) { lo = glm::min(lo, l.position); hi = glm::max(hi, l.position); }
  const glm::vec3 c = 0.5f * (lo + hi), inv = 1.0f / glm::max(0.5f * (hi - lo), glm::vec3(0.05f));
  auto visibility = [&](const glm::vec3& p) {
    const float d = glm::length((p - c) * inv);
    return std::isfinite(d) ? 0.35f + 0.65f * std::min(d, 1.0f) : 1.0f;
  };
  for (size_t i = 0; i < m.position.size(); ++i) m.occlusion[i] = visibility(m.position[i]);
  for (leaf_instance& l : m.leaves) l.occlusion = uint8_t(std::lround(255.0f * visibility(l.position)));
}

std::string validate_mesh(const tree_mesh& m) {
  const size_t nv = m.position.size();
  if (m.normal.size() != nv || m.uv.size() != nv || m.node.size() != nv) return "vertex arrays differ in size";
  if (m.index.size() % 3) return "index count is not a multiple of 3";
  for (size_t k = 0; k < m.index.size(); ++k)
    if (m.index[k] >= nv) return "index " + std::to_string(k) + " is out of range";
  for (size_t v = 0; v < nv; ++v) {
    if (!finite3(m.position[v]) || !finite3(m.normal[v]) || !std::isfinite(m.uv[v].x) || !std::isfinite(m.uv[v].y))
      return "vertex " + std::to_string(v) + " is not finite";
    if (m.node[v] >= m.final_radius.size()) return "vertex " + std::to_string(v) + " names no node";
  }
  const size_t table = size_t(std::max(m.steps, 0)) + 1;
  if (m.index_end.size() != table || m.leaf_end.size() != table) return "step tables are not steps+1 long";
  for (size_t s = 1; s < table; ++s)
    if (m.index_end[s] < m.index_end[s - 1] || m.leaf_end[s] < m.leaf_end[s - 1]) return "step tables are not monotone";
  if (m.index_end.back() != m.index.size()) return "index_end does not end at the index count";
  if (m.leaf_end.back() != m.leaves.size()) return "leaf_end does not end at the leaf count";
  for (size_t k = 0; k < m.leaves.size(); ++k) {
    const leaf_instance& l = m.leaves[k];
    if (!finite3(l.position) || !std::isfinite(l.size)) return "leaf " + std::to_string(k) + " is not finite";
    const size_t s = std::min<size_t>(l.born, table - 1);
    if (k >= m.leaf_end[s] || (s > 0 && k < m.leaf_end[s - 1])) return "leaves are not sorted by born";
  }
  return "";
}

namespace {
// Old index -> new index for the nodes alive at `step`, -1 for the others.
std::vector<int32_t> alive_remap(const tree_skeleton& t, int step, size_t& count) {
  std::vector<int32_t> remap(t.size(), -1);
  count = 0;
  for (size_t i = 0; i < t.size(); ++i)
    if (t.alive(i, step) && (t.parent[i] < 0 || remap[t.parent[i]] >= 0)) remap[i] = int32_t(count++);
  return remap;
}
}  // namespace

tree_skeleton skeleton_at_step(const tree_skeleton& t, int step) {
  tree_skeleton out;
  if (!structurally_sound(t)) return out;
  step = std::clamp(step, 0, std::max(t.steps, 0));
  size_t count = 0;
  const std::vector<int32_t> remap = alive_remap(t, step, count);
  const std::vector<float> r = radii_at_step(t, step);
  const std::vector<glm::vec3> x = positions_at_step(t, step);   // the bend of that step (wood.h)
  out.reserve(count);
  for (size_t i = 0; i < t.size(); ++i) {
    if (remap[i] < 0) continue;
    out.add_node(x[i], t.parent[i] < 0 ? -1 : remap[t.parent[i]], r[i], t.born[i], t.order[i]);
    out.died.back() = t.died[i];
  }
  for (const leaf& l : t.leaves) {
    if (l.node < 0 || size_t(l.node) >= t.size() || remap[l.node] < 0) continue;
    if (!(l.born <= step && step < l.died)) continue;
    leaf c = l;
    c.node = remap[l.node];
    c.position += x[size_t(l.node)] - t.position[size_t(l.node)];
    out.leaves.push_back(c);
  }
  out.pipe_exponent = t.pipe_exponent;
  out.pipe_tip_radius = t.pipe_tip_radius;
  out.steps = step;
  out.tree_count = 0;
  for (int32_t par : out.parent) out.tree_count += par < 0;
  return out;
}

tree_mesh mesh_tree_at_step(const tree_skeleton& t, const tree_mesh& full, const mesh_params& p, int step) {
  if (!structurally_sound(t)) return full;
  step = std::clamp(step < 0 ? t.steps : step, 0, std::max(t.steps, 0));
  tree_skeleton s = skeleton_at_step(t, step);
  s.leaves.clear();
  mesh_params bark_only = p;
  bark_only.leaves_enabled = false;
  tree_mesh m = mesh_tree(s, bark_only);
  size_t count = 0;
  const std::vector<int32_t> remap = alive_remap(t, step, count);
  // Leaves were placed on the final bend: they follow their node to its place at `step`.
  const std::vector<glm::vec3> x = t.wood ? positions_at_step(t, step) : std::vector<glm::vec3>();
  for (const leaf_instance& l : full.leaves) {  // already sorted by born, so the filter stays sorted
    if (!(l.born <= step && step < l.died) || l.node >= remap.size() || remap[l.node] < 0) continue;
    leaf_instance c = l;
    if (!x.empty()) c.position += x[l.node] - t.position[l.node];
    c.node = uint32_t(remap[l.node]);
    m.leaves.push_back(c);
    ++m.leaf_end[std::min<int>(l.born, step)];
  }
  for (int k = 1; k <= step; ++k) m.leaf_end[k] += m.leaf_end[k - 1];
  bake_crown_occlusion(m);   // from the crown of this step's leaves
  return m;
}

}  // namespace sylva
