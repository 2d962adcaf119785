// Archetype texture sets (issue 11): leaf cards drawn from analytic primitives (blades, strokes)
// into float layers, and periodic bark height/colour fields; normal maps from the height fields.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <thread>
#include <tuple>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "render/textures.h"

namespace sylva {
namespace {

using glm::vec2;
using glm::vec3;
constexpr float pi = 3.14159265358979f;

uint64_t mix64(uint64_t x) {  // SplitMix64 finaliser (Steele, Lea & Flood 2014)
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}
float unit(uint64_t x) { return float(mix64(x) >> 40) * (1.0f / 16777216.0f); }

// A small deterministic generator for placing primitives.
struct rng {
  uint64_t state;
  float next() { return unit(state++ * 0x2545F4914F6CDD1Dull); }
  float range(float a, float b) { return a + (b - a) * next(); }
};

// floor and round without libm calls (the baseline x86-64 target has no SSE4.1 roundss).
float ffloor(float x) {
  const float t = float(int(x));
  return t > x ? t - 1 : t;
}
float fround(float x) { return ffloor(x + 0.5f); }
float clamp01(float v) { return std::clamp(v, 0.0f, 1.0f); }
float smooth(float a, float b, float x) {
  const float t = clamp01((x - a) / (b - a));
  return t * t * (3 - 2 * t);
}
int wrap(int i, int n) {  // i mod n for any i; the common cases without a division
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
  srgb_tables() {
    for (int i = 0; i < 256; ++i) {
      const float c = float(i) / 255.0f;
      to_linear[i] = c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
    }
    for (int i = 0; i <= 4096; ++i) {
      const float l = float(i) / 4096.0f;
      const float s = l <= 0.0031308f ? l * 12.92f : 1.055f * std::pow(l, 1.0f / 2.4f) - 0.055f;
      to_srgb[i] = uint8_t(std::clamp(s, 0.0f, 1.0f) * 255.0f + 0.5f);
    }
  }
};
const srgb_tables& srgb() {
  static const srgb_tables t;
  return t;
}
const uint8_t* const linear_to_byte = srgb().to_srgb;  // made before main: no guard per call
uint8_t linear_byte(float l) { return linear_to_byte[int(clamp01(l) * 4096.0f + 0.5f)]; }
uint8_t unit_byte(float v) { return uint8_t(clamp01(v) * 255.0f + 0.5f); }
vec3 srgb_color(int r, int g, int b) {
  const auto& t = srgb().to_linear;
  return {t[r], t[g], t[b]};
}

// Tangent-space normal map from a height field in texel units (dh per texel = slope); +Y points up
// the image (rows run downward), matching the bark shader's convention.
image normal_from_height(const std::vector<float>& h, int n, bool periodic, const std::vector<float>* mask) {
  image img{n, n, 3, std::vector<uint8_t>(size_t(n) * n * 3)};
  auto H = [&](int x, int y) {
    if (periodic) x = wrap(x, n), y = wrap(y, n);
    else x = std::clamp(x, 0, n - 1), y = std::clamp(y, 0, n - 1);
    return h[size_t(y) * n + size_t(x)];
  };
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      uint8_t* p = &img.pixels[(size_t(y) * n + x) * 3];
      if (mask && (*mask)[size_t(y) * n + x] <= 0) {
        p[0] = 128, p[1] = 128, p[2] = 255;
        continue;
      }
      const float dx = 0.5f * (H(x + 1, y) - H(x - 1, y));
      const float dy_up = 0.5f * (H(x, y - 1) - H(x, y + 1));
      const float inv = 1.0f / std::sqrt(dx * dx + dy_up * dy_up + 1.0f);
      p[0] = unit_byte(-dx * inv * 0.5f + 0.5f);
      p[1] = unit_byte(-dy_up * inv * 0.5f + 0.5f);
      p[2] = unit_byte(inv * 0.5f + 0.5f);
    }
  return img;
}

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

vec2 heading(float degrees) {  // 90 = straight up the card
  const float a = degrees * pi / 180.0f;
  return {std::cos(a), std::sin(a)};
}

// The longest length <= len that keeps base + dir * length inside the card with a margin.
float fit(vec2 base, vec2 dir, float len, float margin = 0.012f) {
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
void stroke(leaf_canvas& c, vec2 a, vec2 b, float r0, float r1, const stroke_style& st) {
  const float len = glm::length(b - a);
  if (len < 1e-6f) return;
  const vec2 dir = (b - a) / len;
  const float px = c.px, rmax = std::max(r0, r1);
  raster(c, a, dir, len, rmax, rmax, [&](float along, float across) {
    sample s;
    const float tc = clamp01(along / len);
    const float r = std::max(r0 + (r1 - r0) * tc, 0.35f * px);
    const float da = along < 0 ? -along : (along > len ? along - len : 0.0f);
    const float d = std::sqrt(da * da + across * across);
    s.cover = clamp01((r - d) / px + 0.5f);
    if (s.cover <= 0) return s;
    const float u = std::min(d / r, 1.0f);
    s.height = r * std::sqrt(1 - u * u) * 0.8f;
    s.shade = st.shade * (0.82f + 0.22f * (1 - u * u)) * (1 + st.stripe * std::max(0.0f, 1 - std::abs(across) / (0.3f * r)));
    s.warm = st.warm;
    s.thin = st.thin;
    return s;
  });
}

// A curve drawn as a chain of strokes; curve(t) for t in [0, 1].
template <class Curve>
void curve_stroke(leaf_canvas& c, Curve curve, int segments, float r0, float r1, const stroke_style& st) {
  for (int i = 0; i < segments; ++i) {
    const float t0 = float(i) / float(segments), t1 = float(i + 1) / float(segments);
    stroke(c, curve(t0), curve(t1), r0 + (r1 - r0) * t0, r0 + (r1 - r0) * t1, st);
  }
}

vec2 bezier(vec2 p0, vec2 p1, vec2 p2, float t) {  // quadratic Bezier
  const float s = 1 - t;
  return s * s * p0 + 2 * s * t * p1 + t * t * p2;
}
float degrees_of(vec2 d) { return std::atan2(d.y, d.x) * 180.0f / pi; }

// Blade outlines: relative half-width along t (0 base .. 1 tip).
float ovate_profile(float t) { return std::pow(std::sin(pi * std::pow(t, 0.72f)), 0.8f); }
float lanceolate_profile(float t) { return std::pow(std::sin(pi * std::pow(t, 0.9f)), 0.75f); }

const stroke_style petiole_style{0.78f, 0.75f, 0.2f, 0};
const stroke_style twig_style{0.55f, 1.0f, 0.05f, 0};

// --- the nine cards

void draw_ovate(leaf_canvas& c, rng&) {
  stroke(c, {0.5f, 0.0f}, {0.5f, 0.15f}, 0.0065f, 0.0055f, petiole_style);
  blade_style st;
  st.serration = 0.07f, st.teeth = 26, st.vein_angle = 40, st.veins = 9;
  blade(c, {0.5f, 0.13f}, 90, 0.84f, 0.35f, [](float t, int) { return ovate_profile(t); }, st);
}

void draw_lobed(leaf_canvas& c, rng&) {
  stroke(c, {0.5f, 0.0f}, {0.5f, 0.09f}, 0.0075f, 0.0065f, petiole_style);
  blade_style st;
  const float lobes = 4.5f;
  st.vein_angle = 52, st.veins = lobes;
  blade(c, {0.5f, 0.075f}, 90, 0.9f, 0.37f, [&](float t, int side) {
    // Obovate outline cut by rounded lobes and deep sinuses; the sides are slightly out of step,
    // and two small auricles sit at the base (Quercus robur).
    const float outline = std::pow(std::sin(pi * std::pow(t, 1.25f)), 0.7f);
    const float phase = side ? 0.18f : 0.0f;
    const float lobe = std::pow(0.5f + 0.5f * std::cos(2 * pi * (lobes * t + phase - 0.25f)), 0.35f);
    const float auricle = 0.22f * std::max(0.0f, 1 - std::abs(t - 0.045f) / 0.04f);
    return outline * (0.3f + 0.7f * lobe) + auricle;
  }, st);
}

// Darkens the card's outline as a whole and rounds the blade up from it: for shapes drawn as
// overlapping parts (a maple's lobes), whose own edges would show inside the union. Distance to the
// nearest cut-away texel by a 3-4 chamfer transform (Borgefors 1986), two passes, in texels (x 3).
void darken_silhouette(leaf_canvas& c, float amount, float width_px, float dome) {
  const int n = c.n;
  const float far = 3 * std::max(width_px + 2, 0.08f * float(n) + 2);
  std::vector<float> d(size_t(n) * n);
  for (size_t k = 0; k < d.size(); ++k) d[k] = c.alpha[k] < 0.5f ? 0.0f : far;
  auto at = [&](int x, int y) { return x < 0 || y < 0 || x >= n || y >= n ? 0.0f : d[size_t(y) * n + x]; };
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      float& v = d[size_t(y) * n + x];
      v = std::min({v, at(x - 1, y) + 3, at(x, y - 1) + 3, at(x - 1, y - 1) + 4, at(x + 1, y - 1) + 4});
    }
  for (int y = n - 1; y >= 0; --y)
    for (int x = n - 1; x >= 0; --x) {
      float& v = d[size_t(y) * n + x];
      v = std::min({v, at(x + 1, y) + 3, at(x, y + 1) + 3, at(x + 1, y + 1) + 4, at(x - 1, y + 1) + 4});
    }
  const float dome_px = 0.08f * float(n);  // the dome rises over this distance from the outline
  for (size_t k = 0; k < d.size(); ++k)
    if (c.alpha[k] > 0) {
      c.shade[k] *= 1 - amount + amount * clamp01((d[k] / 3 - 0.5f) / width_px);
      const float t = std::min(d[k] / 3 / dome_px, 1.0f);
      c.height[k] += dome * t * (2 - t);
    }
}

void draw_palmate(leaf_canvas& c, rng&) {
  const vec2 centre{0.5f, 0.31f};
  stroke(c, {0.5f, 0.0f}, centre + vec2(0, 0.01f), 0.0065f, 0.006f, petiole_style);
  blade_style st;
  st.vein_angle = 50, st.veins = 6, st.serration = 0.0f, st.edge_dark = 0, st.midrib = 0, st.dome = 0;
  // Acer platanoides: five pointed lobes with a few large teeth; palmate venation from the centre.
  auto lobe = [](float t, int) {
    const float body = std::pow(1 - t, 0.9f) * (0.5f + 0.5f * smooth(0.0f, 0.3f, t));
    // Two or three big pointed teeth on each side of the lobe's upper half.
    const float f = t * 3.2f - ffloor(t * 3.2f);
    const float tooth = t > 0.32f && t < 0.9f ? 1 - 0.45f * (1 - f) * (1 - f) : 1.0f;
    return body * tooth;
  };
  const float angles[5] = {-10, 40, 90, 140, 190};  // degrees: basal, side, centre, side, basal
  const float lengths[5] = {0.33f, 0.56f, 0.66f, 0.56f, 0.33f};
  const float widths[5] = {0.16f, 0.27f, 0.29f, 0.27f, 0.16f};
  for (int k : {0, 4, 1, 3, 2}) {
    st.bend = k == 0 ? -0.05f : k == 4 ? 0.05f : 0.0f;
    blade(c, centre, angles[k], fit(centre, heading(angles[k]), lengths[k]), widths[k], lobe, st);
  }
  // The main veins all leave the petiole's tip, drawn over the joined lobes.
  const stroke_style vein{1.08f, 0.9f, 0.35f, 0};
  for (int k = 0; k < 5; ++k)
    stroke(c, centre, centre + heading(angles[k]) * (0.85f * fit(centre, heading(angles[k]), lengths[k])), 0.0032f, 0.001f, vein);
  darken_silhouette(c, 0.28f, 4, 0.012f);
}

void draw_pinnate(leaf_canvas& c, rng& g) {
  auto rachis = [](float t) { return vec2(0.5f + 0.015f * std::sin(2.5f * t), 0.78f * t); };
  curve_stroke(c, rachis, 6, 0.0075f, 0.0042f, petiole_style);
  blade_style st;
  st.serration = 0.06f, st.teeth = 16, st.vein_angle = 45, st.veins = 8, st.midrib = 0.9f;
  auto leaflet = [](float t, int) { return lanceolate_profile(t); };
  // Fraxinus excelsior: four opposite pairs and a terminal leaflet (nine in all).
  const float at[4] = {0.28f, 0.46f, 0.63f, 0.80f};
  for (int i = 0; i < 4; ++i) {
    const vec2 p = rachis(at[i]);
    for (int side : {-1, 1}) {
      const float ang = 90 - side * g.range(58, 66);
      const float len = (0.26f + 0.03f * float(i) / 3) * g.range(0.95f, 1.05f);
      const vec2 d = heading(ang);
      stroke(c, p, p + d * 0.015f, 0.003f, 0.0025f, petiole_style);
      st.bend = -side * 0.03f;
      blade(c, p + d * 0.012f, ang, fit(p, d, len), 0.058f, leaflet, st);
    }
  }
  st.bend = 0;
  blade(c, rachis(1.0f) - vec2(0, 0.005f), 90, fit(rachis(1.0f), {0, 1}, 0.21f), 0.058f, leaflet, st);
}

void draw_needles(leaf_canvas& c, rng& g) {
  // Pinus sylvestris shoot: fascicles of two (sometimes three) long needles packed along a twig,
  // fanning outward and upward so that the card reads as a dense tuft.
  auto twig = [](float t) { return vec2(0.5f + 0.02f * std::sin(3.0f * t), 0.57f * t); };
  stroke_style needle{0.92f, 0.0f, 0.3f, 0.12f};
  const int fascicles = 56;
  for (int i = 0; i < fascicles; ++i) {
    const float t = 0.06f + 0.94f * float(i) / float(fascicles - 1);
    const vec2 p = twig(t) + vec2(g.range(-0.008f, 0.008f), 0);
    const float side = (i % 2) ? 1.0f : -1.0f;
    const float spread = 72 - 58 * t + g.range(-10, 10);   // low fascicles splay wide, the tip points up
    const float ang = 90 + side * spread;
    const int count = g.next() < 0.2f ? 3 : 2;
    for (int k = 0; k < count; ++k) {
      const float a = ang + (float(k) - 0.5f * float(count - 1)) * g.range(5, 10);
      const vec2 d = heading(a);
      const float len = fit(p, d, g.range(0.36f, 0.5f));
      needle.shade = g.range(0.85f, 1.0f);
      stroke(c, p, p + d * len, 0.0064f, 0.0009f, needle);
    }
    stroke(c, p - heading(ang) * 0.006f, p + heading(ang) * 0.012f, 0.0065f, 0.005f, {0.45f, 1.0f, 0.05f, 0});  // sheath
  }
  curve_stroke(c, twig, 5, 0.013f, 0.009f, twig_style);
  // The shoot's terminal tuft.
  const vec2 tip = twig(1.0f);
  for (int k = 0; k < 14; ++k) {
    const float a = 90 + g.range(-32, 32);
    const vec2 d = heading(a);
    stroke(c, tip, tip + d * fit(tip, d, g.range(0.3f, 0.42f)), 0.0055f, 0.0008f, needle);
  }
}

// Needles on both sides of an axis, pointing forward (flat sprays of Abies, Picea).
void needle_comb(leaf_canvas& c, rng& g, vec2 a, vec2 b, float needle_len, float spacing, const stroke_style& st) {
  const float len = glm::length(b - a);
  const vec2 dir = (b - a) / len;
  const float ang = degrees_of(dir);
  for (float s = 0.01f; s < len; s += spacing)
    for (int side : {-1, 1}) {
      const vec2 p = a + dir * s;
      const float taper = 0.6f + 0.4f * std::min(1.0f, (len - s) / 0.08f);
      const vec2 d = heading(ang + float(side) * g.range(58, 75));
      stroke(c, p, p + d * fit(p, d, needle_len * taper * g.range(0.85f, 1.1f)), 0.0042f, 0.0028f, st);
    }
  stroke(c, a, b, 0.0045f, 0.0035f, twig_style);
}

void draw_flat_spray(leaf_canvas& c, rng& g) {
  const stroke_style st{0.95f, 0.05f, 0.35f, 0.1f};
  auto axis = [](float t) { return vec2(0.5f + 0.02f * std::sin(2 * t), 0.95f * t); };
  // Alternate side branchlets, longer below: the spray's outline narrows to the tip.
  for (int i = 0; i < 8; ++i) {
    const float t = 0.1f + 0.1f * float(i);
    const vec2 p = axis(t);
    const float side = (i % 2) ? 1.0f : -1.0f;
    const vec2 d = heading(90 + side * g.range(48, 56));
    const float len = fit(p, d, 0.44f * (1 - 0.6f * t), 0.07f);
    needle_comb(c, g, p, p + d * len, 0.058f, 0.011f, st);
  }
  for (int i = 0; i < 6; ++i) needle_comb(c, g, axis(float(i) / 6), axis(float(i + 1) / 6), 0.062f, 0.011f, st);
}

// A flattened scale-leaf branchlet: paired scales along an axis (Chamaecyparis, Thuja).
void scale_chain(leaf_canvas& c, vec2 a, vec2 b, float width) {
  const float len = glm::length(b - a);
  const vec2 dir = (b - a) / len;
  const float ang = degrees_of(dir), step = width * 0.75f;
  blade_style st;
  st.veins = 1, st.midrib = 0.6f, st.edge_dark = 0.4f;
  int k = 0;
  for (float s = 0; s < len; s += step, ++k) {
    const float side = (k % 2) ? 1.0f : -1.0f;
    const vec2 p = a + dir * s + vec2(-dir.y, dir.x) * (side * 0.2f * width);
    const float w = width * (1 - 0.35f * s / len);
    blade(c, p, ang + side * 22, 2.1f * w, 0.5f * w, [](float t, int) { return std::sin(pi * std::pow(t, 0.6f)); }, st);
  }
}

void draw_scale_spray(leaf_canvas& c, rng& g) {
  auto axis = [](float t) { return vec2(0.5f - 0.03f * std::sin(2.2f * t), 0.0f + 0.93f * t); };
  // A fan: alternate laterals off the main axis, each divided again into short branchlets.
  for (int i = 0; i < 10; ++i) {
    const float t = 0.1f + 0.088f * float(i);
    const vec2 p = axis(t);
    const float side = (i % 2) ? 1.0f : -1.0f;
    const vec2 d = heading(90 + side * g.range(38, 48));
    const float len = fit(p, d, 0.5f * (1 - 0.55f * t), 0.03f);
    const vec2 q = p + d * len;
    for (int j = 0; j < 7; ++j) {
      const float s = 0.14f + 0.12f * float(j);
      if (s * len < 0.02f) continue;
      const vec2 o = p + d * (s * len);
      const float sub_side = (j % 2) ? 1.0f : -1.0f;
      const vec2 e = heading(degrees_of(d) + sub_side * 40);
      scale_chain(c, o, o + e * fit(o, e, 0.12f * (1 - 0.5f * s), 0.02f), 0.022f);
    }
    scale_chain(c, p, q, 0.028f);
  }
  for (int i = 0; i < 8; ++i) scale_chain(c, axis(float(i) / 8), axis(float(i + 1) / 8), 0.032f);
}

void draw_palm_frond(leaf_canvas& c, rng& g) {
  // A pinnate frond: the rachis sweeps across the card, leaflets droop from both sides of it.
  const vec2 p0{0.5f, 0.0f}, p1{0.24f, 0.78f}, p2{0.93f, 0.9f};
  blade_style st;
  st.veins = 1, st.midrib = 1.2f, st.edge_dark = 0.3f;
  const int pairs = 30;
  for (int i = 0; i < pairs; ++i) {
    const float t = 0.08f + 0.9f * float(i) / float(pairs - 1);
    const vec2 p = bezier(p0, p1, p2, t);
    const vec2 tangent = glm::normalize(2 * (1 - t) * (p1 - p0) + 2 * t * (p2 - p1));
    const float along = degrees_of(tangent);
    const float env = 0.42f + 0.58f * std::sin(pi * std::min(1.0f, t * 1.05f));
    for (int side : {-1, 1}) {
      const float ang = along + float(side) * g.range(50, 60);
      const vec2 d = heading(ang);
      st.bend = -float(side) * 0.12f;   // droop back toward the rachis' tip
      const float len = fit(p, d, 0.34f * env * g.range(0.92f, 1.05f), 0.015f);
      blade(c, p, ang, len, 0.021f, [](float u, int) { return std::pow(std::sin(pi * std::pow(u, 0.55f)), 0.6f); }, st);
    }
  }
  curve_stroke(c, [&](float t) { return bezier(p0, p1, p2, t); }, 10, 0.011f, 0.0035f, {0.85f, 0.8f, 0.15f, 0.15f});
}

void draw_twig_cluster(leaf_canvas& c, rng& g) {
  auto twig = [](float t) { return vec2(0.5f + 0.04f * std::sin(2.4f * t), 0.62f * t); };
  blade_style st;
  st.serration = 0.08f, st.teeth = 14, st.vein_angle = 42, st.veins = 6;
  auto leaf = [](float t, int) { return ovate_profile(t); };
  const int leaves = 7;
  for (int i = 0; i < leaves; ++i) {
    const float t = 0.22f + 0.74f * float(i) / float(leaves - 1);
    const vec2 p = twig(t);
    const float side = (i % 2) ? 1.0f : -1.0f;
    const float ang = 90 + side * g.range(48, 64) * (1.1f - 0.3f * t);
    const vec2 d = heading(ang);
    const vec2 q = p + d * 0.035f;
    stroke(c, p, q, 0.0035f, 0.003f, petiole_style);
    const float len = fit(q, d, g.range(0.27f, 0.32f), 0.01f);
    blade(c, q - d * 0.005f, ang, len, len * 0.42f, leaf, st);
  }
  curve_stroke(c, twig, 6, 0.011f, 0.0055f, twig_style);
  const vec2 tip = twig(1.0f);
  stroke(c, tip, tip + vec2(0, 0.03f), 0.0035f, 0.003f, petiole_style);
  blade(c, tip + vec2(0, 0.025f), 90, fit(tip, {0, 1}, 0.32f) - 0.02f, 0.13f, leaf, st);
}

struct leaf_look {
  vec3 blade, vein;  // sRGB bytes
};
// Near a mid green (the tint sets the hue); each archetype keeps a little of its own character.
// A pale, low-chroma mid green (linear ~0.45), so that the tint sets the hue and the leaf's albedo
// is a little under half the tint; each archetype keeps a little character of its own.
const leaf_look leaf_looks[leaf_archetype_count] = {
    {{178, 194, 156}, {206, 208, 160}},  // ovate: fresh, slightly yellow
    {{170, 188, 156}, {196, 202, 156}},  // lobed: deeper
    {{178, 194, 152}, {210, 208, 152}},  // palmate
    {{174, 192, 158}, {202, 206, 162}},  // pinnate
    {{164, 186, 172}, {190, 202, 176}},  // needles: blue-green
    {{162, 184, 166}, {188, 200, 172}},  // flat spray: bluish
    {{176, 190, 152}, {198, 202, 152}},  // scale spray: yellow-green
    {{182, 194, 150}, {212, 208, 150}},  // palm frond: yellowish
    {{178, 194, 156}, {206, 208, 160}},  // twig cluster
};

leaf_texture_set finish_leaf(const leaf_canvas& c, std::vector<float>& h, const leaf_look& look, uint64_t seed) {
  const int n = c.n;
  const size_t count = size_t(n) * n;
  const vec3 base = srgb_color(int(look.blade.x), int(look.blade.y), int(look.blade.z));
  const vec3 vein = srgb_color(int(look.vein.x), int(look.vein.y), int(look.vein.z));
  const lattice blotch(7, 7, seed * 3 + 1), hue(5, 5, seed * 3 + 2);
  leaf_texture_set out;
  out.color = image{n, n, 4, std::vector<uint8_t>(count * 4)};
  out.thickness = image{n, n, 3, std::vector<uint8_t>(count * 3)};
  h.resize(count);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const size_t k = size_t(y) * n + x;
      const float u = (float(x) + 0.5f) * c.px, v = (float(y) + 0.5f) * c.px;
      uint8_t* p = &out.color.pixels[k * 4];
      h[k] = c.height[k] * float(n) * 1.6f;  // card units -> texel units, with some emphasis
      if (c.alpha[k] <= 0) {  // outside: the blade's own colour, so filtering adds no dark fringe
        p[0] = linear_byte(base.x), p[1] = linear_byte(base.y), p[2] = linear_byte(base.z), p[3] = 0;
        std::fill_n(&out.thickness.pixels[k * 3], 3, uint8_t(230));
        continue;
      }
      // Per-texel variation: broad blotches of value and hue, and a fine grain.
      const float grain = unit(seed * 0x9E3779B1ull + k) - 0.5f;
      const float w = clamp01(c.warm[k] + 0.35f * (hue(u, v) - 0.5f));
      const float value = c.shade[k] * (1 + 0.16f * (blotch(u, v) - 0.5f) + 0.05f * grain);
      const vec3 col = (base + (vein - base) * w) * value;
      p[0] = linear_byte(col.x), p[1] = linear_byte(col.y), p[2] = linear_byte(col.z);
      p[3] = unit_byte(c.alpha[k]);
      std::fill_n(&out.thickness.pixels[k * 3], 3, unit_byte(c.thin[k]));
    }
  out.normal = normal_from_height(h, n, false, &c.alpha);
  return out;
}

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

