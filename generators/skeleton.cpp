// Skeleton invariants, pipe-model radii and the per-step view.
#include "generators/skeleton.h"

#include <cassert>
#include <cmath>
#include <string>

#include <glm/geometric.hpp>

#include "generators/history.h"

namespace sylva {

int32_t tree_skeleton::add_node(const glm::vec3& p, int32_t par, float r, uint16_t born_step, uint8_t ord) {
  position.push_back(p);
  parent.push_back(par);
  radius.push_back(r);
  born.push_back(born_step);
  died.push_back(never_died);
  order.push_back(ord);
  return int32_t(position.size() - 1);
}

void tree_skeleton::reserve(size_t n) {
  position.reserve(n);
  parent.reserve(n);
  radius.reserve(n);
  born.reserve(n);
  died.reserve(n);
  order.reserve(n);
}

std::string validate_skeleton(const tree_skeleton& s) {
  const size_t n = s.position.size();
  if (s.parent.size() != n || s.radius.size() != n || s.born.size() != n || s.died.size() != n ||
      s.order.size() != n || (!s.dead.empty() && s.dead.size() != n))
    return "array sizes differ";
  for (size_t i = 0; i < n; ++i) {
    const auto& p = s.position[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      return "node " + std::to_string(i) + " has a non-finite position";
    if (!std::isfinite(s.radius[i]) || s.radius[i] < 0)
      return "node " + std::to_string(i) + " has an invalid radius";
    const int32_t par = s.parent[i];
    if (par >= int32_t(i)) return "node " + std::to_string(i) + " has parent >= itself";
    if (par < -1) return "node " + std::to_string(i) + " has a negative parent";
    if (s.died[i] <= s.born[i]) return "node " + std::to_string(i) + " dies before it is born";
    if (s.born[i] > s.steps) return "node " + std::to_string(i) + " is born after the last step";
    if (s.dead_from(i) <= s.born[i]) return "node " + std::to_string(i) + " is dead wood before it is born";
    if (par >= 0) {
      if (s.born[i] < s.born[par]) return "node " + std::to_string(i) + " is born before its parent";
      if (s.died[i] > s.died[par]) return "node " + std::to_string(i) + " outlives its parent";
    }
  }
  for (size_t k = 0; k < s.leaves.size(); ++k) {
    const leaf& l = s.leaves[k];
    if (l.node < 0 || size_t(l.node) >= n) return "leaf " + std::to_string(k) + " has no node";
    if (l.born < s.born[l.node]) return "leaf " + std::to_string(k) + " is born before its node";
    if (!std::isfinite(l.size) || l.size < 0) return "leaf " + std::to_string(k) + " has an invalid size";
  }
  return "";
}

void compute_pipe_radii(const std::vector<int32_t>& parent, const std::vector<uint16_t>& born,
                        const std::vector<uint16_t>& died, int step, float exponent, float r_tip,
                        std::vector<float>& radius, const std::vector<glm::vec3>* position, float taper) {
  const size_t n = parent.size();
  radius.assign(n, 0.0f);
  const bool tapered = position && position->size() == n && std::isfinite(taper) && taper > 0;
  // Accumulate r^n sums bottom-up (children have larger indices than their parents).
  std::vector<float> sum(n, 0.0f);
  const float rt = std::pow(r_tip, exponent);
  for (size_t k = n; k-- > 0;) {
    const bool alive = step < 0 || (born[k] <= step && step < died[k]);
    if (!alive) continue;
    // Shinozaki's pipe model as used by Palubicki 2009 §5: r^n = Σ r_i^n; a tip has r_tip.
    const float s = sum[k] > 0 ? sum[k] : rt;
    radius[k] = std::pow(s, 1.0f / exponent);
    assert(parent[k] < int32_t(k) && "compute_pipe_radii: one reverse sweep needs parent[i] < i");
    if (parent[k] < 0) continue;
    if (tapered) {
      // Disused pipes: the internode's base is (1 + τ·ℓ) times its tip (see skeleton.h).
      const float len = glm::length((*position)[k] - (*position)[size_t(parent[k])]);
      const float f = 1.0f + taper * (std::isfinite(len) ? len : 0.0f);
      sum[parent[k]] += s * std::pow(f, exponent);
    } else {
      sum[parent[k]] += s;
    }
  }
}

float pipe_taper_factor(const tree_skeleton& s, size_t i) {
  if (!(s.pipe_exponent > 0) || !(s.pipe_taper > 0) || !std::isfinite(s.pipe_taper) || i >= s.size()) return 1.0f;
  const int32_t par = s.parent[i];
  if (par < 0) return 1.0f;
  const float len = glm::length(s.position[i] - s.position[size_t(par)]);
  return std::isfinite(len) ? 1.0f + s.pipe_taper * len : 1.0f;
}

void apply_pipe_radii(tree_skeleton& s, float exponent, float r_tip, float taper) {
  s.pipe_exponent = exponent;
  s.pipe_tip_radius = r_tip;
  s.pipe_taper = std::isfinite(taper) && taper > 0 ? taper : 0.0f;
  compute_pipe_radii(s.parent, s.born, s.died, s.steps, exponent, r_tip, s.radius, &s.position, s.pipe_taper);
  thicken_stubs(s, s.steps, exponent, r_tip, s.radius);   // dead stubs keep their girth (history.h)
}

std::vector<float> radii_at_step(const tree_skeleton& s, int step) {
  std::vector<float> r;
  if (s.pipe_exponent > 0) {
    compute_pipe_radii(s.parent, s.born, s.died, step, s.pipe_exponent, s.pipe_tip_radius, r, &s.position,
                       s.pipe_taper);
    thicken_stubs(s, step, s.pipe_exponent, s.pipe_tip_radius, r);
    return r;
  }
  r = s.radius;
  for (size_t i = 0; i < r.size(); ++i)
    if (!s.alive(i, step)) r[i] = 0;
  return r;
}

bool structurally_sound(const tree_skeleton& t) {
  const size_t n = t.position.size();
  if (t.parent.size() != n || t.radius.size() != n || t.born.size() != n || t.died.size() != n ||
      t.order.size() != n || (!t.dead.empty() && t.dead.size() != n))
    return false;
  for (size_t i = 0; i < n; ++i)
    if (t.parent[i] < -1 || t.parent[i] >= int32_t(i)) return false;
  return true;
}

}  // namespace sylva
