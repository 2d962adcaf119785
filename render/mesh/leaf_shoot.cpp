#include "render/mesh/leaf_shoot.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <tuple>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <glm/vec3.hpp>

#include "generators/leaves.h"
#include "render/assets/textures.h"

namespace sylva {

bool archetype_is_shoot(leaf_archetype a) { return archetype_is_needle_shoot(a) || a == leaf_archetype::lanceolate; }

uint32_t shoot_archetype_mask() {
  uint32_t m = 0;
  for (int k = 0; k < std::min(leaf_archetype_count, 32); ++k)
    if (archetype_is_shoot(leaf_archetype(k))) m |= 1u << k;
  return m;
}

// ---------------------------------------------------------------- the picture's colours

shoot_swatches swatches_of(const image& im) {
  shoot_swatches out;
  const glm::vec2 centre(0.5f);
  out.needle.fill(centre), out.twig = centre;
  const int w = im.width, h = im.height;
  if (w <= 2 || h <= 2 || im.channels != 4 || im.pixels.size() < size_t(w) * size_t(h) * 4) return out;
  auto px = [&](int x, int y) { return &im.pixels[(size_t(y) * size_t(w) + size_t(x)) * 4]; };
  // Opaque texels, by hue: needles (green over red) and twig (red over green). A sample at a
  // texel's centre reads that texel alone in any reader's bilinear filter.
  struct texel {
    int luminance, x, y;
    bool operator<(const texel& o) const { return std::tie(luminance, y, x) < std::tie(o.luminance, o.y, o.x); }
  };
  std::vector<texel> green, brown, any;
  // Texels whose 3 x 3 neighbourhood is opaque where the picture has them; a small picture's
  // needles are narrower than three texels, so then any opaque texel, sampled at its centre.
  for (int need = 1; need >= 0 && any.empty(); --need)
    for (int y = 1; y + 1 < h; ++y)
      for (int x = 1; x + 1 < w; ++x) {
        bool solid = true;
        for (int dy = -need; dy <= need && solid; ++dy)
          for (int dx = -need; dx <= need && solid; ++dx) solid = px(x + dx, y + dy)[3] == 255;
        if (!solid) continue;
        const uint8_t* p = px(x, y);
        const texel t{2 * p[0] + 5 * p[1] + p[2], x, y};
        any.push_back(t);
        if (p[1] > p[0] + 8) green.push_back(t);
        else if (p[0] > p[1] + 8) brown.push_back(t);
      }
  if (any.empty()) return out;
  auto at = [&](std::vector<texel>& v, float q) {
    std::sort(v.begin(), v.end());
    const texel& t = v[std::min(v.size() - 1, size_t(q * float(v.size() - 1) + 0.5f))];
    return glm::vec2((float(t.x) + 0.5f) / float(w), (float(t.y) + 0.5f) / float(h));
  };
  std::vector<texel>& needles = green.empty() ? any : green;
  out.needle = {at(needles, 0.7f), at(needles, 0.5f), at(needles, 0.3f)};
  out.twig = brown.empty() ? at(any, 0.15f) : at(brown, 0.4f);
  return out;
}

const shoot_swatches& archetype_swatches(leaf_archetype a, int size, uint64_t seed) {
  static std::mutex mutex;
  static std::map<std::tuple<int, int, uint64_t>, std::unique_ptr<shoot_swatches>> cache;
  const auto key = std::make_tuple(std::clamp(int(a), 0, leaf_archetype_count - 1), size, seed);
  std::lock_guard lock(mutex);
  auto& slot = cache[key];
  if (!slot) slot = std::make_unique<shoot_swatches>(swatches_of(leaf_archetype_textures(leaf_archetype(std::get<0>(key)), size, seed).color));
  return *slot;
}

// ---------------------------------------------------------------- the spikes

namespace {

// A small deterministic generator, so a prototype is the same in every run and every reader.
struct shoot_random {
  uint32_t state;
  float next() {
    state ^= state << 13, state ^= state >> 17, state ^= state << 5;
    return float(state >> 8) * (1.0f / 16777216.0f);
  }
  float range(float a, float b) { return a + (b - a) * next(); }
};

constexpr float golden = 2.3999632f;   // radians: the golden angle of a spiral phyllotaxis

struct shoot_builder {
  leaf_mesh& m;
  int budget;
  int used = 0;