vec3 mix3(vec3 a, vec3 b, float t) { return a + (b - a) * t; }

// Periodic jittered-grid cellular noise (Worley 1996): distances to the nearest two feature points
// and the nearest one's cell id, on a cx * cy grid. Distances are measured in cell units (a cell is
// a unit square, so the 3 x 3 neighbourhood holds the nearest points): cells taller than wide make
// plates longer along the trunk.
struct cells {
  int cx, cy;
  std::vector<vec2> points;  // inside each cell, 0..1
  cells(int cx_, int cy_, uint64_t seed, float jitter) : cx(cx_), cy(cy_), points(size_t(cx_) * size_t(cy_)) {
    for (size_t i = 0; i < points.size(); ++i)
      points[i] = vec2(0.5f + jitter * (unit(seed * 77 + 2 * i) - 0.5f), 0.5f + jitter * (unit(seed * 77 + 2 * i + 1) - 0.5f));
  }
  // edge: distance to the bisector of the two nearest points, (F2^2 - F1^2) / (2 |p2 - p1|), which
  // (unlike F2 - F1) stays narrow where two points lie close together; id: the nearest's cell.
  void query(float u, float v, float& edge, int& id) const {
    const float fx = u * float(cx), fy = v * float(cy);
    const int ix = int(ffloor(fx)), iy = int(ffloor(fy));
    float f1 = 1e9f, f2 = 1e9f;
    vec2 p1(0), p2(0);
    id = 0;
    for (int j = -1; j <= 1; ++j)
      for (int i = -1; i <= 1; ++i) {
        const int wx = wrap(ix + i, cx), wy = wrap(iy + j, cy);
        const vec2 p = points[size_t(wy) * cx + wx];
        const vec2 d(float(ix + i) + p.x - fx, float(iy + j) + p.y - fy);
        const float dd = glm::dot(d, d);
        if (dd < f1) f2 = f1, p2 = p1, f1 = dd, p1 = d, id = wy * cx + wx;
        else if (dd < f2) f2 = dd, p2 = d;
      }
    edge = (f2 - f1) / (2 * std::max(glm::length(p2 - p1), 1e-6f));
  }
};

