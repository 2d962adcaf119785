// Growth history: seasons of unequal vigour and the self-pruning of the lower limbs (history.h).
#include "generators/history.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

namespace sylva {

std::vector<float> season_anomalies(uint64_t seed, int steps) {
  std::vector<float> z(size_t(std::max(steps, 0)) + 1, 0.0f);
  rng r(seed ^ 0x5ea5011a11ull);
  // Fritts 1976: ring-width indices persist from year to year; an AR(1) sequence with ρ = 0.5 and
  // unit variance (ε uniform on [−√3, √3] has unit variance).
  constexpr float rho = 0.5f, innovation = 0.8660254f, half_width = 1.7320508f;
  for (size_t k = 1; k < z.size(); ++k) z[k] = rho * z[k - 1] + innovation * r.uniform(-half_width, half_width);
  return z;
}

float season_vigour(float amplitude, float anomaly) { return amplitude > 0 ? std::exp(amplitude * anomaly) : 1.0f; }

std::vector<int32_t> self_prune(tree_skeleton& t, float live_crown, float stub_length) {
  const size_t n = t.size();
  if (!(live_crown < 1.0f) || n < 2) return {};
  const float keep = std::clamp(1.0f - live_crown, 0.0f, 1.0f);
  // H(k): the height of the tree at step k, the highest node born by then.
  const int steps = std::max(t.steps, 0);
  std::vector<float> top(size_t(steps) + 1, 0.0f);
  for (size_t i = 0; i < n; ++i) {
    const size_t k = std::min<size_t>(t.born[i], size_t(steps));
    top[k] = std::max(top[k], t.position[i].y);
  }
  for (size_t k = 1; k < top.size(); ++k) top[k] = std::max(top[k], top[k - 1]);
  // Each limb's death step, carried down its subtree with the path length from its axis.
  std::vector<uint16_t> death(n, never_died);
  std::vector<float> arc(n, 0.0f);
  bool any = false;
  for (size_t i = 1; i < n; ++i) {
    const int32_t par = t.parent[i];
    if (par < 0) continue;
    if (death[size_t(par)] != never_died) {
      death[i] = death[size_t(par)];
      arc[i] = arc[size_t(par)] + glm::length(t.position[i] - t.position[size_t(par)]);
      continue;
    }
    if (t.order[size_t(par)] != 0 || t.order[i] == 0) continue;   // not a limb leaving an order-0 axis
    const float y = t.position[size_t(par)].y;
    for (int k = int(t.born[i]) + 1; k <= steps && k < int(t.died[i]); ++k)
      if (y < keep * top[size_t(k)]) {   // the crown has risen past the limb: it dies at k
        death[i] = uint16_t(k);
        arc[i] = glm::length(t.position[i] - t.position[size_t(par)]);
        any = true;
        break;
      }
  }
  if (!any) return {};
  // Wood the limb grew from its death on never grew: removed. Internodes that start within the stub
  // length stay as dead wood; the rest falls.
  std::vector<int32_t> kept, index(n, -1);
  kept.reserve(n);
  std::vector<uint16_t> dead(n, never_died);
  for (size_t i = 0; i < n; ++i) {
    const uint16_t k = death[i];
    if (k != never_died) {
      if (t.born[i] >= k) continue;
      const float start = arc[i] - glm::length(t.position[i] - t.position[size_t(t.parent[i])]);
      if (start < stub_length && t.died[i] > k) dead[i] = k;
      else t.died[i] = std::min(t.died[i], k);
    }
    index[i] = int32_t(kept.size());
    kept.push_back(int32_t(i));
  }
  auto compact = [&](auto& v) {
    for (size_t j = 0; j < kept.size(); ++j) v[j] = v[size_t(kept[j])];
    v.resize(kept.size());
  };
  for (size_t j = 0; j < kept.size(); ++j) {
    const int32_t par = t.parent[size_t(kept[j])];
    t.parent[size_t(kept[j])] = par < 0 ? -1 : index[size_t(par)];
  }
  compact(t.position), compact(t.parent), compact(t.radius), compact(t.born), compact(t.died), compact(t.order);
  if (!t.dead.empty())
    for (size_t i = 0; i < n; ++i) dead[i] = std::min(dead[i], t.dead[i]);
  compact(dead);
  t.dead = std::move(dead);
  // Generator leaves go with their node, and fall when it falls or dies.
  size_t w = 0;
  for (const leaf& l0 : t.leaves) {
    if (l0.node < 0 || index[size_t(l0.node)] < 0) continue;
    leaf l = l0;
    l.node = index[size_t(l0.node)];
    l.died = std::min({l.died, t.died[size_t(l.node)], t.dead[size_t(l.node)]});
    if (l.died <= l.born) continue;
    t.leaves[w++] = l;
  }
  t.leaves.resize(w);
  return kept;
}

void thicken_stubs(const tree_skeleton& t, int step, float exponent, float r_tip, std::vector<float>& radius) {
  const size_t n = t.size();
  if (t.dead.empty() || !(exponent > 0) || radius.size() != n) return;
  const int last = step < 0 ? t.steps : step;
  // The step each dying limb died in, for its stub (dead) and for the wood that fell with it (died
  // at the same step below a stub); parents come before their children.
  std::vector<uint16_t> limb(n, never_died);
  for (size_t i = 0; i < n; ++i) {
    if (t.dead[i] != never_died) limb[i] = t.dead[i];
    else if (const int32_t par = t.parent[i]; par >= 0 && limb[size_t(par)] != never_died && t.died[i] == limb[size_t(par)])
      limb[i] = limb[size_t(par)];
  }
  // The tips each limb carried through each of its nodes in the step before its death k (alive at
  // k − 1: born before k, fallen not before k).
  std::vector<float> pipes(n, 0.0f);
  bool any = false;
  for (size_t i = n; i-- > 0;) {
    const uint16_t k = limb[i];
    if (k == never_died || int(k) > last || !(t.born[i] < k && t.died[i] >= k)) continue;
    if (pipes[i] == 0) pipes[i] = 1;   // a tip at k − 1
    any = true;
    if (const int32_t par = t.parent[i]; par >= 0 && limb[size_t(par)] == k) pipes[size_t(par)] += pipes[i];
  }
  if (!any) return;
  // In index order, so a stub's base is held to its axis before the rest of the stub to it.
  for (size_t i = 0; i < n; ++i) {
    if (t.dead[i] == never_died || int(t.dead[i]) > last || !(pipes[i] > 0)) continue;
    float r = r_tip * std::pow(pipes[i], 1.0f / exponent);   // Shinozaki 1964: r^n = Σ r_tip^n
    if (const int32_t par = t.parent[i]; par >= 0) r = std::min(r, radius[size_t(par)]);
    radius[i] = std::max(radius[i], r);
  }
}

glm::vec3 open_side_direction(float azimuth_degrees) {
  const float a = glm::radians(azimuth_degrees);
  return {std::cos(a), 0.0f, std::sin(a)};
}

glm::vec3 lean_to_sky(const glm::vec3& d, float lean, const glm::vec3& open) {
  if (!(lean > 0)) return d;
  const glm::vec3 v = d + lean * open;   // Loehle 1986: shoots turn towards the open side's light
  const float l = glm::length(v);
  return l > 1e-5f ? v / l : d;
}

float sky_keep_chance(const glm::vec3& u, float lean, const glm::vec3& open) {
  if (!(lean > 0)) return 1.0f;
  const float side = std::clamp(glm::dot(glm::vec3(u.x, 0.0f, u.z), open), -1.0f, 1.0f);
  return std::clamp(1.0f - lean * 0.5f * (1.0f - side), 0.0f, 1.0f);
}

}  // namespace sylva