  // One spike from `base` along unit `dir`, `length` long, its root a triangle of `radius`; with
  // `flat` < 1 the root is squashed to `flat` of that across `wide` (a thin blade broad along `wide`).
  void spike(glm::vec3 base, glm::vec3 dir, float length, float radius, glm::vec2 uv, glm::vec3 wide = glm::vec3(0), float flat = 1) {
    if (used >= budget) return;
    ++used;
    dir = glm::normalize(dir);
    const glm::vec3 helper = std::abs(dir.z) < 0.9f ? glm::vec3(0, 0, 1) : glm::vec3(1, 0, 0);
    glm::vec3 e1 = wide - dir * glm::dot(wide, dir);
    e1 = glm::length(e1) > 1e-4f ? glm::normalize(e1) : glm::normalize(glm::cross(helper, dir));
    const glm::vec3 e2 = glm::cross(dir, e1);
    for (int k = 0; k < 3; ++k) {
      const float a = 2.0943951f * float(k);
      // The normal of the ellipse (radius, radius * flat) at angle a.
      const glm::vec3 normal = glm::normalize(flat * std::cos(a) * e1 + std::sin(a) * e2);
      m.vertex.push_back({base + radius * (std::cos(a) * e1 + flat * std::sin(a) * e2), normal, uv});
    }
    // The tip's normal leans to the shoot's upper side (the card's +Z), so a spike's tip shades
    // as its flanks seen from above.
    glm::vec3 up = glm::vec3(0, 0, 1) - dir * dir.z;
    up = glm::length(up) > 1e-4f ? glm::normalize(up) : e1;
    m.vertex.push_back({base + length * dir, up, uv});
  }
  void pad() {
    while (used < budget) {
      ++used;
      for (int k = 0; k < shoot_piece_vertices; ++k) m.vertex.push_back({glm::vec3(0), glm::vec3(0, 0, 1), glm::vec2(0.5f)});
    }
  }
};

// The unit directions across a shoot running along `d`: `across` in the card's plane, `up` the
// card's +Z side of it.
void shoot_frame(glm::vec3 d, glm::vec3& across, glm::vec3& up) {
  across = glm::vec3(1, 0, 0) - d * d.x;
  across = glm::length(across) > 1e-4f ? glm::normalize(across) : glm::vec3(0, 0, 1);
  up = glm::normalize(glm::cross(across, d));
  if (up.z < 0) up = -up, across = -across;
}

// A needle's direction: `forward` radians from the shoot's direction d, `azimuth` round it from
// `across` toward `up`.
glm::vec3 needle_direction(glm::vec3 d, float forward, float azimuth) {
  glm::vec3 across, up;
  shoot_frame(d, across, up);
  return std::cos(forward) * d + std::sin(forward) * (std::cos(azimuth) * across + std::sin(azimuth) * up);
}

// The azimuth of the k-th needle along a shoot: a golden-angle spiral all round it (spread 360),
// or, narrower, two ranks to the shoot's sides raised into a shallow V, each rank spread / 2 wide
// (fir's lateral shoots: the needles parted and turned up toward the light).
float needle_azimuth(int k, float spread, shoot_random& g) {
  if (spread >= 359.0f) return golden * float(k) + g.range(-0.2f, 0.2f);
  const float half_rank = glm::radians(std::clamp(spread, 20.0f, 360.0f)) * 0.25f;
  const float lift = glm::radians(25.0f);
  const float a = lift + g.range(-half_rank, half_rank);
  return k % 2 ? a : glm::radians(180.0f) - a;
}

// A straight shoot from a to b clothed in `count` needles of `length` (tapering near its tip).
void needle_axis(shoot_builder& b, glm::vec3 a, glm::vec3 e, int count, float length, float radius, const shoot_swatches& sw,
                 float spread, shoot_random& g, float axis_radius) {
  const glm::vec3 d = glm::normalize(e - a);
  const float len = glm::length(e - a);
  b.spike(a, d, len * 1.04f, axis_radius, sw.twig);
  for (int k = 0; k < count; ++k) {
    const float t = (float(k) + 0.5f) / float(std::max(count, 1));
    const float taper = 0.55f + 0.45f * std::min(1.0f, (1.0f - t) * len / 0.07f);
    const glm::vec3 p = a + (e - a) * t;
    const glm::vec3 dir = needle_direction(d, glm::radians(g.range(48, 70)), needle_azimuth(k, spread, g));
    b.spike(p, dir, length * taper * g.range(0.85f, 1.1f), radius, sw.needle[size_t(k % 3)]);
  }
}

// Pinus sylvestris (as the card, render/assets/archetype_conifers.cpp): a shoot bare below, then
// fascicles of two needles in a spiral, parted into a V, shorter upward, and a brush of the
// youngest needles round the terminal buds.
void build_pine(shoot_builder& b, int pieces, const shoot_swatches& sw, shoot_random& g) {
  const float top = 0.64f, fine = pieces >= 64 ? 1.0f : 0.0f;
  const float radius = 0.0075f + 0.0025f * (1 - fine);
  b.spike(glm::vec3(0), glm::vec3(0, 1, 0), top * 1.03f, 0.012f, sw.twig);
  const int needles = pieces - 1, brush = std::max(3, needles / 6), pairs = (needles - brush) / 2;
  const glm::vec3 d(0, 1, 0);
  for (int i = 0; i < pairs; ++i) {
    const float t = 0.3f + 0.68f * float(i) / float(std::max(pairs - 1, 1));
    const glm::vec3 p(0, top * t, 0);
    const float azimuth = golden * float(i);
    const float forward = glm::radians((58 - 30 * t) + g.range(-5, 5));
    const float part = glm::radians(g.range(12, 20));
    for (int k = 0; k < 2; ++k) {
      const glm::vec3 dir = needle_direction(d, forward, azimuth + (k ? part : -part) / std::max(std::sin(forward), 0.3f));
      b.spike(p, dir, g.range(0.25f, 0.33f) * (1 - 0.3f * t), radius, sw.needle[size_t((i + k) % 3)]);
    }
  }
  for (int k = 0; b.used < pieces; ++k) {
    const glm::vec3 dir = needle_direction(d, glm::radians(g.range(5, 32)), golden * float(k));
    b.spike(glm::vec3(0, top, 0), dir, g.range(0.13f, 0.2f), radius * 0.85f, sw.needle[size_t(k % 3)]);
  }
}

// Picea and Abies sprays: a leading shoot and alternate side shoots, longer below, every shoot
// clothed in needles round it (spread 360, spruce) or in two raised ranks (fir).
void build_spray(shoot_builder& b, int pieces, const shoot_swatches& sw, float spread, shoot_random& g) {
  const int sides = pieces >= 64 ? 6 : 2;
  struct axis {
    glm::vec3 a, e;
  };
  std::vector<axis> axes{{glm::vec3(0), glm::vec3(0.02f, 0.95f, 0.0f)}};
  for (int i = 0; i < sides; ++i) {
    const float t = 0.1f + 0.7f * float(i) / float(std::max(sides - 1, 1));
    const glm::vec3 p(0.02f * t, 0.95f * t, 0);
    const float side = i % 2 ? 1.0f : -1.0f, angle = glm::radians(g.range(46, 56));
    const float len = std::min(0.44f * (1 - 0.6f * t), 0.45f);
    axes.push_back({p, p + len * glm::vec3(side * std::sin(angle), std::cos(angle), 0.04f)});
  }
  float total = 0;
  for (const axis& x : axes) total += glm::length(x.e - x.a);
  const int needles = pieces - int(axes.size());
  const float radius = pieces >= 64 ? 0.0085f : 0.012f;
  int left = needles;
  for (size_t k = 0; k < axes.size(); ++k) {
    const float share = glm::length(axes[k].e - axes[k].a) / total;
    const int count = k + 1 == axes.size() ? left : std::min(left, int(std::lround(share * float(needles))));
    left -= count;
    needle_axis(b, axes[k].a, axes[k].e, count, pieces >= 64 ? 0.075f : 0.09f, radius, sw, spread, g, k ? 0.006f : 0.009f);
  }
}

// Cedrus: a long shoot and two side shoots with spur shoots along them, each spur ending in a
// rosette of short stiff needles that radiate forward.
void build_tufts(shoot_builder& b, int pieces, const shoot_swatches& sw, shoot_random& g) {
  struct axis {
    glm::vec3 a, e;
  };
  const axis axes[] = {{glm::vec3(0), glm::vec3(0.02f, 0.92f, 0)},
                       {glm::vec3(0.006f, 0.28f, 0), glm::vec3(-0.34f, 0.62f, 0.03f)},
                       {glm::vec3(0.009f, 0.41f, 0), glm::vec3(0.36f, 0.78f, 0.03f)}};
  for (const axis& x : axes) b.spike(x.a, x.e - x.a, glm::length(x.e - x.a), 0.0075f, sw.twig);
  const int rosette = pieces >= 64 ? 10 : 7;
  const int rosettes = (pieces - 3) / rosette;
  const float radius = pieces >= 64 ? 0.0075f : 0.01f;
  for (int r = 0; r < rosettes; ++r) {
    const axis& x = axes[size_t(r % 3)];
    const float t = 0.2f + 0.75f * float(r / 3 + 0.5f) / float((rosettes + 2) / 3);
    const glm::vec3 d = glm::normalize(x.e - x.a);
    const glm::vec3 p = x.a + (x.e - x.a) * std::min(t, 0.97f);
    const glm::vec3 toward = needle_direction(d, glm::radians(g.range(25, 45)), golden * float(r));
    for (int k = 0; k < rosette; ++k) {
      const glm::vec3 dir = needle_direction(toward, glm::radians(g.range(10, 62)), golden * float(k) + g.range(-0.3f, 0.3f));
      b.spike(p, dir, g.range(0.055f, 0.09f), radius, sw.needle[size_t(k % 3)]);
    }
  }
  for (int k = 0; b.used < pieces; ++k) {   // the long shoot's own scattered single needles
    const glm::vec3 p(0.02f * (0.55f + 0.04f * float(k)), 0.92f * (0.55f + 0.04f * float(k)), 0);
    b.spike(p, needle_direction(glm::vec3(0, 1, 0), glm::radians(g.range(35, 60)), golden * float(k)), g.range(0.04f, 0.06f), radius * 0.8f,
            sw.needle[size_t(k % 3)]);
  }
}

// Salix babylonica (as the lanceolate card, render/assets/archetype_leaves.cpp): a slender hanging
// shoot with narrow leaves 8-15 cm long lying close along it (8-22 degrees), alternate in a spiral,
// each a thin blade broad across the shoot, so a strand reads as a loose tassel from every side.
constexpr int willow_leaves = 18;   // the card's 13 and its tip, a few more as the strand is seen all round

void build_willow(shoot_builder& b, int pieces, const shoot_swatches& sw, shoot_random& g) {
  const float top = 0.74f;
  b.spike(glm::vec3(0), glm::vec3(0, 1, 0), top * 1.03f, 0.008f, sw.twig);
  const int leaves = std::min(pieces - 1, willow_leaves);
  const glm::vec3 d(0, 1, 0);
  for (int i = 0; i < leaves; ++i) {
    const float t = std::clamp(0.05f + 0.9f * (float(i) + g.range(-0.3f, 0.3f)) / float(std::max(leaves - 1, 1)), 0.03f, 0.97f);
    const float azimuth = glm::radians(144.0f) * float(i) + g.range(-0.3f, 0.3f);   // 2/5 phyllotaxis
    const glm::vec3 dir = needle_direction(d, glm::radians(g.range(8, 22) * (1.1f - 0.4f * t)), azimuth);
    glm::vec3 across, up;
    shoot_frame(d, across, up);
    const glm::vec3 radial = std::cos(azimuth) * across + std::sin(azimuth) * up;
    const float len = g.range(0.3f, 0.5f) * (1.0f - 0.3f * t);
    b.spike(glm::vec3(0, top * t, 0), dir, len, len * 0.045f, sw.needle[size_t(i % 3)], glm::cross(d, radial), 0.15f);
  }
}

}  // namespace

leaf_mesh shoot_prototype(leaf_archetype a, const leaf_blade_shape& s, int pieces, const shoot_swatches& sw) {
  leaf_mesh m;
  pieces = std::max(pieces, 4);
  m.vertex.reserve(size_t(pieces * shoot_piece_vertices));
  shoot_builder b{m, pieces};
  shoot_random g{0x9e3779b9u ^ (uint32_t(a) * 0x85ebca6bu) ^ uint32_t(pieces)};
  const float spread = std::isfinite(s.needle_spread) ? std::clamp(s.needle_spread, 20.0f, 360.0f) : 360.0f;
  if (a == leaf_archetype::needles) build_pine(b, pieces, sw, g);
  else if (a == leaf_archetype::lanceolate) build_willow(b, pieces, sw, g);
  else if (a == leaf_archetype::needle_tufts) build_tufts(b, pieces, sw, g);
  else build_spray(b, pieces, sw, spread, g);
  b.pad();
  // The species' curl bends the whole shoot down over its length about the card's x axis (a
  // drooping spray), the bend growing with the height along the card.
  const float curl = s.on && std::isfinite(s.curl) ? glm::radians(std::clamp(s.curl, -120.0f, 120.0f)) : 0.0f;
  if (curl != 0)
    for (blade_vertex& v : m.vertex) {
      const float phi = curl * std::clamp(v.position.y, 0.0f, 1.2f) * 0.5f;
      const float c = std::cos(phi), sn = std::sin(phi);
      auto turn = [&](glm::vec3 p) { return glm::vec3(p.x, c * p.y + sn * p.z, -sn * p.y + c * p.z); };
      v.position = turn(v.position), v.normal = turn(v.normal);
    }
  m.index = shoot_indices(pieces);
  return m;
}

std::vector<uint16_t> shoot_indices(int pieces) {
  std::vector<uint16_t> out;
  out.reserve(size_t(pieces * shoot_piece_triangles * 3));
  for (int p = 0; p < pieces; ++p) {
    const uint16_t o = uint16_t(p * shoot_piece_vertices), tip = uint16_t(o + 3);
    // Seen from outside each side (base vertices run counter-clockwise about the spike's direction).
    for (int k = 0; k < 3; ++k) out.insert(out.end(), {uint16_t(o + k), uint16_t(o + (k + 1) % 3), tip});
  }
  return out;
}

}  // namespace sylva