// Lengthwise lines that wander: line i of `count` sits at (i + 0.5 + offset_i(v)) / count, with
// offset_i = swing * (noise - 0.5), so neighbours approach, touch and part again. The offsets depend
// on the row only, so they are computed once per row.
struct wandering_lines {
  int count;
  float swing;
  lattice slow, fast;
  std::vector<float> offset;  // this row's
  wandering_lines(int count_, float swing_, int cells_along, uint64_t seed)
      : count(count_), swing(swing_), slow(count_, cells_along, seed), fast(count_, 40, seed + 1), offset(size_t(count_)) {}
  void row(float v) {
    for (int i = 0; i < count; ++i) {
      const float at = (float(i) + 0.5f) / float(count);
      offset[size_t(i)] = swing * (0.86f * slow(at, v) + 0.14f * fast(at, v) - 0.5f);
    }
  }
  float distance(float u) const {  // to the nearest line, in line spacings
    const float fu = u * float(count);
    const int i0 = int(ffloor(fu));
    float best = 1e9f;
    for (int i = i0 - 2; i <= i0 + 2; ++i) best = std::min(best, std::abs(fu - (float(i) + 0.5f + offset[size_t(wrap(i, count))])));
    return best;
  }
};

void bark_furrowed(bark_field& f, uint64_t seed) {
  // Quercus: corky ridges between deep furrows that run along the trunk and wander, so that
  // neighbouring furrows meet and part (they interlace); shallower furrows split the wide ridges,
  // a few cross cracks break them into long blocks, and fine fibres run along them.
  wandering_lines deep(9, 2.2f, 8, seed + 1), shallow(17, 1.6f, 10, seed + 3);
  const lattice fibre(72, 6, seed + 4), tone(6, 4, seed + 5), lump(20, 8, seed + 6);
  const cells blocks(12, 12, seed + 7, 0.9f);
  const vec3 ridge_col = srgb_color(230, 222, 206), furrow_col = srgb_color(66, 54, 44), warm_col = srgb_color(206, 182, 154);
  const int n = f.n;
  for (int y = 0; y < n; ++y) {
    const float v = (float(y) + 0.5f) / float(n);
    deep.row(v), shallow.row(v);
    for (int x = 0; x < n; ++x) {
      const float u = (float(x) + 0.5f) / float(n);
      float edge;
      int bid;
      blocks.query(u, v, edge, bid);
      const float ridge = smooth(0.02f, 0.24f, deep.distance(u));        // 0 at the bottom of a deep furrow
      const float split = 1 - smooth(0.02f, 0.2f, shallow.distance(u));  // a shallow furrow
      const float crack = (1 - smooth(0.0f, 0.02f, edge)) * 0.35f;       // cross cracks
      const float fb = fibre(u, v), lm = lump(u, v);
      const float top_h = 1 - 0.35f * split - 0.25f * crack;
      const size_t k = size_t(y) * n + x;
      f.height[k] = 0.85f * std::sqrt(ridge) * top_h + 0.1f * fb + 0.08f * lm;
      const vec3 top = mix3(ridge_col, warm_col, tone(u, v)) * (0.85f + 0.2f * lm);
      f.paint(k, mix3(furrow_col, top, ridge * (1 - 0.45f * split) * (1 - 0.4f * crack)) * (0.88f + 0.22f * fb), 0.97f - 0.1f * ridge);
    }
  }
}

