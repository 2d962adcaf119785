// Cones and fruit on shoot tips (generators/fruits.h).
#include "generators/fruits.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>

#include "generators/leaves.h"

namespace sylva {
namespace {

// The card's frame: +Y along `axis` (petiole at the origin), its face turned to azimuth `turn`
// and then `spin` radians further around the axis (the crossed cards of one fruit).
glm::quat card_frame(const glm::vec3& axis, float turn, float spin) {
  const glm::vec3 y = glm::normalize(axis);
  glm::vec3 z(std::cos(turn), 0, std::sin(turn));
  z = z - glm::dot(z, y) * y;
  if (glm::length(z) < 1e-4f) z = glm::vec3(0, 0, 1) - y.z * y;
  z = glm::normalize(z);
  z = std::cos(spin) * z + std::sin(spin) * glm::cross(y, z);
  const glm::vec3 x = glm::cross(y, z);
  return glm::normalize(glm::quat_cast(glm::mat3(x, y, z)));
}

}  // namespace

void place_fruits(const tree_skeleton& t, const fruit_params& p, uint64_t seed, float ground, std::vector<leaf>& out) {
  const size_t n = t.size();
  const int count = std::clamp(p.count, 0, 100000);
  if (count == 0 || n == 0) return;
  const int last = std::max(t.steps, 0);
  auto alive = [&](size_t i) { return int(t.born[i]) <= last && last < int(t.died[i]); };
  std::vector<uint8_t> parent_of_living(n, 0);
  float top = -1e30f, bottom = 1e30f;
  for (size_t i = 0; i < n; ++i) {
    if (!alive(i)) continue;
    if (t.parent[i] >= 0) parent_of_living[size_t(t.parent[i])] = 1;
    top = std::max(top, t.position[i].y), bottom = std::min(bottom, t.position[i].y);
  }
  if (!(top > bottom)) return;
  const float lowest = top - std::clamp(p.crown_top, 0.0f, 1.0f) * (top - bottom);
  // Eligible tips, ranked by a seeded hash of their node: the first `count` bear fruit.
  std::vector<std::pair<uint64_t, uint32_t>> tips;
  const bool axils = p.site == fruit_site::axils;
  // An axil's fruit hangs `reach` metres out along its branch: the walk follows each node's
  // continuation (its first living child of the same order).
  std::vector<int32_t> next;
  if (axils) {
    next.assign(n, -1);
    for (size_t i = n; i-- > 0;) {
      const int32_t q = t.parent[i];
      if (q >= 0 && alive(i) && t.order[i] == t.order[size_t(q)]) next[size_t(q)] = int32_t(i);
    }
  }
  const float reach = std::clamp(p.reach, 0.0f, 100.0f);
  auto site = [&](size_t i) {
    if (!axils) return t.position[i];
    glm::vec3 at = t.position[size_t(t.parent[i])];
    float left = reach;
    for (int32_t k = int32_t(i); k >= 0 && left > 0; k = next[size_t(k)]) {
      const glm::vec3 step = t.position[size_t(k)] - at;
      const float len = glm::length(step);
      if (len >= left) return at + step * (left / len);
      at = t.position[size_t(k)], left -= len;
    }
    return at;
  };
  for (size_t i = 0; i < n; ++i) {
    if (!alive(i) || t.parent[i] < 0 || int(t.order[i]) < p.min_order || int(t.order[i]) > p.max_order) continue;
    if (axils ? t.order[size_t(t.parent[i])] >= t.order[i] : parent_of_living[i] != 0) continue;
    if (int(t.dead_from(i)) <= last) continue;   // a self-pruned limb's dead stub bears nothing (history.h)
    const float y = site(i).y;
    if (y >= lowest && std::isfinite(y)) tips.push_back({rng(seed * 0x100000001B3ull ^ (uint64_t(i) + 0x5851F42D4C957F2Dull)).next(), uint32_t(i)});
  }
  const size_t take = std::min(tips.size(), size_t(count));
  std::partial_sort(tips.begin(), tips.begin() + std::ptrdiff_t(take), tips.end());
  tips.resize(take);
  std::sort(tips.begin(), tips.end(), [](const auto& a, const auto& b) { return a.second < b.second; });

  const int cards = std::clamp(p.cards, 1, 3);
  const float pi = 3.14159265f;
  const float tilt = std::clamp(p.tilt, 0.0f, 90.0f) * pi / 180.0f;
  const uint8_t archetype = uint8_t(std::clamp(int(p.archetype), 0, leaf_archetype_count - 1));
  const size_t first = out.size();
  for (const auto& [h, node] : tips) {
    rng r(h);
    const float r0 = r.uniform(), r1 = r.uniform(), r2 = r.uniform(), r3 = r.uniform();
    // Straight down or up, leaning by up to `tilt` toward a random side.
    const float lean = tilt * std::sqrt(r0), side = 2 * pi * r1;
    const glm::vec3 across(std::cos(side) * std::sin(lean), 0, std::sin(side) * std::sin(lean));
    const glm::vec3 axis = across + glm::vec3(0, p.pose == fruit_pose::upright ? std::cos(lean) : -std::cos(lean), 0);
    const float size = std::max(0.001f, p.size * (1 + std::clamp(p.size_jitter, 0.0f, 1.0f) * (2 * r2 - 1)));
    const float turn = 2 * pi * r3;
    for (int k = 0; k < cards; ++k) {
      leaf l;
      l.position = site(node);
      l.orientation = card_frame(axis, turn, pi * float(k) / float(cards));
      l.size = size;
      l.born = uint16_t(std::max<int>(t.born[node], last > 0 ? last - 1 : 0));
      l.died = t.died[node];
      l.node = int32_t(node);
      l.archetype = archetype;
      out.push_back(l);
    }
  }
  // Fruit whose card would reach below the ground is dropped (not turned up as a leaf is).
  out.erase(std::remove_if(out.begin() + std::ptrdiff_t(first), out.end(), [&](const leaf& l) {
              return card_lowest_y(l, l.orientation * glm::vec3(1, 0, 0), l.orientation * glm::vec3(0, 1, 0)) < ground;
            }),
            out.end());
}

}  // namespace sylva
