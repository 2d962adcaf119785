// Conifer foliage cards: pine needle fascicles, flat needle sprays (spruce, fir) and
// scale-leaf sprays (cypress, thuja) and the needle rosettes of true cedars (Cedrus), drawn with the strokes and blades of render/assets/archetype_canvas.h.
#include <algorithm>
#include <cmath>

#include "render/assets/archetype_canvas.h"

namespace sylva::archetype {

// Sizes below are in card units; the presets give the card side (leaf_size), so a needle's real
// length and width follow: e.g. a 0.2 m pine card makes 0.26 card = 5 cm needles, 1.5 mm wide.

void draw_needles(leaf_canvas& c, rng& g) {
  // Pinus sylvestris shoot tip, drawn so the pairs read at 1-3 m (round 19's reader saw the old
  // card's 56 tight pairs as "dense fir-like brush shoots, not needles in paired bundles"): the
  // twig's older lower part is bare but for the brown scale leaves (the needles of a Scots pine
  // live 2-4 years, so they crowd the last shoots); above them 22 fascicles, each two stiff,
  // slightly twisted needles of 4-7 cm from one short sheath, parted 20-40 degrees into a V
  // (paired, twisted and spreading: Mitchell 1974); the youngest, shorter ones stand
  // forward round the terminal bud cluster, a brush only at the very tip.
  auto twig = [](float t) { return vec2(0.5f + 0.012f * std::sin(3.0f * t), 0.62f * t); };
  stroke_style needle{0.92f, 0.0f, 0.3f, 0.14f};
  const stroke_style sheath{0.4f, 1.0f, 0.05f, 0};
  for (int i = 0; i < 7; ++i) {  // scale leaves on the bare part
    const float t = 0.03f + 0.045f * float(i);
    const vec2 p = twig(t);
    const float side = (i % 2) ? 1.0f : -1.0f;
    stroke(c, p, p + heading(90 + side * 55) * 0.012f, 0.0038f, 0.0012f, sheath);
  }
  const int fascicles = 22;
  for (int i = 0; i < fascicles; ++i) {
    const float t = 0.3f + 0.68f * float(i) / float(fascicles - 1);
    const vec2 p = twig(t);
    // The spiral seen from the side: the fascicle's azimuth sets how far it leans out of the twig.
    const float lean = std::sin(2.39996f * float(i));  // golden angle
    const float spread = (58 - 30 * t) * (0.45f + 0.55f * std::abs(lean)) + g.range(-5, 5);
    const float ang = 90 + (lean < 0 ? -spread : spread);
    const float part = g.range(12, 20) * (0.55f + 0.45f * std::abs(lean));  // half the V's opening
    const vec2 base = p + heading(ang) * 0.012f;
    stroke(c, p, base, 0.0046f, 0.0036f, sheath);
    for (int k = 0; k < 2; ++k) {
      // A twisted needle: its course turns a little along its length (drawn as a gentle arc).
      const float a0 = ang + (k ? 1.0f : -1.0f) * part;
      const float len = g.range(0.25f, 0.33f) * (1 - 0.3f * t);
      const float turn = g.range(-9, 9);
      needle.shade = g.range(0.8f, 1.0f);
      const vec2 m = base + heading(a0) * (0.5f * len);
      const vec2 d2 = heading(a0 + turn);
      const vec2 e = m + d2 * fit(m, d2, 0.5f * len);
      stroke(c, base, m, 0.0062f, 0.0052f, needle);
      stroke(c, m, e, 0.0052f, 0.0011f, needle);
    }
  }
  curve_stroke(c, twig, 5, 0.0095f, 0.0065f, twig_style);
  // The bud cluster: a terminal bud and its ring of lateral buds, with the youngest needles.
  const vec2 tip = twig(1.0f);
  for (int k = 0; k < 8; ++k) {
    const float a = 90 + g.range(-30, 30);
    const vec2 d = heading(a);
    stroke(c, tip, tip + d * fit(tip, d, g.range(0.13f, 0.2f)), 0.005f, 0.001f, needle);
  }
  for (int k = -1; k <= 1; ++k) {
    const vec2 d = heading(90 + 28.0f * float(k));
    stroke(c, tip, tip + d * (k ? 0.026f : 0.036f), 0.0075f, 0.003f, sheath);
  }
}

// Needles on both sides of an axis, pointing forward (Abies, Picea shoots), fine enough at the
// card's size to leave sky between them.
void needle_comb(leaf_canvas& c, rng& g, vec2 a, vec2 b, float needle_len, float spacing, const stroke_style& st) {
  const float len = glm::length(b - a);
  const vec2 dir = (b - a) / len;
  const float ang = degrees_of(dir);
  for (float s = 0.008f; s < len; s += spacing * g.range(0.85f, 1.15f))
    for (int side : {-1, 1}) {
      const vec2 p = a + dir * s;
      const float taper = 0.55f + 0.45f * std::min(1.0f, (len - s) / 0.07f);
      const vec2 d = heading(ang + float(side) * g.range(50, 72));
      stroke(c, p, p + d * fit(p, d, needle_len * taper * g.range(0.85f, 1.1f)), 0.0034f, 0.001f, st);
    }
  stroke(c, a, b, 0.0038f, 0.0026f, twig_style);
}

void draw_flat_spray(leaf_canvas& c, rng& g) {
  const stroke_style st{0.95f, 0.05f, 0.35f, 0.1f};
  auto axis = [](float t) { return vec2(0.5f + 0.02f * std::sin(2 * t), 0.95f * t); };
  // Alternate side shoots, longer below: the spray narrows to the leading shoot's tip.
  for (int i = 0; i < 7; ++i) {
    const float t = 0.1f + 0.115f * float(i);
    const vec2 p = axis(t);
    const float side = (i % 2) ? 1.0f : -1.0f;
    const vec2 d = heading(90 + side * g.range(46, 56));
    const float len = fit(p, d, 0.44f * (1 - 0.6f * t), 0.07f);
    needle_comb(c, g, p, p + d * len, 0.07f, 0.0105f, st);
  }
  for (int i = 0; i < 6; ++i) needle_comb(c, g, axis(float(i) / 6), axis(float(i + 1) / 6), 0.074f, 0.0105f, st);
}

void draw_needle_tufts(leaf_canvas& c, rng& g) {
  // Cedrus: a long shoot with a few single needles, and short spur shoots along it and its two
  // side shoots, each ending in a rosette of 20-30 short stiff needles that radiate forward.
  const stroke_style needle{0.95f, 0.0f, 0.3f, 0.14f};
  auto rosette = [&](vec2 p, float toward) {
    const int count = 26 + int(g.range(0, 10));
    for (int k = 0; k < count; ++k) {
      const float a = toward + g.range(-110, 110);
      const vec2 d = heading(a);
      stroke(c, p, p + d * fit(p, d, g.range(0.055f, 0.09f)), 0.0052f, 0.0014f, needle);
    }
    stroke(c, p - heading(toward) * 0.012f, p, 0.006f, 0.0055f, twig_style);  // the spur
  };
  auto shoot = [&](vec2 a, vec2 b, float spurs_every) {
    const float len = glm::length(b - a);
    const vec2 dir = (b - a) / len;
    const float ang = degrees_of(dir);
    int k = 0;
    for (float s = 0.03f; s < len - 0.02f; s += spurs_every * g.range(0.8f, 1.2f), ++k) {
      const float side = (k % 2) ? 1.0f : -1.0f;
      const vec2 p = a + dir * s + heading(ang + side * 90) * 0.016f;
      rosette(p, ang + side * g.range(25, 45));
    }
    stroke(c, a, b, 0.0055f, 0.0035f, twig_style);
    for (int k2 = 0; k2 < 10; ++k2) {  // the long shoot's own scattered single needles
      const vec2 p = a + dir * (len * (0.55f + 0.045f * float(k2)));
      const vec2 d = heading(ang + (k2 % 2 ? 1.0f : -1.0f) * g.range(35, 60));
      stroke(c, p, p + d * fit(p, d, g.range(0.04f, 0.06f)), 0.0024f, 0.0008f, needle);
    }
  };
  const vec2 base{0.5f, 0.0f}, top{0.52f, 0.92f};
  shoot(base, top, 0.085f);
  shoot(base + (top - base) * 0.3f, {0.16f, 0.62f}, 0.09f);
  shoot(base + (top - base) * 0.45f, {0.86f, 0.78f}, 0.09f);
}

// A flattened scale-leaf branchlet: paired scales along an axis (Chamaecyparis, Thuja).
void scale_chain(leaf_canvas& c, vec2 a, vec2 b, float width) {
  const float len = glm::length(b - a);
  const vec2 dir = (b - a) / len;
  // Scale leaves lie pressed to the shoot, each overlapping the next (Cupressus sempervirens: scales
  // 0.5-1 mm, closely appressed, in four ranks), so a branchlet reads as a scalloped green cord.
  // Round 22-23's readers saw the old chain, scales 2.1 widths long splayed 22 degrees out, as
  // "small broad leaves, not scale-leaf sprays": they are now short, splayed 9 degrees and overlap.
  const float ang = degrees_of(dir), step = width * 0.5f;
  blade_style st;
  st.veins = 1, st.midrib = 0.3f, st.edge_dark = 0.45f;
  int k = 0;
  for (float s = 0; s < len; s += step, ++k) {
    const float side = (k % 2) ? 1.0f : -1.0f;
    const vec2 p = a + dir * s + vec2(-dir.y, dir.x) * (side * 0.12f * width);
    const float w = width * (1 - 0.35f * s / len);
    blade(c, p, ang + side * 9, 1.35f * w, 0.5f * w, [](float t, int) { return std::sin(pi * std::pow(t, 0.45f)); }, st);
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
      scale_chain(c, o, o + e * fit(o, e, 0.12f * (1 - 0.5f * s), 0.02f), 0.03f);
    }
    scale_chain(c, p, q, 0.036f);
  }
  for (int i = 0; i < 8; ++i) scale_chain(c, axis(float(i) / 8), axis(float(i + 1) / 8), 0.04f);
}

}  // namespace sylva::archetype