void bark_plated(bark_field& f, uint64_t seed) {
  // Pinus: irregular flat plates, longer along the trunk than across, separated by dark fissures;
  // plates reddish with flaky layers; a finer cell pattern breaks the plates up.
  const cells plates(5, 3, seed + 1, 0.9f), flakes(14, 10, seed + 2, 0.9f);
  const lattice warp(7, 6, seed + 3), jag(40, 30, seed + 6), layer(22, 12, seed + 4), grain(96, 24, seed + 5);
  const vec3 red = srgb_color(238, 164, 126), grey = srgb_color(206, 184, 166), fissure = srgb_color(52, 40, 32);
  const int n = f.n;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const float u = (float(x) + 0.5f) / float(n), v = (float(y) + 0.5f) / float(n);
      // A broad warp bends the plates' outlines, a fine one makes their edges ragged.
      const float wu = u + 0.035f * (warp(u, v) - 0.5f) + 0.008f * (jag(u, v) - 0.5f);
      const float wv = v + 0.035f * (warp(v, u) - 0.5f) + 0.008f * (jag(v, u) - 0.5f);
      float e1, e2;
      int id, fid;
      plates.query(wu, wv, e1, id);
      flakes.query(wu, wv, e2, fid);
      const float gap = smooth(0.018f, 0.06f, e1);       // 0 in a fissure
      const float fine = smooth(0.0f, 0.03f, e2);
      const float level = unit(seed * 131 + uint64_t(id)), flevel = unit(seed * 171 + uint64_t(fid));
      const float lay = layer(wu, wv);
      const size_t k = size_t(y) * n + x;
      f.height[k] = gap * (0.55f + 0.2f * level + 0.12f * flevel * fine + 0.1f * lay) - 0.08f * (1 - fine);
      vec3 plate = mix3(red, grey, 0.8f * level * level) * (0.8f + 0.3f * lay) * (0.93f + 0.07f * fine);
      plate *= 0.92f + 0.16f * grain(wu, wv);
      f.paint(k, mix3(fissure, plate, gap), 0.95f - 0.12f * gap);
    }
}

