// The self-organizing model's per-bud rules (Palubicki et al. 2009, with seed 001): the extended
// Borchert-Honda split of resource, the priority weights, the shoot plan and the shedding choice
// (declared in generators/self_organizing.h; the growth loop is self_organizing.cpp).
#include "generators/self_organizing.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace sylva {

void split_borchert_honda(float v, float q_main, float q_lateral, float lambda, float& v_main, float& v_lateral) {
  // Palubicki 2009 eqs. 4–5 (seed 001 eqs. 4–5): v_m = v·λQ_m / (λQ_m + (1−λ)Q_l), v_l likewise.
  const float m = lambda * std::max(q_main, 0.0f), l = (1 - lambda) * std::max(q_lateral, 0.0f);
  const float d = m + l;
  if (!(d > 0)) {
    v_main = v;
    v_lateral = 0;
    return;
  }
  v_main = v * m / d;
  v_lateral = v * l / d;
}

float priority_weight(int i, int n, float w_max, float w_min, float kappa) {
  // Seed 000 eq. 2 (Palubicki 2009 eq. 6): linear from w_max at rank 0 to w_min at rank κN.
  const float kn = kappa * float(n);
  if (float(i) >= kn) return w_min;
  return w_max - (w_max - w_min) * float(i) / kn;
}

void allocate_priority(float v, const std::vector<float>& q, float w_max, float w_min, float kappa,
                       std::vector<float>& out) {
  // Seed 000 eq. 1 (Palubicki 2009 eq. 5): v_i = v·Q_i·w_i / Σ_j Q_j·w_j.
  const int n = int(q.size());
  out.resize(q.size());
  double sum = 0;
  for (int i = 0; i < n; ++i) {
    out[i] = std::max(q[i], 0.0f) * priority_weight(i, n, w_max, w_min, kappa);
    sum += out[i];
  }
  const float f = sum > 0 ? float(double(v) / sum) : 0.0f;
  for (float& x : out) x *= f;
}

shoot_plan plan_shoot(float v, float internode_length) {
  // Palubicki 2009 §5: n = ⌊v⌋ metamers, each of length l·v/n.
  if (!(v >= 1)) return {};
  const float n = std::floor(std::min(v, 1e6f));
  return {int(n), internode_length * std::min(v, 1e6f) / n};
}

std::vector<uint8_t> select_shed(const std::vector<int32_t>& parent, const std::vector<float>& flow,
                                 const std::vector<int32_t>& buds, int n_min) {
  std::vector<uint8_t> shed(parent.size(), 0);
  if (n_min <= 0) return shed;
  for (size_t i = 0; i < parent.size(); ++i) {
    if (parent[i] < 0) continue;
    // Parents precede children, so a shed ancestor is known before its subtree.
    shed[i] = shed[parent[i]] || (flow[i] < 0 && buds[i] < n_min);
  }
  return shed;
}

}  // namespace sylva
