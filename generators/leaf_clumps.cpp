// Foliage clumping: limb masses from subtree extents, a shell profile in each, seeded variation.
#include "generators/leaf_clumps.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/exponential.hpp>
#include <glm/geometric.hpp>

namespace sylva {
namespace {

float smooth(float a, float b, float x) {
  const float u = std::clamp((x - a) / (b - a), 0.0f, 1.0f);
  return u * u * (3 - 2 * u);
}

}  // namespace

std::vector<int32_t> limb_masses(const tree_skeleton& t, float size) {
  const size_t n = t.size();
  std::vector<int32_t> mass(n, -1);
  if (n == 0) return mass;
  // Subtree boxes in one reverse sweep (parent < i).
  std::vector<glm::vec3> lo(t.position), hi(t.position);
  for (size_t i = n; i-- > 0;) {
    const int32_t par = t.parent[i];
    if (par < 0) continue;
    lo[par] = glm::min(lo[par], lo[i]);
    hi[par] = glm::max(hi[par], hi[i]);
  }
  const float limit = std::isfinite(size) ? std::max(size, 0.01f) : 1.0f;
  auto small = [&](size_t i) {
    const glm::vec3 h = 0.5f * (hi[i] - lo[i]);
    return std::max({h.x, h.y, h.z}) <= limit;
  };
  // A node starts a mass when its subtree is small enough and its parent's is not.
  for (size_t i = 0; i < n; ++i) {
    const int32_t par = t.parent[i];
    if (par >= 0 && mass[par] >= 0) mass[i] = mass[par];
    else if (small(i)) mass[i] = int32_t(i);
  }
  return mass;
}

std::vector<float> clump_density(const tree_skeleton& t, const std::vector<float>& weight, const clump_settings& s,
                                 uint64_t seed) {
  const size_t n = t.size();
  std::vector<float> out(n, 1.0f);
  const float clumping = std::isfinite(s.clumping) ? std::clamp(s.clumping, 0.0f, 1.0f) : 0.0f;
  if (clumping <= 0 || n == 0 || weight.size() != n) return out;
  const std::vector<int32_t> mass = limb_masses(t, s.size);

  // The midpoint of each internode stands for its leaves.
  auto mid = [&](size_t i) { return 0.5f * (t.position[i] + t.position[t.parent[i]]); };
  // Per mass (indexed by its root node) and per tree (by its root): weighted centroids, then the
  // masses' rms radii.
  std::vector<int32_t> tree(n, -1);
  std::vector<glm::vec3> sum(n, glm::vec3(0)), tree_sum(n, glm::vec3(0));
  std::vector<float> w_mass(n, 0), w_tree(n, 0);
  std::vector<glm::vec3> sq(n, glm::vec3(0));
  for (size_t i = 0; i < n; ++i) {
    const int32_t par = t.parent[i];
    tree[i] = par < 0 ? int32_t(i) : tree[par];
    const float w = weight[i];
    if (par < 0 || !(w > 0)) continue;
    const glm::vec3 x = mid(i);
    tree_sum[tree[i]] += w * x;
    w_tree[tree[i]] += w;
    if (mass[i] < 0) continue;
    sum[mass[i]] += w * x;
    w_mass[mass[i]] += w;
  }
  for (size_t i = 0; i < n; ++i) {
    if (w_mass[i] > 0) sum[i] /= w_mass[i];
    if (w_tree[i] > 0) tree_sum[i] /= w_tree[i];
  }
  for (size_t i = 0; i < n; ++i) {
    if (t.parent[i] < 0 || !(weight[i] > 0) || mass[i] < 0) continue;
    const glm::vec3 e = mid(i) - sum[mass[i]];
    sq[mass[i]] += weight[i] * e * e;
  }
  const float variation = std::isfinite(s.variation) ? std::clamp(s.variation, 0.0f, 1.0f) : 0.0f;
  std::vector<glm::vec3> radius(n, glm::vec3(1));
  std::vector<float> vary(n, 1);
  std::vector<glm::vec3> outward(n, glm::vec3(0));
  for (size_t i = 0; i < n; ++i) {
    if (!(w_mass[i] > 0)) continue;
    // The mass's extent along each axis: a ball of radius R has an rms spread of R sqrt(1/5) per
    // axis. Per axis, so that a long mass (a poplar's or a cypress's leader, a level limb) is an
    // ellipsoid whose ends lie inside its rim: one radius for all axes made it a ball, and its
    // ends (the leader's top metres) fell in the "gap" past the rim and lost their leaves. A
    // floor keeps a lone twig's mass from being a point.
    const float floor_r = 0.15f * std::max(s.size, 0.01f);
    radius[i] = glm::max(glm::sqrt(sq[i] / w_mass[i] / 0.2f), glm::vec3(floor_r));
    const glm::vec3 o = sum[i] - tree_sum[tree[i]];
    const float len = glm::length(o);
    outward[i] = len > 1e-4f ? o / len : glm::vec3(0, 1, 0);
    rng r(seed ^ (uint64_t(i) * 0xD1B54A32D192ED03ull + 0xc1u));
    vary[i] = std::max(0.0f, 1 + variation * r.uniform(-1, 1));
  }

  // The shell profile: leaves thin out toward the mass's centre (its interior) and past its rim
  // (the gaps between masses), and lean to the side facing out of the crown and up to the light.
  double total = 0, shaped = 0;
  for (size_t i = 0; i < n; ++i) {
    out[i] = 0;
    if (t.parent[i] < 0 || !(weight[i] > 0)) continue;
    total += weight[i];
    const int32_t m = mass[i];
    if (m < 0) continue;
    const glm::vec3 u = (mid(i) - sum[m]) / radius[m];
    const float r = glm::length(u);
    const float shell = smooth(0.2f, 0.75f, r) * (1 - smooth(0.95f, 1.4f, r));
    const float side = std::clamp(1 + 0.7f * glm::dot(u, outward[m]) + 0.3f * u.y, 0.15f, 2.0f);
    out[i] = shell * side * vary[m];
    shaped += weight[i] * out[i];
  }
  const float k = shaped > 0 ? float(total / shaped) : 1.0f;
  for (size_t i = 0; i < n; ++i) out[i] = (1 - clumping) + clumping * std::min(k * out[i], 4.0f);
  return out;
}

}  // namespace sylva