void bark_smooth(bark_field& f, uint64_t seed) {
  // Betula / Fagus: light, smooth bark; horizontal lenticels (short dark dashes across the
  // trunk), dark patches and faint horizontal banding. Light and neutral: the tint decides.
  const lattice patch(5, 4, seed + 1), patch2(11, 8, seed + 2), band(3, 40, seed + 3), fine(80, 80, seed + 4);
  const int cx = 7, cy = 26;
  struct dash { float x, y, inv_half, inv_thick; };  // in cells
  std::vector<dash> dashes(size_t(cx) * cy);
  for (size_t c = 0; c < dashes.size(); ++c) {
    const uint64_t cell = seed * 1000003ull + c;
    if (unit(cell * 5) < 0.15f) continue;  // some cells are empty
    dashes[c] = {unit(cell * 5 + 1), unit(cell * 5 + 2), 1 / (0.1f + 0.3f * unit(cell * 5 + 3)), 1 / (0.05f + 0.05f * unit(cell * 5 + 4))};
  }
  const vec3 light = srgb_color(240, 239, 236), dark = srgb_color(78, 74, 70);
  const int n = f.n;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const float u = (float(x) + 0.5f) / float(n), v = (float(y) + 0.5f) / float(n);
      // Lenticels: one dash per cell of a jittered grid, checking the neighbouring cells too.
      const float fx = u * cx, fy = v * cy;
      const int ix = int(ffloor(fx)), iy = int(ffloor(fy));
      float lent = 0;
      for (int j = -1; j <= 1; ++j)
        for (int i = -1; i <= 1; ++i) {
          const dash& d = dashes[size_t(wrap(iy + j, cy)) * cx + size_t(wrap(ix + i, cx))];
          if (d.inv_half == 0) continue;
          const float dx = (fx - float(ix + i) - d.x) * d.inv_half, dy = (fy - float(iy + j) - d.y) * d.inv_thick;
          lent = std::max(lent, 1 - smooth(0.55f, 1.0f, dx * dx + dy * dy));
        }
      const float p = 0.7f * patch(u, v) + 0.3f * patch2(u, v);
      const float spot = smooth(0.6f, 0.68f, p);
      const float b = band(u, v), fn = fine(u, v);
      const size_t k = size_t(y) * n + x;
      f.height[k] = -0.5f * lent + 0.1f * b + 0.06f * fn - 0.08f * spot;
      vec3 c = light * (0.93f + 0.1f * b + 0.05f * fn);
      c = mix3(c, dark * (0.9f + 0.2f * fn), 0.8f * spot);
      c = mix3(c, dark * 0.7f, 0.85f * lent);
      f.paint(k, c, 0.5f + 0.3f * spot + 0.35f * lent);
    }
}

