// Conifer foliage cards (issue 11): pine needle fascicles, flat needle sprays (spruce, fir) and
// scale-leaf sprays (cypress, cedar), drawn with the strokes and blades of render/archetype_canvas.h.
#include <algorithm>
#include <cmath>

#include "render/archetype_canvas.h"

namespace sylva::archetype {

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

}  // namespace sylva::archetype
