// The archetype textures' shared primitives (render/assets/archetype_canvas.h): sRGB tables, normal maps
// from height fields, the stroke primitive and the last steps that turn a canvas or a bark field
// into a texture set.
#include <algorithm>
#include <cmath>

#include "render/assets/archetype_canvas.h"

namespace sylva::archetype {

srgb_tables::srgb_tables() {
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
const srgb_tables& srgb() {
  static const srgb_tables t;
  return t;
}
const uint8_t* const linear_to_byte = srgb().to_srgb;
vec3 srgb_color(int r, int g, int b) {
  const auto& t = srgb().to_linear;
  return {t[r], t[g], t[b]};
}

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

bark_texture_set finish_bark(bark_field& f, float relief) {
  // relief: height units per tile width; scaled to per-texel slope for the normal map.
  const float scale = relief * float(f.n) / 512.0f;
  for (float& h : f.height) h *= scale;
  f.out.normal = normal_from_height(f.height, f.n, true, nullptr);
  return std::move(f.out);
}

}  // namespace sylva::archetype