void bark_peeling(bark_field& f, uint64_t seed) {
  // Thuja / Sequoia: long fibrous strips that separate and peel; each strip breaks along the
  // trunk into pieces of its own tone, reddish fresh bark and greyed weathered strips.
  const int strips = 16;
  const lattice warp(3, 2, seed + 1), warp2(7, 3, seed + 2), fibre(110, 5, seed + 3), tone(4, 4, seed + 4);
  const vec3 fresh = srgb_color(228, 158, 124), weathered = srgb_color(204, 194, 182), gap_col = srgb_color(64, 46, 36);
  const int n = f.n;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const float u = (float(x) + 0.5f) / float(n), v = (float(y) + 0.5f) / float(n);
      const float s = (u + 0.08f * (warp(u, v) - 0.5f) + 0.03f * (warp2(u, v) - 0.5f)) * float(strips);
      const int id = wrap(int(ffloor(s)), strips);
      const float w = s - ffloor(s);
      const uint64_t sid = seed * 7919 + uint64_t(id);
      const float pieces = 1 + ffloor(3 * unit(sid * 3));
      const float pv = v + unit(sid * 3 + 1);
      const int piece = int(ffloor((pv - ffloor(pv)) * pieces));
      const float lift = unit(sid * 31 + uint64_t(piece));
      const float profile = std::sqrt(std::max(0.0f, std::sin(pi * w)));
      const float gap = smooth(0.0f, 0.12f, std::min(w, 1 - w));
      const float fb = fibre(u + 0.08f * (warp(u, v) - 0.5f), v);
      const size_t k = size_t(y) * n + x;
      f.height[k] = profile * (0.5f + 0.35f * lift) + 0.25f * fb;
      const vec3 c = mix3(fresh, weathered, smooth(0.35f, 0.85f, 0.6f * lift + 0.4f * tone(u, v)));
      f.paint(k, mix3(gap_col, c * (0.78f + 0.35f * fb), gap), 0.92f - 0.05f * fb);
    }
}

