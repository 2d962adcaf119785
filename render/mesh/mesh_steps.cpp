// The mesh after mesh_tree: crown occlusion, the invariant check, and the tree (and its mesh) at an
// earlier growth step for export.
#include <algorithm>
#include <cmath>

#include "generators/vec_util.h"
#include "generators/wood.h"
#include "render/mesh/mesh.h"

namespace sylva {

uint64_t mesh_digest(const tree_mesh& m) {
  uint64_t h = 0xcbf29ce484222325ull;
  auto bytes = [&](const void* data, size_t size) {
    const unsigned char* b = static_cast<const unsigned char*>(data);
    for (size_t k = 0; k < size; ++k) h = (h ^ b[k]) * 0x100000001b3ull;
  };
  auto all = [&](const auto& v) {
    const uint64_t count = v.size();
    bytes(&count, sizeof count);
    if (!v.empty()) bytes(v.data(), v.size() * sizeof v[0]);
  };
  all(m.position), all(m.normal), all(m.uv), all(m.node), all(m.occlusion), all(m.index), all(m.index_end);
  for (const leaf_instance& l : m.leaves) {   // field by field: the struct has padding
    bytes(&l.position, sizeof l.position), bytes(&l.orientation, sizeof l.orientation), bytes(&l.size, sizeof l.size);
    bytes(&l.born, sizeof l.born), bytes(&l.died, sizeof l.died), bytes(&l.node, sizeof l.node);
    bytes(&l.texture, 1), bytes(&l.occlusion, 1);
  }
  all(m.leaf_end), all(m.final_radius);
  bytes(&m.bounds_min, sizeof m.bounds_min), bytes(&m.bounds_max, sizeof m.bounds_max);
  bytes(&m.steps, sizeof m.steps), bytes(&m.radial_segments, sizeof m.radial_segments);
  bytes(m.message.data(), m.message.size());
  bytes(&m.blade.on, sizeof m.blade.on), bytes(&m.blade.fold, sizeof m.blade.fold), bytes(&m.blade.curl, sizeof m.blade.curl);
  bytes(&m.blade.needle_spread, sizeof m.blade.needle_spread);
  return h;
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
    if (!t.dead.empty()) out.dead.push_back(t.dead[i]);   // dead wood stays dead wood
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
  out.pipe_taper = t.pipe_taper;
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
  // The full mesh's leaves moved with the full tree's gnarl; move them to this step's instead.
  const std::vector<rotation_terms> turn_full = gnarl_turns(gnarl_rotations(t, p)), turn_step = gnarl_turns(gnarl_rotations(s, p));
  const std::vector<glm::vec3> disp_full = gnarl_offsets(t, turn_full), disp_step = gnarl_offsets(s, turn_step);
  for (const leaf_instance& l : full.leaves) {  // already sorted by born, so the filter stays sorted
    if (!(l.born <= step && step < l.died) || l.node >= remap.size() || remap[l.node] < 0) continue;
    leaf_instance c = l;
    c.node = uint32_t(remap[l.node]);
    // Undo the full tree's turn of the leaf's internode, then apply this step's.
    const int32_t par = t.parent[l.node];
    glm::vec3 at = l.position - disp_full[l.node];
    if (par >= 0) at = t.position[par] + rotate_by(l.position - t.position[par] - disp_full[par], turn_full[l.node].inverse());
    if (!x.empty()) at += x[l.node] - t.position[l.node];   // the wood pass's bend at this step
    c.position = gnarled_point(s, turn_step, disp_step, c.node, at);
    m.leaves.push_back(c);
    ++m.leaf_end[std::min<int>(l.born, step)];
  }
  for (int k = 1; k <= step; ++k) m.leaf_end[k] += m.leaf_end[k - 1];
  bake_crown_occlusion(m);   // from the crown of this step's leaves
  return m;
}

}  // namespace sylva
