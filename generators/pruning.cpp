// Pruning: which nodes a cut takes, and the common part of applying it during growth.
#include "generators/pruning.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glm/geometric.hpp>

#include "generators/tree_spec.h"

namespace sylva {

namespace {

bool outside(const prune_cut& c, const glm::vec3& p) {
  const glm::vec3 h = glm::max(c.size, glm::vec3(1e-6f));
  const glm::vec3 q = (p - c.point) / h;
  if (c.shape == prune_shape::outside_box) return std::abs(q.x) > 1 || std::abs(q.y) > 1 || std::abs(q.z) > 1;
  return glm::dot(q, q) > 1;
}

}  // namespace

bool select_cut(const tree_skeleton& t, const prune_cut& c, std::vector<uint8_t>& removed) {
  const size_t n = t.size();
  removed.resize(n, 0);
  const int before = c.step - 1;   // the tree the cut is made on
  std::vector<uint8_t> mark(n, 0);
  if (c.shape == prune_shape::branch) {
    int32_t best = -1;
    float best_d2 = c.reach * c.reach;
    for (size_t i = 0; i < n; ++i) {
      if (t.parent[i] < 0 || !t.alive(i, before)) continue;
      const glm::vec3 d = t.position[i] - c.point;
      const float d2 = glm::dot(d, d);
      if (d2 <= best_d2 && (best < 0 || d2 < best_d2)) best = int32_t(i), best_d2 = d2;
    }
    if (best < 0) return false;
    mark[size_t(best)] = 1;
  } else {
    // Shears at the surface: an internode that leaves the shape (it starts inside and ends
    // outside) is cut, with everything beyond. What never entered the shape, such as the trunk
    // below a crown-shaped brush, stays.
    for (size_t i = 0; i < n; ++i)
      if (t.parent[i] >= 0 && t.alive(i, before) && outside(c, t.position[i]) &&
          !outside(c, t.position[size_t(t.parent[i])]))
        mark[i] = 1;
  }
  // The subtrees: parents precede children, so one forward sweep reaches every descendant.
  for (size_t i = 0; i < n; ++i) {
    if (!mark[i] && t.parent[i] >= 0 && mark[size_t(t.parent[i])]) mark[i] = 1;
    if (mark[i] && t.alive(i, before)) removed[i] = 1;
  }
  return true;
}

std::vector<int32_t> apply_cuts(tree_skeleton& t, const std::vector<prune_cut>* cuts, int step, grow_report& rep) {
  std::vector<int32_t> out;
  if (!cuts || cuts->empty()) return out;
  std::vector<uint8_t> removed;
  for (size_t k = 0; k < cuts->size(); ++k) {
    const prune_cut& c = (*cuts)[k];
    if (c.step != step) continue;
    if (!select_cut(t, c, removed)) {
      rep.missed_cuts.push_back(int(k));
      char b[200];
      std::snprintf(b, sizeof b, "cut %d at step %d finds no branch within %.3g m of (%.3g, %.3g, %.3g); nothing was cut",
                    int(k) + 1, step, double(c.reach), double(c.point.x), double(c.point.y), double(c.point.z));
      rep.message += (rep.message.empty() ? "" : "; ") + std::string(b);
    }
  }
  for (size_t i = 0; i < removed.size(); ++i)
    if (removed[i] && t.died[i] == never_died) {
      t.died[i] = uint16_t(step);
      out.push_back(int32_t(i));
    }
  return out;
}

std::string check_cut(const tree_spec& spec, const prune_cut& c) {
  const std::string at = "cut at step " + std::to_string(c.step);
  if (const auto* l = std::get_if<lsystem_params>(&spec.params); l && l->mode == lsystem_mode::text)
    return at + ": text L-systems cannot be pruned during growth, since the turtle draws the string only after the "
                "last derivation";
  const int top = max_keyframe_step(spec);   // past the last step a cut is kept, inactive
  if (c.step < 1) return at + ": steps start at 1";
  if (c.step > top)
    return at + ": step " + std::to_string(c.step) + " is beyond the most steps a growth can have (" + std::to_string(top) + ")";
  if (int(c.shape) < 0 || int(c.shape) > 2) return at + ": unknown shape";
  auto finite = [](const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
  if (!finite(c.point) || std::abs(c.point.x) > 1e4f || std::abs(c.point.y) > 1e4f || std::abs(c.point.z) > 1e4f)
    return at + ": the point must be finite and within 10 km of the root";
  if (c.shape == prune_shape::branch && !(c.reach > 0 && c.reach <= 100))
    return at + ": the reach must be in (0, 100] metres";
  if (c.shape != prune_shape::branch &&
      !(finite(c.size) && std::min({c.size.x, c.size.y, c.size.z}) > 0 && std::max({c.size.x, c.size.y, c.size.z}) <= 1e4f))
    return at + ": the brush size must be positive and finite";
  return "";
}

std::string check_cuts(const tree_spec& spec) {
  for (const prune_cut& c : spec.cuts)
    if (std::string e = check_cut(spec, c); !e.empty()) return e;
  return "";
}

std::string add_cut(tree_spec& spec, const prune_cut& cut) {
  if (std::string e = check_cut(spec, cut); !e.empty()) return e;
  // A branch cut has a reach and a brush a size; the other field is not saved (render/io/preset.cpp),
  // so the document keeps it at its default and saves and reopens exactly as it is.
  prune_cut c = cut;
  if (c.shape == prune_shape::branch) c.size = prune_cut{}.size;
  else c.reach = prune_cut{}.reach;
  for (const prune_cut& o : spec.cuts)
    if (o == c) return "cut at step " + std::to_string(c.step) + ": the same cut is already in the list";
  spec.cuts.push_back(c);
  return "";
}

const char* cut_response(const tree_spec& spec) {
  if (const auto* l = std::get_if<lsystem_params>(&spec.params); l && l->mode == lsystem_mode::text)
    return "not available for text L-systems";
  return generator_table[spec.params.index()].cut_response;
}

}  // namespace sylva