void bark_ringed(bark_field& f, uint64_t seed) {
  // Palm stem: rings of leaf-base scars. Each ring holds a few leaf bases side by side; each base
  // left a raised band whose lower edge sags in a crescent, with a dark scar line along it and a
  // notch where one base meets the next. Between the rings the stem is fibrous and greyer.
  const int rings = 6, bases = 3;
  const lattice wave(3, 3, seed + 1), fibre(90, 6, seed + 2), tone(4, 6, seed + 3);
  const vec3 body = srgb_color(200, 190, 168), band_col = srgb_color(238, 230, 212), scar = srgb_color(70, 58, 46);
  const int n = f.n;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const float u = (float(x) + 0.5f) / float(n), v = (float(y) + 0.5f) / float(n);
      const float r = v * float(rings) + 0.25f * (wave(u, v) - 0.5f);
      const float rf = ffloor(r), l = r - rf;  // l: 0..1 down the ring interval
      const int ring = wrap(int(rf), rings);
      const float a = u * float(bases) + unit(seed * 97 + uint64_t(ring));
      const float along = a - ffloor(a);  // 0..1 across one leaf base
      const float sag = 0.2f + 0.16f * std::sin(pi * along);
      const float band = smooth(0.0f, 0.05f, l) * (1 - smooth(sag - 0.03f, sag, l));
      const float scar_line = 1 - smooth(0.012f, 0.04f, std::abs(l - sag - 0.01f));
      const float notch = (1 - smooth(0.0f, 0.035f, std::min(along, 1 - along))) * (l < sag + 0.02f ? 1.0f : 0.0f);
      const float bulge = std::sin(pi * l);
      const float fb = fibre(u, v);
      const size_t k = size_t(y) * n + x;
      f.height[k] = 0.3f * bulge + 0.45f * band * (1 - 0.5f * l / std::max(sag, 1e-3f)) - 0.45f * scar_line - 0.3f * notch +
                    0.15f * fb * (1 - band);
      vec3 c = mix3(body * (0.78f + 0.35f * fb), band_col * (0.95f + 0.08f * fb), band) * (0.9f + 0.2f * tone(u, v));
      c = mix3(c, scar, std::max(0.9f * scar_line, 0.8f * notch));
      f.paint(k, c, 0.88f + 0.1f * scar_line - 0.1f * band);
    }
}

bark_texture_set finish_bark(bark_field& f, float relief) {
  // relief: height units per tile width; scaled to per-texel slope for the normal map.
  const float scale = relief * float(f.n) / 512.0f;
  for (float& h : f.height) h *= scale;
  f.out.normal = normal_from_height(f.height, f.n, true, nullptr);
  return std::move(f.out);
}

