// The foliage model: leaves along young shoots (with phyllotaxis and retention), tips, or the
// generator's own leaves.
#include "generators/leaves.h"

#include "generators/job_pool.h"
#include "generators/leaf_clumps.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtx/quaternion.hpp>
#include <glm/mat3x3.hpp>

namespace sylva {
namespace {

// The rotation whose columns are the orthonormal x, y, z, as a unit quaternion (Shoemake 1985): from
// the trace where the rotation turns less than about 150° (w ≥ 1/4, so the division by w loses
// nothing), glm::quat_cast otherwise. quat_cast alone branches on the largest of the four
// components, which leaves at random azimuths mispredict: this is most of a leaf's placement.
glm::quat basis_quat(const glm::vec3& x, const glm::vec3& y, const glm::vec3& z) {
  const float trace = x.x + y.y + z.z;
  if (!(trace > -0.75f)) return glm::normalize(glm::quat_cast(glm::mat3(x, y, z)));
  const float w = 0.5f * std::sqrt(1 + trace), k = 0.25f / w;
  return glm::normalize(glm::quat(w, (y.z - z.y) * k, (z.x - x.z) * k, (x.y - y.x) * k));
}

// Leaf frame (skeleton.h: blade along +Y, normal +Z) from the blade direction b and a wanted
// normal direction w; w need not be perpendicular to b.
glm::quat blade_frame(const glm::vec3& b, glm::vec3 w, const glm::vec3& fallback) {
  w -= glm::dot(w, b) * b;
  float len = glm::length(w);
  if (len < 1e-4f) {
    w = fallback - glm::dot(fallback, b) * b;
    len = glm::length(w);
    if (len < 1e-6f) w = std::abs(b.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 0, 1), w -= glm::dot(w, b) * b, len = glm::length(w);
  }
  glm::vec3 n = w / len;
  if (n.y < 0) n = -n;   // the upper face is the one toward the sky
  return basis_quat(glm::cross(b, n), b, n);
}

uint16_t retention_end(uint16_t born, int retention, uint16_t died) {
  const int end = int(born) + std::max(retention, 0) + 1;
  return end >= int(never_died) ? died : std::min<uint16_t>(died, uint16_t(end));
}

}  // namespace

foliage place_shoot_leaves(const tree_skeleton& t, const leaf_params& p, uint64_t seed) {
  foliage out;
  const size_t n = t.size();
  if (n == 0) return out;
  // Internodes from the end of each node's own axis (its continuation is the child of the same
  // order), on the final tree; parent < i, so one reverse sweep.
  std::vector<uint16_t> from_tip;
  if (p.outer_internodes > 0) {
    from_tip.assign(n, never_died);
    for (size_t i = n; i-- > 0;) {
      if (from_tip[i] == never_died) from_tip[i] = 0;
      const int32_t par = t.parent[i];
      if (par >= 0 && t.order[par] == t.order[i])
        from_tip[par] = std::min<uint16_t>(from_tip[par], uint16_t(std::min<int>(from_tip[i] + 1, never_died - 1)));
    }
  }
  const int per_node = leaves_per_node(p);
  const float spacing = std::isfinite(p.spacing) ? std::clamp(p.spacing, 0.001f, 100.0f) : 0.06f;
  const int cluster = p.clusters ? std::clamp(p.cluster_size, 2, 32) : 1;
  // Crossed cards: each leaf stands as `planes` cards turned pi/planes apart about its blade axis
  // (the frame's +Y), all from the leaf's one set of draws, so a tree with one plane is unchanged.
  const int planes = card_planes(p);
  glm::quat turn[3];
  for (int c = 0; c < 3; ++c) turn[c] = glm::angleAxis(3.14159265f * float(c) / float(planes), glm::vec3(0, 1, 0));
  const size_t cap = size_t(std::clamp(p.cap, 1, 2000000));
  auto carries = [&](size_t i) {
    return t.parent[i] >= 0 && t.order[i] >= p.min_order && t.died[i] > t.born[i] &&
           (from_tip.empty() || from_tip[i] < p.outer_internodes);
  };
  // One cheap forward pass: the distance of each node from the root (leaf nodes counted along each
  // path give the phyllotactic angle without a sequential placement).
  std::vector<float> arc(n, 0);
  const bool clumped = std::isfinite(p.clumping) && p.clumping > 0;
  std::vector<float> bearing(clumped ? n : 0, 0.0f);   // leaf-bearing length per internode
  for (size_t i = 0; i < n; ++i) {
    if (t.parent[i] < 0) continue;
    const float len = glm::length(t.position[i] - t.position[t.parent[i]]);
    arc[i] = arc[t.parent[i]] + (std::isfinite(len) ? len : 0.0f);
    if (clumped && carries(i) && std::isfinite(len)) bearing[i] = len;
  }
  // Clumping: a factor per internode on its leaf count (leaf_clumps.h); none when 0, so the
  // placement below is exactly the even one.
  const std::vector<float> density =
      clumped ? clump_density(t, bearing, clump_settings{p.clumping, p.clump_size, p.clump_variation}, seed) : std::vector<float>();

  const float spread = glm::radians(std::isfinite(p.spread) ? p.spread : 50.0f);
  const float cs = std::cos(spread), sn = std::sin(spread);
  const float divergence = glm::radians(std::isfinite(p.divergence) ? p.divergence : 137.5f);
  const float droop = std::isfinite(p.droop) ? std::clamp(p.droop, 0.0f, 1.0f) : 0.0f;
  const float jitter = std::isfinite(p.size_jitter) ? std::clamp(p.size_jitter, 0.0f, 1.0f) : 0.0f;
  const float taper = std::isfinite(p.taper) ? std::clamp(p.taper, 0.0f, 0.95f) : 0.0f;
  const float base_size = std::isfinite(p.size) && p.size > 0 ? p.size : 0.1f;
  // A cluster card covers the area of its leaves: side grows with the square root of the count.
  const float card_scale = p.clusters ? 0.9f * std::sqrt(float(cluster)) : 1.0f;
  const uint8_t card = p.clusters ? uint8_t(p.cluster_archetype) : uint8_t(255);
  const float step_around = 2 * 3.14159265f / float(per_node);
  const glm::vec3 up(0, 1, 0), down(0, -1, 0);
  float taper_pow[9];
  for (int k = 0; k < 9; ++k) taper_pow[k] = std::pow(1 - taper, float(k));

  // Leaf nodes along internode i (the fraction gives one more with its probability), from its own
  // stream r, whose first draw this takes; 0 for an internode that carries none.
  auto leaf_nodes = [&](size_t i, rng& r) {
    const int32_t par = t.parent[i];
    if (par < 0 || !carries(i)) return 0;
    const float len = glm::length(t.position[i] - t.position[par]);
    if (!(len > 1e-6f)) return 0;
    r = rng(seed ^ (uint64_t(i) * 0x9E3779B97F4A7C15ull + 0xf011a9eull));
    float want = len / spacing / float(cluster) * (density.empty() ? 1.0f : density[i]);
    if (!(want > 0)) return 0;            // NaN too
    want = std::min(want, 1.0e6f);        // a limb km long (an out-of-range L-system define) still counts in int
    int nodes = int(want);
    if (r.uniform() < want - float(nodes)) ++nodes;
    return nodes;
  };
  // Newest nodes first: when the cap is reached it is the oldest history that goes, never the final
  // crown. Each node draws from its own stream, so the result does not depend on the order: a
  // first pass counts each node's leaves, so that chunks of nodes then fill their own slots of the
  // list in parallel (job_pool.h), the bytes those of one thread placing them newest first.
  // The counting pass keeps each node's stream as its first draw left it, for the filling pass.
  std::vector<size_t> first(n + 1, 0);   // first[k]: the slot of node n-1-k's first leaf
  std::vector<rng> stream(n, rng(0));      // stream[k]: node n-1-k's
  for (size_t k = 0; k < n; ++k)
    first[k + 1] = first[k] + size_t(leaf_nodes(n - 1 - k, stream[k])) * size_t(per_node) * size_t(planes);
  out.capped = first[n] > cap;
  out.leaves.resize(std::min(first[n], cap));
  parallel_chunks(n, 1024, [&](size_t k0, size_t k1) {
    for (size_t k = k0; k < k1 && first[k] < cap; ++k) {
      const size_t i = n - 1 - k;
      rng r = stream[k];
      const int nodes = int((first[k + 1] - first[k]) / (size_t(per_node) * size_t(planes)));
      if (nodes == 0) continue;
      const int32_t par = t.parent[i];
      glm::vec3 d = t.position[i] - t.position[par];
      const float len = glm::length(d);
      d /= len;
      glm::vec3 e1 = glm::cross(d, up);
      const float e1len = glm::length(e1);
      e1 = e1len > 1e-3f ? e1 / e1len : glm::vec3(1, 0, 0);
      const glm::vec3 e2 = glm::cross(d, e1);
      // Dead wood (a self-pruned limb's stub, generators/history.h) drops its leaves when it dies.
      const uint16_t died = retention_end(t.born[i], p.retention, std::min(t.died[i], t.dead_from(i)));
      const int above = std::clamp(int(t.order[i]) - p.min_order, 0, 8);
      const float size = base_size * taper_pow[above] * card_scale;
      float az = divergence * std::floor(arc[par] / (spacing * float(cluster)));
      size_t at_slot = first[k];
      for (int kk = 0; kk < nodes && at_slot < cap; ++kk) {
        const float along = (float(kk) + 0.5f + 0.3f * r.uniform(-1, 1)) / float(nodes);
        const glm::vec3 at = t.position[par] + d * (len * along);
        for (int m = 0; m < per_node && at_slot < cap; ++m) {
          const float a = az + step_around * float(m) + r.uniform(-0.15f, 0.15f);
          const glm::vec3 radial = std::cos(a) * e1 + std::sin(a) * e2;
          glm::vec3 b = cs * d + sn * radial;
          if (droop > 0) b = glm::normalize(b + droop * 2.0f * (down - b * std::max(glm::dot(b, down), 0.0f)));
          // Blades turn their upper face outward and to the sky, each a little differently, so a crown
          // reads as dense from the side as from above.
          const glm::vec3 wobble(r.uniform(-0.5f, 0.5f), r.uniform(-0.5f, 0.5f), r.uniform(-0.5f, 0.5f));
          const glm::quat frame = blade_frame(b, 0.7f * up + radial + wobble, radial);
          const float leaf_size = size * (1 + jitter * r.uniform(-1, 1));
          for (int c = 0; c < planes && at_slot < cap; ++c) {
            leaf& l = out.leaves[at_slot++];
            l.position = at;
            l.orientation = c == 0 ? frame : glm::normalize(frame * turn[c]);
            l.size = leaf_size;
            l.born = t.born[i];
            l.died = died;
            l.node = int32_t(i);
            l.archetype = card;
          }
        }
        az += divergence;
      }
    }
  });
  return out;
}

std::vector<leaf> place_tip_leaves(const tree_skeleton& t, const leaf_params& p, uint64_t seed) {
  const size_t n = t.size();
  // A node stops being a tip when its first child appears.
  std::vector<uint16_t> first_child(n, never_died);
  for (size_t i = 0; i < n; ++i)
    if (t.parent[i] >= 0) first_child[t.parent[i]] = std::min(first_child[t.parent[i]], t.born[i]);
  auto carries_leaves = [&](size_t i) {
    return t.parent[i] >= 0 && t.order[i] >= p.min_order && std::min(t.died[i], first_child[i]) > t.born[i];
  };
  // Reserve once: a tree of 20,000 nodes otherwise regrows this vector a dozen times.
  size_t tips = 0;
  for (size_t i = 0; i < n; ++i) tips += carries_leaves(i);
  std::vector<leaf> out;
  out.reserve(tips * (p.density > 0 ? size_t(std::min(p.density, 64.0f)) + 1 : 1));
  rng r(seed ^ 0x1eafull);
  const float spread = glm::radians(p.spread);
  const glm::quat tilt = glm::angleAxis(spread, glm::vec3(1, 0, 0));   // the same for every leaf
  for (size_t i = 0; i < n; ++i) {
    if (!carries_leaves(i)) continue;
    const uint16_t died = std::min({t.died[i], first_child[i], t.dead_from(i)});
    glm::vec3 dir = t.position[i] - t.position[t.parent[i]];
    const float len = glm::length(dir);
    dir = len > 1e-12f ? dir / len : glm::vec3(0, 1, 0);
    int count = int(p.density);
    if (r.uniform() < p.density - float(count)) ++count;
    const glm::quat along = glm::rotation(glm::vec3(0, 1, 0), dir);   // per node, not per leaf
    for (int k = 0; k < count; ++k) {
      // Phyllotaxis: successive leaves 137.5° apart around the twig, tilted away by `spread`.
      const float az = glm::radians(137.5f) * float(k) + r.uniform(0, 0.5f);
      glm::quat q = along * glm::angleAxis(az, glm::vec3(0, 1, 0)) * tilt;
      leaf l;
      l.position = t.position[i] - dir * (len * 0.4f * float(k) / float(std::max(count, 1)));
      l.orientation = glm::normalize(q);
      l.size = p.size * (1 + p.size_jitter * r.uniform(-1, 1));
      l.born = t.born[i];
      l.died = died;
      l.node = int32_t(i);
      out.push_back(l);
    }
  }
  return out;
}

float card_lowest_y(const leaf& l, const glm::vec3& x, const glm::vec3& y) {
  return l.position.y - 0.5f * l.size * std::abs(x.y) + l.size * std::min(0.0f, y.y);
}

void keep_leaves_above_ground(std::vector<leaf>& leaves, float ground) {
  if (!std::isfinite(ground)) return;
  const auto lowest = card_lowest_y;
  std::erase_if(leaves, [&](leaf& l) {
    if (l.position.y < ground) return true;
    // A card reaches at most 1.5 sizes from its petiole along axes a unit quaternion turns, and any
    // quaternion q lengthens a unit axis to at most 1 + 3|q|²: a leaf twice 1 + 4|q|² sizes above
    // the ground keeps its frame without turning the axes (most of a crown).
    const float reach = std::abs(l.size) * (1.0f + 4.0f * glm::dot(l.orientation, l.orientation));
    if (l.position.y - 2.0f * reach >= ground) return false;
    const glm::vec3 x = l.orientation * glm::vec3(1, 0, 0), y = l.orientation * glm::vec3(0, 1, 0);
    if (lowest(l, x, y) >= ground) return false;
    // Mirror the frame in the horizontal plane and flip the normal back to the sky, which keeps it
    // a rotation: the blade then rises as far as it fell.
    const glm::vec3 z = l.orientation * glm::vec3(0, 0, 1);
    const glm::vec3 mx(x.x, -x.y, x.z), my(y.x, -y.y, y.z), mz(-z.x, z.y, -z.z);
    if (lowest(l, mx, my) < ground) return true;
    l.orientation = glm::normalize(glm::quat_cast(glm::mat3(mx, my, mz)));
    return false;
  });
}

foliage place_leaves(const tree_skeleton& t, const leaf_params& p, uint64_t seed) {
  foliage f;
  if (p.mode == leaf_mode::generator && !t.leaves.empty()) {
    f.leaves = t.leaves;
  } else if (p.mode == leaf_mode::tips) {
    f.leaves = place_tip_leaves(t, p, seed);
    keep_leaves_above_ground(f.leaves, p.ground);
  } else {
    foliage s = place_shoot_leaves(t, p, seed);
    keep_leaves_above_ground(s.leaves, p.ground);
    return s;
  }
  const size_t cap = size_t(std::clamp(p.cap, 1, 2000000));
  if (f.leaves.size() > cap) {
    f.leaves.resize(cap);
    f.capped = true;
  }
  return f;
}

}  // namespace sylva
