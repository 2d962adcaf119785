// Internal to the archetype textures (render/assets/archetype_*.cpp): the shared drawing kit.
// Noise and colour helpers, the leaf canvas with its primitives (blades, strokes), the bark field,
// and the draw / fill functions each file defines. Not part of the public API (render/assets/textures.h).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "render/assets/textures.h"

namespace sylva::archetype {

using glm::vec2;
using glm::vec3;
inline constexpr float pi = 3.14159265358979f;

inline uint64_t mix64(uint64_t x) {  // SplitMix64 finaliser (Steele, Lea & Flood 2014)
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}
inline float unit(uint64_t x) { return float(mix64(x) >> 40) * (1.0f / 16777216.0f); }

// A small deterministic generator for placing primitives.
struct rng {
  uint64_t state;
  float next() { return unit(state++ * 0x2545F4914F6CDD1Dull); }
  float range(float a, float b) { return a + (b - a) * next(); }
};

// floor and round without libm calls (the baseline x86-64 target has no SSE4.1 roundss).
inline float ffloor(float x) {
  const float t = float(int(x));
  return t > x ? t - 1 : t;
}
inline float fround(float x) { return ffloor(x + 0.5f); }
inline float clamp01(float v) { return v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f; }   // NaN -> 0
inline float smooth(float a, float b, float x) {
  const float t = clamp01((x - a) / (b - a));
  return t * t * (3 - 2 * t);
}
inline int wrap(int i, int n) {  // i mod n for any i; the common cases without a division
  if (i >= 0 && i < n) return i;
  if (i < 0 && i >= -n) return i + n;
  if (i >= n && i < 2 * n) return i - n;
  return ((i % n) + n) % n;
}

// Periodic value noise: a cx * cy table of random values, smoothly interpolated; it wraps at 1.
struct lattice {
  int cx, cy;
  std::vector<float> v;
  lattice(int cx_, int cy_, uint64_t seed) : cx(cx_), cy(cy_), v(size_t(cx_) * size_t(cy_)) {
    for (size_t i = 0; i < v.size(); ++i) v[i] = unit(seed * 0x100000001B3ull + i);
  }
  float operator()(float u, float w) const {
    const float fx = u * float(cx), fy = w * float(cy);
    const float flx = ffloor(fx), fly = ffloor(fy);
    const int x0 = wrap(int(flx), cx), y0 = wrap(int(fly), cy);
    const int x1 = x0 + 1 == cx ? 0 : x0 + 1, y1 = y0 + 1 == cy ? 0 : y0 + 1;
    float tx = fx - flx, ty = fy - fly;
    tx = tx * tx * (3 - 2 * tx), ty = ty * ty * (3 - 2 * ty);
    const float* r0 = &v[size_t(y0) * cx];
    const float* r1 = &v[size_t(y1) * cx];
    const float a = r0[x0] + (r0[x1] - r0[x0]) * tx, b = r1[x0] + (r1[x1] - r1[x0]) * tx;
    return a + (b - a) * ty;
  }
};

// sRGB transfer function (IEC 61966-2-1) as tables: 256 bytes -> linear, 4096 linear steps -> byte.
struct srgb_tables {
  float to_linear[256];
  uint8_t to_srgb[4097];
  srgb_tables();
};
const srgb_tables& srgb();
extern const uint8_t* const linear_to_byte;  // made before main: no guard per call
inline uint8_t linear_byte(float l) { return linear_to_byte[int(clamp01(l) * 4096.0f + 0.5f)]; }
inline uint8_t unit_byte(float v) { return uint8_t(clamp01(v) * 255.0f + 0.5f); }
vec3 srgb_color(int r, int g, int b);

// Tangent-space normal map from a height field in texel units (dh per texel = slope); +Y points up
// the image (rows run downward), matching the bark shader's convention.
image normal_from_height(const std::vector<float>& h, int n, bool periodic, const std::vector<float>* mask);

// Float work buffers reused from one set to the next (fresh pages cost a fault each): a small
// pool any thread may take from.
struct scratch {
  std::vector<float> layer[6];
};
struct scratch_lease {
  std::unique_ptr<scratch> s;
  static std::mutex& mu() {
    static std::mutex m;
    return m;
  }
  static std::vector<std::unique_ptr<scratch>>& pool() {
    static std::vector<std::unique_ptr<scratch>> p;
    return p;
  }
  scratch_lease() {
    std::lock_guard lock(mu());
    if (pool().empty()) {
      s = std::make_unique<scratch>();
    } else {
      s = std::move(pool().back());
      pool().pop_back();
    }
  }
  ~scratch_lease() {
    std::lock_guard lock(mu());
    pool().push_back(std::move(s));
  }
  scratch_lease(const scratch_lease&) = delete;
  scratch_lease& operator=(const scratch_lease&) = delete;
  std::vector<float>& operator[](int i) { return s->layer[i]; }
};

// ================================================================ leaf cards
// Card coordinates: x right, y up, both 0..1; the petiole enters at (0.5, 0).

struct sample {
  float cover = 0;   // 0..1 (anti-aliased)
  float height = 0;  // card units
  float shade = 1;   // colour multiplier
  float warm = 0;    // 0: the archetype's blade colour, 1: its (yellower) vein colour
  float thin = 0.9f; // 1: thinnest blade
};

struct leaf_canvas {
  int n;
  float px;  // one texel in card units
  std::vector<float>&alpha, &height, &shade, &warm, &thin;  // in a scratch lease
  leaf_canvas(int n_, scratch_lease& s)
      : n(n_), px(1.0f / float(n_)), alpha(s[0]), height(s[1]), shade(s[2]), warm(s[3]), thin(s[4]) {
    const size_t count = size_t(n_) * size_t(n_);
    alpha.assign(count, 0.0f), height.assign(count, 0.0f), shade.assign(count, 1.0f), warm.assign(count, 0.0f);
    thin.assign(count, 0.9f);
  }
  // Painter's order: a later primitive covers an earlier one by its coverage.
  void put(size_t k, const sample& s) {
    const float c = s.cover, o = 1 - c;
    height[k] = height[k] * o + s.height * c;
    shade[k] = shade[k] * o + s.shade * c;
    warm[k] = warm[k] * o + s.warm * c;
    thin[k] = thin[k] * o + s.thin * c;
    alpha[k] = c + alpha[k] * o;
  }
};

inline vec2 heading(float degrees) {  // 90 = straight up the card
  const float a = degrees * pi / 180.0f;
  return {std::cos(a), std::sin(a)};
}

// The longest length <= len that keeps base + dir * length inside the card with a margin.
inline float fit(vec2 base, vec2 dir, float len, float margin = 0.012f) {
  for (int i = 0; i < 2; ++i) {
    if (dir[i] > 1e-6f) len = std::min(len, (1 - margin - base[i]) / dir[i]);
    if (dir[i] < -1e-6f) len = std::min(len, (margin - base[i]) / dir[i]);
  }
  return std::max(len, 0.0f);
}

// Visits the texels near the oriented rectangle {base + dir * a + perp * b : a in [-cap, len + cap],
// |b| <= reach} row by row (only the span each row crosses) and hands f the texel's (a, b).
template <class F>
void raster(leaf_canvas& c, vec2 base, vec2 dir, float len, float reach, float cap, F&& f) {
  const vec2 perp(-dir.y, dir.x);
  const float m = 2 * c.px;
  const float a0 = -cap - m, a1 = len + cap + m, b0 = -reach - m, b1 = reach + m;
  float ymin = 1e9f, ymax = -1e9f;
  for (float a : {a0, a1})
    for (float b : {b0, b1}) {
      const float y = base.y + dir.y * a + perp.y * b;
      ymin = std::min(ymin, y), ymax = std::max(ymax, y);
    }
  const int n = c.n;
  const int row0 = std::max(0, int(ffloor((1 - ymax) * float(n) - 0.5f)));
  const int row1 = std::min(n - 1, int(std::ceil((1 - ymin) * float(n) - 0.5f)));
  for (int row = row0; row <= row1; ++row) {
    const float y = 1 - (float(row) + 0.5f) * c.px;
    float xlo = 0, xhi = 1;
    // Each constraint is linear in x: k * x + q in [lo, hi].
    auto limit = [&](float k, float q, float lo, float hi) {
      if (std::abs(k) < 1e-7f) {
        if (q < lo || q > hi) xlo = 1, xhi = 0;
        return;
      }
      float u = (lo - q) / k, v = (hi - q) / k;
      if (u > v) std::swap(u, v);
      xlo = std::max(xlo, u), xhi = std::min(xhi, v);
    };
    limit(dir.x, dir.y * (y - base.y) - dir.x * base.x, a0, a1);
    limit(perp.x, perp.y * (y - base.y) - perp.x * base.x, b0, b1);
    if (xlo > xhi) continue;
    const int col0 = std::max(0, int(std::ceil(xlo * float(n) - 0.5f)));
    const int col1 = std::min(n - 1, int(ffloor(xhi * float(n) - 0.5f)));
    for (int col = col0; col <= col1; ++col) {
      const vec2 d((float(col) + 0.5f) * c.px - base.x, y - base.y);
      const sample s = f(glm::dot(d, dir), glm::dot(d, perp));
      if (s.cover > 0) c.put(size_t(row) * n + col, s);
    }
  }
}

struct blade_style {
  float serration = 0;    // depth of the teeth as a share of the half-width
  float teeth = 0;        // teeth along the blade
  float vein_angle = 45;  // secondary veins leave the midrib at this angle (degrees)
  float veins = 8;        // secondary veins per side
  float bend = 0;         // the axis curves sideways by bend * len * t^2
  float midrib = 1;       // midrib strength
  float edge_dark = 0.28f;
  float dome = 0.10f;     // height of the blade's curvature, as a share of its width
};

// A blade: half-width width * profile(t, side) along an axis from base (t = 0) to tip (t = 1).
// Height: a gentle dome across the blade, a midrib ridge and secondary veins as shallow grooves.
template <class Profile>
void blade(leaf_canvas& c, vec2 base, float degrees, float len, float width, Profile profile, const blade_style& st) {
  const vec2 dir = heading(degrees);
  const float px = c.px;
  const float tan_a = std::tan(st.vein_angle * pi / 180.0f), sin_a = std::sin(st.vein_angle * pi / 180.0f);
  const float spacing = len / std::max(st.veins, 1.0f);
  const float mw = std::max(1.4f * px, 0.05f * width), vw = std::max(0.9f * px, 0.012f * width);
  // The outline tabulated per side (the profiles use pow and sin: too slow per texel).
  constexpr int steps = 256;
  float table[2][steps + 2];
  for (int side = 0; side < 2; ++side) {
    for (int i = 0; i <= steps; ++i) table[side][i] = profile(std::clamp(float(i) / steps, 1e-4f, 1 - 1e-4f), side);
    table[side][steps + 1] = table[side][steps];
  }
  raster(c, base, dir, len, width + std::abs(st.bend) * len, 0, [&](float a, float b) {
    sample s;
    const float t = a / len;
    if (t <= 0 || t >= 1) return s;
    const float bs = b - st.bend * len * t * t;
    const float as = std::abs(bs);
    const float ft = t * steps;
    const int it = int(ft);
    const float* tb = table[bs < 0 ? 1 : 0];
    const float w0 = width * (tb[it] + (tb[it + 1] - tb[it]) * (ft - float(it)));
    float w = w0;
    if (st.serration > 0 && t > 0.05f && t < 0.97f) w *= 1 - st.serration * (1 - (t * st.teeth - ffloor(t * st.teeth)));
    const float edge = w - as;
    s.cover = clamp01(edge / px + 0.5f);
    if (s.cover <= 0) return s;
    const float u = std::min(as / std::max(w0, 1e-6f), 1.0f);  // across the outline without its teeth
    const float r = as / mw, mid = st.midrib * std::max(0.0f, 1 - r * r) * (1 - 0.6f * t);
    // Secondary veins: lines a - |b| / tan(angle) = const, bending toward the tip near the margin.
    const float q = (a - as / tan_a * (1 + 0.4f * u)) / spacing;
    const float dv = std::abs(q - fround(q)) * spacing * sin_a;
    float vein = std::max(0.0f, 1 - dv / vw) * smooth(mw, 2 * mw, as) * (1 - smooth(0.8f, 0.97f, u)) * (q > 0.3f ? 1.0f : 0.0f);
    vein *= 0.9f;
    const float edge_fade = clamp01(edge / (4 * px));
    // The dome follows the distance from the midrib, not the outline, so lobes and teeth add no
    // ripples of their own.
    const float across = std::min(as / width, 1.0f);
    s.height = st.dome * width * (1 - across * across) + 1.3f * px * mid - 0.5f * px * vein;
    s.shade = (1 + 0.10f * mid + 0.07f * vein) * (1 - st.edge_dark + st.edge_dark * edge_fade);
    s.warm = std::min(1.0f, 0.7f * mid + 0.45f * vein);
    s.thin = 0.95f - 0.6f * mid - 0.3f * vein;
    return s;
  });
}

struct stroke_style {
  float shade = 0.8f, warm = 0.6f, thin = 0.15f;
  float stripe = 0;  // lighter line along the middle (needles' stomatal bands)
};

// A tapered capsule from a (radius r0) to b (radius r1): stems, rachises, needles.
void stroke(leaf_canvas& c, vec2 a, vec2 b, float r0, float r1, const stroke_style& st);

// A curve drawn as a chain of strokes; curve(t) for t in [0, 1].
template <class Curve>
void curve_stroke(leaf_canvas& c, Curve curve, int segments, float r0, float r1, const stroke_style& st) {
  for (int i = 0; i < segments; ++i) {
    const float t0 = float(i) / float(segments), t1 = float(i + 1) / float(segments);
    stroke(c, curve(t0), curve(t1), r0 + (r1 - r0) * t0, r0 + (r1 - r0) * t1, st);
  }
}

inline vec2 bezier(vec2 p0, vec2 p1, vec2 p2, float t) {  // quadratic Bezier
  const float s = 1 - t;
  return s * s * p0 + 2 * s * t * p1 + t * t * p2;
}
inline float degrees_of(vec2 d) { return std::atan2(d.y, d.x) * 180.0f / pi; }

// Blade outlines: relative half-width along t (0 base .. 1 tip).
inline float ovate_profile(float t) { return std::pow(std::sin(pi * std::pow(t, 0.72f)), 0.8f); }
inline float lanceolate_profile(float t) { return std::pow(std::sin(pi * std::pow(t, 0.9f)), 0.75f); }

inline const stroke_style petiole_style{0.78f, 0.75f, 0.2f, 0};
inline const stroke_style twig_style{0.55f, 1.0f, 0.05f, 0};

struct leaf_look {
  vec3 blade, vein;  // sRGB bytes
};
// The canvas turned into the card's maps: colour (blade to vein colour, blotches, grain) + alpha,
// normal from the height layer (h: scratch for it), thickness.
leaf_texture_set finish_leaf(const leaf_canvas& c, std::vector<float>& h, const leaf_look& look, uint64_t seed);

// The cards (render/assets/archetype_leaves.cpp: broadleaves and the palm frond;
// render/assets/archetype_conifers.cpp: needles and scale sprays).
void draw_ovate(leaf_canvas& c, rng& g);
void draw_lobed(leaf_canvas& c, rng& g);
void draw_palmate(leaf_canvas& c, rng& g);
void draw_pinnate(leaf_canvas& c, rng& g);
void draw_needles(leaf_canvas& c, rng& g);
void draw_flat_spray(leaf_canvas& c, rng& g);
void draw_scale_spray(leaf_canvas& c, rng& g);
void draw_palm_frond(leaf_canvas& c, rng& g);
void draw_twig_cluster(leaf_canvas& c, rng& g);
void draw_needle_tufts(leaf_canvas& c, rng& g);
void draw_lanceolate(leaf_canvas& c, rng& g);
void draw_beech_spray(leaf_canvas& c, rng& g);
void draw_hazel_spray(leaf_canvas& c, rng& g);
void draw_poplar_spray(leaf_canvas& c, rng& g);
void draw_maple_spray(leaf_canvas& c, rng& g);
void draw_horse_chestnut(leaf_canvas& c, rng& g);
void draw_cypress_cones(leaf_canvas& c, rng& g);
void draw_birch(leaf_canvas& c, rng& g);
// Fruit cards (render/assets/archetype_fruits.cpp), drawn in their final colours.
void draw_cone_hanging(leaf_canvas& c, rng& g);
void draw_cone_upright(leaf_canvas& c, rng& g);
void draw_samaras(leaf_canvas& c, rng& g);
void draw_hazelnuts(leaf_canvas& c, rng& g);
void draw_cone_ovoid(leaf_canvas& c, rng& g);
void draw_beechnuts(leaf_canvas& c, rng& g);
void draw_coconuts(leaf_canvas& c, rng& g);
void draw_ash_keys(leaf_canvas& c, rng& g);
void draw_cone_barrel(leaf_canvas& c, rng& g);
void draw_acorns(leaf_canvas& c, rng& g);

// ================================================================ bark
// Tile coordinates u (around the branch) and v (along it, image rows), both periodic in [0, 1).

// The fill functions write each texel's height (scratch, for the normal map) and its colour
// (linear) and roughness straight into the output bytes.
struct bark_field {
  int n;
  std::vector<float>& height;
  bark_texture_set out;
  bark_field(int n_, scratch_lease& s) : n(n_), height(s[0]) {
    const size_t count = size_t(n_) * size_t(n_);
    height.assign(count, 0.0f);
    out.color = image{n_, n_, 3, std::vector<uint8_t>(count * 3)};
    out.roughness = image{n_, n_, 3, std::vector<uint8_t>(count * 3)};
  }
  void paint(size_t k, const vec3& linear, float roughness) {
    uint8_t* c = &out.color.pixels[k * 3];
    c[0] = linear_byte(linear.x), c[1] = linear_byte(linear.y), c[2] = linear_byte(linear.z);
    uint8_t* r = &out.roughness.pixels[k * 3];
    r[0] = r[1] = unit_byte(roughness), r[2] = 0;  // glTF: G roughness, B metalness
  }
};

inline vec3 mix3(vec3 a, vec3 b, float t) { return a + (b - a) * t; }

// The barks (render/assets/archetype_bark.cpp).
void bark_furrowed(bark_field& f, uint64_t seed);
void bark_plated(bark_field& f, uint64_t seed);
void bark_smooth(bark_field& f, uint64_t seed);
void bark_peeling(bark_field& f, uint64_t seed);
void bark_ringed(bark_field& f, uint64_t seed);
void bark_mottled(bark_field& f, uint64_t seed);
void bark_fissured(bark_field& f, uint64_t seed);
void bark_fibrous(bark_field& f, uint64_t seed);
void bark_silver(bark_field& f, uint64_t seed);
// Scales the heights by relief (height units per tile width) and makes the normal map.
bark_texture_set finish_bark(bark_field& f, float relief);

}  // namespace sylva::archetype