int clamp_size(int size) { return std::clamp(size, 8, 4096); }

template <class Set>
struct cache_entry {
  std::once_flag once;
  Set set;
};
using cache_key = std::tuple<int, int, uint64_t>;

// The first caller of a key makes the set, callers of the same key wait for it, and different keys
// are made in parallel.
template <class Set, class Make>
const Set& cached(std::map<cache_key, std::unique_ptr<cache_entry<Set>>>& cache, std::mutex& mu, cache_key key, Make&& make) {
  cache_entry<Set>* e;
  {
    std::lock_guard lock(mu);
    auto& slot = cache[key];
    if (!slot) slot = std::make_unique<cache_entry<Set>>();
    e = slot.get();
  }
  std::call_once(e->once, [&] { e->set = make(); });
  return e->set;
}

}  // namespace

leaf_texture_set make_leaf_archetype_textures(leaf_archetype a, int size, uint64_t seed) {
  const int n = clamp_size(size);
  const int i = std::clamp(int(a), 0, leaf_archetype_count - 1);
  scratch_lease lease;
  leaf_canvas c(n, lease);
  rng g{mix64(seed * 1315423911ull + uint64_t(i))};
  using draw_fn = void (*)(leaf_canvas&, rng&);
  static const draw_fn draw[leaf_archetype_count] = {draw_ovate,      draw_lobed,       draw_palmate,
                                                      draw_pinnate,    draw_needles,     draw_flat_spray,
                                                      draw_scale_spray, draw_palm_frond, draw_twig_cluster};
  draw[i](c, g);
  return finish_leaf(c, lease[5], leaf_looks[i], mix64(seed + uint64_t(i) * 101));
}

bark_texture_set make_bark_archetype_textures(bark_archetype a, int size, uint64_t seed) {
  const int n = clamp_size(size);
  const int i = std::clamp(int(a), 0, bark_archetype_count - 1);
  scratch_lease lease;
  bark_field f(n, lease);
  const uint64_t s = mix64(seed * 2654435761ull + uint64_t(i));
  using fill_fn = void (*)(bark_field&, uint64_t);
  static const fill_fn fill[bark_archetype_count] = {bark_furrowed, bark_plated, bark_smooth, bark_peeling, bark_ringed};
  static const float relief[bark_archetype_count] = {14, 10, 4, 9, 8};
  fill[i](f, s);
  return finish_bark(f, relief[i]);
}

const leaf_texture_set& leaf_archetype_textures(leaf_archetype a, int size, uint64_t seed) {
  static std::mutex mu;
  static std::map<cache_key, std::unique_ptr<cache_entry<leaf_texture_set>>> cache;
  return cached(cache, mu, {int(a), clamp_size(size), seed}, [&] { return make_leaf_archetype_textures(a, size, seed); });
}

const bark_texture_set& bark_archetype_textures(bark_archetype a, int size, uint64_t seed) {
  static std::mutex mu;
  static std::map<cache_key, std::unique_ptr<cache_entry<bark_texture_set>>> cache;
  return cached(cache, mu, {int(a), clamp_size(size), seed}, [&] { return make_bark_archetype_textures(a, size, seed); });
}

namespace {
// Runs job(0 .. jobs-1) on `threads` threads taking jobs in order from a shared counter.
template <class Job>
void run_jobs(int jobs, int threads, Job&& job) {
  std::atomic<int> next{0};
  auto worker = [&] {
    for (int j; (j = next.fetch_add(1)) < jobs;) job(j);
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < std::max(threads, 1); ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
}
// The costliest first, so two threads finish close together.
constexpr int job_order[leaf_archetype_count + bark_archetype_count] = {9, 10, 11, 12, 13, 4, 6, 5, 7, 8, 0, 1, 2, 3};
}  // namespace

void prepare_archetype_textures(int size, uint64_t seed, int threads) {
  run_jobs(leaf_archetype_count + bark_archetype_count, threads, [&](int j) {
    const int k = job_order[j];
    if (k < leaf_archetype_count) leaf_archetype_textures(leaf_archetype(k), size, seed);
    else bark_archetype_textures(bark_archetype(k - leaf_archetype_count), size, seed);
  });
}

size_t make_all_archetype_textures(int size, uint64_t seed, int threads) {
  std::atomic<size_t> bytes{0};
  run_jobs(leaf_archetype_count + bark_archetype_count, threads, [&](int j) {
    const int k = job_order[j];
    if (k < leaf_archetype_count) {
      const leaf_texture_set s = make_leaf_archetype_textures(leaf_archetype(k), size, seed);
      bytes += s.color.pixels.size() + s.normal.pixels.size() + s.thickness.pixels.size();
    } else {
      const bark_texture_set s = make_bark_archetype_textures(bark_archetype(k - leaf_archetype_count), size, seed);
      bytes += s.color.pixels.size() + s.normal.pixels.size() + s.roughness.pixels.size();
    }
  });
  return bytes;
}

// albedo = min(1, texture_tint_gain * tint * linear(texel)), written back as sRGB bytes (textures.h).
image tinted_texture(const image& color, const glm::vec3& tint) {
  image out = color;
  const auto& lin = srgb().to_linear;
  const size_t count = size_t(out.width) * size_t(out.height), ch = size_t(std::max(out.channels, 1));
  if (out.pixels.size() < count * ch || ch < 3) return out;
  const float gain[3] = {texture_tint_gain * std::max(tint.x, 0.0f), texture_tint_gain * std::max(tint.y, 0.0f),
                         texture_tint_gain * std::max(tint.z, 0.0f)};
  for (size_t k = 0; k < count; ++k)
    for (size_t c = 0; c < 3; ++c) {
      uint8_t& v = out.pixels[k * ch + c];
      v = linear_byte(gain[c] * lin[v]);
    }
  return out;
}

}  // namespace sylva
