// Broadleaf cards and the palm frond: blades and strokes on the leaf canvas
// (render/assets/archetype_canvas.h). Each card: petiole at the bottom edge's centre, blade up the image.
#include <algorithm>
#include <cmath>
#include <vector>

#include "render/assets/archetype_canvas.h"

namespace sylva::archetype {

void draw_ovate(leaf_canvas& c, rng&) {
  stroke(c, {0.5f, 0.0f}, {0.5f, 0.15f}, 0.0065f, 0.0055f, petiole_style);
  blade_style st;
  st.serration = 0.07f, st.teeth = 26, st.vein_angle = 40, st.veins = 9;
  blade(c, {0.5f, 0.13f}, 90, 0.84f, 0.35f, [](float t, int) { return ovate_profile(t); }, st);
}

// Silver birch (Betula pendula): a triangular-ovate blade, broadest about a quarter of the way up
// over a broad, nearly truncate base, straight sides to a long-pointed tip, and doubly serrate: a
// larger tooth every few small ones; a slender petiole a third of the blade's length.
void draw_birch(leaf_canvas& c, rng&) {
  stroke(c, {0.5f, 0.0f}, {0.5f, 0.24f}, 0.005f, 0.0045f, petiole_style);
  blade_style st;
  st.serration = 0.05f, st.teeth = 34, st.vein_angle = 42, st.veins = 7;
  blade(c, {0.5f, 0.22f}, 90, 0.76f, 0.38f, [](float t, int) {
    const float base = std::min(1.0f, std::sqrt(t / 0.2f));
    const float taper = t < 0.26f ? 1.0f : std::pow((1 - t) / 0.74f, 1.15f);
    const float saw = t * 8.5f - std::floor(t * 8.5f);   // the larger teeth of the double serration
    return base * taper * (1 - 0.1f * (1 - saw));
  }, st);
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

// One Norway maple blade (Acer platanoides: five pointed lobes with a few large teeth, palmate
// venation from the petiole's tip at centre); turn rotates it (0 = pointing up the card), size
// scales it (1 = the palmate card's leaf).
static void palmate_blade(leaf_canvas& c, vec2 centre, float turn, float size) {
  blade_style st;
  st.vein_angle = 50, st.veins = 6, st.serration = 0.0f, st.edge_dark = 0, st.midrib = 0, st.dome = 0;
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
    const float a = angles[k] + turn;
    blade(c, centre, a, fit(centre, heading(a), lengths[k] * size), widths[k] * size, lobe, st);
  }
  // The main veins all leave the petiole's tip, drawn over the joined lobes.
  const stroke_style vein{1.08f, 0.9f, 0.35f, 0};
  for (int k = 0; k < 5; ++k) {
    const float a = angles[k] + turn;
    stroke(c, centre, centre + heading(a) * (0.85f * fit(centre, heading(a), lengths[k] * size)), 0.0032f * std::sqrt(size),
           0.001f, vein);
  }
}

void draw_palmate(leaf_canvas& c, rng&) {
  const vec2 centre{0.5f, 0.31f};
  stroke(c, {0.5f, 0.0f}, centre + vec2(0, 0.01f), 0.0065f, 0.006f, petiole_style);
  palmate_blade(c, centre, 0, 1);
  darken_silhouette(c, 0.28f, 4, 0.012f);
}

// A young Norway maple's leading shoot (Acer platanoides: leaves opposite, in pairs set crosswise
// on long petioles, 8-15 cm, so each pair stands clear of the next; the shoot ends in a fat
// terminal bud between two smaller ones): two pairs and a young pair at the tip, drawn flat as a
// pressed shoot so that the opposite arrangement, which sets maples apart from planes and
// sweetgums (alternate), reads on the card.
void draw_maple_spray(leaf_canvas& c, rng& g) {
  auto twig = [](float t) { return vec2(0.5f + 0.01f * std::sin(4.0f * t), 0.66f * t); };
  struct node { float t, ang, petiole, size; };
  const node nodes[3] = {{0.2f, 62, 0.15f, 0.36f}, {0.62f, 48, 0.12f, 0.33f}, {0.97f, 24, 0.05f, 0.18f}};
  for (const node& n : nodes) {
    const vec2 p = twig(n.t);
    for (int side : {-1, 1}) {
      const float ang = 90 + float(side) * (n.ang + g.range(-4, 4));
      const vec2 q = p + heading(ang) * n.petiole;
      stroke(c, p, q, 0.0048f, 0.0038f, petiole_style);
      // The blade turns a little back toward the shoot's tip from its petiole's line.
      palmate_blade(c, q, ang - 90 - float(side) * g.range(8, 16), n.size * g.range(0.94f, 1.06f));
    }
  }
  curve_stroke(c, twig, 6, 0.011f, 0.007f, twig_style);
  const vec2 tip = twig(1.0f);
  const stroke_style bud{0.5f, 1.0f, 0.1f, 0};
  stroke(c, tip, tip + vec2(0, 0.03f), 0.009f, 0.004f, bud);
  for (int side : {-1, 1}) stroke(c, tip, tip + heading(90 + float(side) * 30) * 0.018f, 0.006f, 0.003f, bud);
  darken_silhouette(c, 0.28f, 4, 0.012f);
}

// A horse chestnut leaf (Aesculus hippocastanum: palmately compound, five to seven obovate,
// abruptly pointed, doubly toothed leaflets without stalks, the middle one longest, up to about
// 25 cm, on a petiole about as long; leaves opposite; Rushforth 1999). Seven leaflets fanned from
// the petiole's tip a third of the way up the card, the outer pairs shorter and turned down; each
// leaflet is narrow at its wedge-shaped base and widest two thirds of the way to its tip, with
// many straight secondary veins. No other tree in the library has a palmately compound leaf.
void draw_horse_chestnut(leaf_canvas& c, rng& g) {
  const vec2 hub(0.5f, 0.34f);
  stroke(c, {0.5f, 0.0f}, hub, 0.0085f, 0.0062f, petiole_style);
  blade_style st;
  st.serration = 0.085f, st.teeth = 24, st.vein_angle = 52, st.veins = 15, st.midrib = 1.1f, st.edge_dark = 0.32f;
  auto leaflet = [](float t, int side) {
    // Obovate: a wedge at the base, widest near t = 0.7, then a short abrupt point; the two
    // halves a little out of step.
    const float u = std::pow(t, side ? 1.95f : 2.05f);
    return std::pow(std::sin(pi * u), 0.62f) * (1 - 0.25f * smooth(0.9f, 1.0f, t));
  };
  const float angles[4] = {0, 37, 74, 112};       // degrees from the middle leaflet
  const float lengths[4] = {0.62f, 0.56f, 0.43f, 0.27f};
  for (int k : {3, 2, 1, 0})
    for (int side : {-1, 1}) {
      if (k == 0 && side > 0) continue;
      const float a = 90 + float(side) * (angles[k] + g.range(-3, 3));
      const vec2 d = heading(a);
      const vec2 base = hub + d * 0.012f;
      const float len = fit(base, d, lengths[k] * g.range(0.95f, 1.04f), 0.02f);
      st.bend = -float(side) * (k == 0 ? 0 : 0.04f + 0.02f * float(k));   // the outer ones droop outward
      blade(c, base, a, len, 0.19f * len, leaflet, st);
    }
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

void draw_palm_frond(leaf_canvas& c, rng& g) {
  // A fan of four long, narrow leaflets (pinnae) from one point, each with its own midrib and
  // gaps of sky between them: one card per side of a rachis node, so a frond is the L-system's
  // rachis (wood) with these cards along both sides, leaflets in pairs like Phoenix or Cocos.
  blade_style st;
  st.veins = 1, st.midrib = 1.4f, st.edge_dark = 0.3f, st.dome = 0.25f;
  auto leaflet = [](float u, int) { return std::pow(std::sin(pi * std::pow(u, 0.45f)), 0.7f); };
  const float spread[4] = {-9.0f, -3.0f, 3.0f, 9.0f};
  for (int k = 0; k < 4; ++k) {
    const vec2 base{0.5f + 0.03f * (float(k) - 1.5f), 0.0f};
    const float ang = 90 + spread[k] + g.range(-1.5f, 1.5f);
    st.bend = (k % 2 ? 1.0f : -1.0f) * 0.025f;
    const float len = fit(base, heading(ang), (k == 1 || k == 2 ? 0.97f : 0.88f) * g.range(0.95f, 1.0f), 0.01f);
    blade(c, base, ang, len, 0.04f, leaflet, st);
  }
  // The leaflets' joint with the rachis: a short, thick stalk.
  stroke(c, {0.5f, 0.0f}, {0.5f, 0.05f}, 0.03f, 0.012f, {0.8f, 0.85f, 0.2f, 0});
}

// A hanging willow shoot (Salix babylonica: leaves lanceolate, about 8-12 by 1-2 cm, alternate,
// finely toothed, drawn out into a long point; Flora of China): a thin shoot up the card's centre
// carrying eight blades, alternate, each on a short petiole and leaving the shoot at 25-35 degrees
// toward its tip with a slight seeded curve, with sky between them so each reads as its own leaf
// (round 17's reader: the old card's thirteen overlapping blades read as "feathery strips").
void draw_lanceolate(leaf_canvas& c, rng& g) {
  // A weeping willow's hanging shoot (Salix babylonica: leaves narrow-lanceolate, 8-15 cm, long-
  // pointed, finely toothed, alternate and crowded along a slender pendulous shoot). Round 22-23's
  // readers saw the old card's eight leaves, set at 25-35 degrees in a regular chevron, as "fern
  // fronds": the leaves now lie close along the shoot (8-22 degrees), at uneven spacing and lengths,
  // each curving its own way, so a strand reads as a loose tassel of leaves, not a pinnate frond.
  auto shoot = [](float t) { return vec2(0.5f + 0.03f * std::sin(2.6f * t), 0.74f * t); };
  blade_style st;
  st.serration = 0.05f, st.teeth = 36, st.vein_angle = 58, st.veins = 12, st.dome = 0.16f, st.midrib = 1.2f;
  auto leaf = [](float t, int) { return std::pow(std::sin(pi * std::pow(t, 0.55f)), 1.05f); };
  curve_stroke(c, shoot, 6, 0.007f, 0.0035f, twig_style);
  const int leaves = 13;
  for (int i = 0; i < leaves; ++i) {
    const float t = std::clamp(0.05f + 0.86f * (float(i) + g.range(-0.35f, 0.35f)) / float(leaves - 1), 0.03f, 0.93f);
    const vec2 p = shoot(t);
    const float side = (i % 2) ? 1.0f : -1.0f;
    const float ang = 90 + side * g.range(8, 22) * (1.1f - 0.4f * t);
    const vec2 d = heading(ang);
    const vec2 q = p + d * 0.018f;
    stroke(c, p, q, 0.0028f, 0.0024f, petiole_style);
    st.bend = side * g.range(-0.03f, 0.07f);
    const float len = fit(q, d, g.range(0.3f, 0.5f) * (1.0f - 0.3f * t), 0.01f);
    blade(c, q - d * 0.004f, ang, len, len * g.range(0.07f, 0.09f), leaf, st);
  }
  const vec2 tip = shoot(1.0f);
  st.bend = 0;
  blade(c, tip - vec2(0, 0.01f), 90, fit(tip, {0, 1}, 0.26f), 0.022f, leaf, st);
}

// A twig carrying leaves up the card, alternate left and right, and one leaf at its tip: the
// layout the cluster cards share (twig_cluster and the beech, hazel and poplar sprays).
struct spray_layout {
  float wobble, freq, height;        // twig: x = 0.5 + wobble sin(freq t), y = height t
  float twig_w0, twig_w1;            // twig width at its base and tip
  int leaves;                        // side leaves, at t0 .. t0 + t_span along the twig
  float t0, t_span;
  float ang_lo, ang_hi;              // degrees off the twig (times 1.1 - 0.3 t)
  float petiole_lo, petiole_hi;      // petiole length (drawn from the range when lo < hi)
  float petiole_w0, petiole_w1;
  float sink;                        // the blade starts this far back along the petiole
  float bend;                        // at most this sideways curve per blade (none at 0)
  float len_lo, len_hi;              // blade length, and half-width as a share of it
  float width;
  float tip_petiole, tip_base, tip_len, tip_trim, tip_width;  // the tip leaf
  float bud = 0;                     // > 0: no tip leaf; the twig ends in a pointed bud this long
};

struct no_extra {
  void operator()(vec2, float, float, float) const {}
};

// `extra(base, degrees, len, half_width)` runs before each blade is drawn, so what it draws (a
// hazel's basal lobes) lies under the blade.
template <class Profile, class Extra = no_extra>
void leaf_spray(leaf_canvas& c, rng& g, const spray_layout& s, blade_style st, Profile leaf, Extra extra = {}) {
  // A shoot that ends in a bud zigzags: it turns at each node, the bend's outer corner on the
  // side of the leaf there, so it does not run straight like a compound leaf's rachis (Fagus,
  // Corylus); the other sprays' twigs wave gently.
  auto node_t = [&](int i) { return s.t0 + s.t_span * float(i) / float(s.leaves - 1); };
  auto twig = [&](float t) {
    if (s.bud <= 0) return vec2(0.5f + s.wobble * std::sin(s.freq * t), s.height * t);
    float x0 = 0.5f, t_prev = 0;
    for (int i = 0; i < s.leaves; ++i) {
      const float ti = node_t(i), xi = 0.5f + ((i % 2) ? -s.wobble : s.wobble);
      if (t <= ti) return vec2(x0 + (xi - x0) * (t - t_prev) / std::max(ti - t_prev, 1e-3f), s.height * t);
      x0 = xi, t_prev = ti;
    }
    return vec2(x0 + (0.5f - x0) * (t - t_prev) / std::max(1 - t_prev, 1e-3f), s.height * t);
  };
  for (int i = 0; i < s.leaves; ++i) {
    const float t = node_t(i);
    const vec2 p = twig(t);
    const float side = (i % 2) ? 1.0f : -1.0f;
    const float ang = 90 + side * g.range(s.ang_lo, s.ang_hi) * (1.1f - 0.3f * t);
    const vec2 d = heading(ang);
    const vec2 q = p + d * (s.petiole_lo < s.petiole_hi ? g.range(s.petiole_lo, s.petiole_hi) : s.petiole_lo);
    stroke(c, p, q, s.petiole_w0, s.petiole_w1, petiole_style);
    if (s.bend > 0) st.bend = side * g.range(0.0f, s.bend);
    const float len = fit(q, d, g.range(s.len_lo, s.len_hi), 0.01f);
    extra(q - d * s.sink, ang, len, len * s.width);
    blade(c, q - d * s.sink, ang, len, len * s.width, leaf, st);
  }
  curve_stroke(c, twig, s.bud > 0 ? 4 * (s.leaves + 1) : 6, s.twig_w0, s.twig_w1, twig_style);
  const vec2 tip = twig(1.0f);
  if (s.bud > 0) {
    // A shoot ends in its winter bud, not in a leaf: a tip leaf in line with the twig, flanked by
    // leaves left and right, is how a pinnate compound leaf ends, and readers took the sprays for
    // one (round 29: hazel, "rows that look like pinnate leaflets"; round 31: beech named as ash).
    const stroke_style bud{0.45f, 1.0f, 0.1f, 0};
    const vec2 d = glm::normalize(twig(1.0f) - twig(0.97f));
    stroke(c, tip - d * 0.005f, tip + d * s.bud, 1.3f * s.twig_w1, 0.0015f, bud);
    return;
  }
  st.bend = 0;
  stroke(c, tip, tip + vec2(0, s.tip_petiole), s.petiole_w0, s.petiole_w1, petiole_style);
  const float tip_len = fit(tip, {0, 1}, s.tip_len) - s.tip_trim;
  extra(tip + vec2(0, s.tip_base), 90.0f, tip_len, s.tip_width);
  blade(c, tip + vec2(0, s.tip_base), 90, tip_len, s.tip_width, leaf, st);
}

void draw_twig_cluster(leaf_canvas& c, rng& g) {
  blade_style st;
  st.serration = 0.08f, st.teeth = 14, st.vein_angle = 42, st.veins = 6;
  const spray_layout s{0.04f, 2.4f, 0.62f, 0.011f, 0.0055f, 7, 0.22f, 0.74f, 48, 64, 0.035f, 0.035f, 0.0035f, 0.003f,
                       0.005f, 0, 0.27f, 0.32f, 0.42f, 0.03f, 0.025f, 0.32f, 0.02f, 0.13f};
  leaf_spray(c, g, s, st, [](float t, int) { return ovate_profile(t); });
}

// A flat two-ranked beech spray (Fagus sylvatica: leaves elliptic, 5-10 cm, with an entire, wavy
// margin and 5-9 pairs of straight parallel veins that run out to it; alternate along a zigzag
// twig and held in one plane): four leaves on a twig that bends at each node.
void draw_beech_spray(leaf_canvas& c, rng& g) {
  blade_style st;
  st.serration = 0, st.vein_angle = 36, st.veins = 8, st.edge_dark = 0.34f;
  // Four side leaves and the long, slender, pointed bud beech shoots end in (no tip leaf). Six
  // smaller ones in a row read as a compound leaf's leaflets (round 34: "pinnately compound leaves
  // with many oval leaflets", the beech named as an ash at 2).
  const spray_layout s{0.04f, 9.0f, 0.72f, 0.009f, 0.005f, 4, 0.16f, 0.68f, 50, 64, 0.02f, 0.02f, 0.0035f, 0.003f,
                       0.004f, 0.04f, 0.42f, 0.48f, 0.33f, 0, 0, 0, 0, 0, 0.07f};
  // Widest a little below the middle, tapering straight to an acute tip (a pow below 1 would round
  // it off); no teeth (round 17's reader saw the old card's twelve shallow teeth as "jagged" and
  // thought of hornbeam), only a low wave between the vein ends.
  leaf_spray(c, g, s, st, [](float t, int) {
    const float wave = 1 - 0.03f * (0.5f + 0.5f * std::cos(2 * pi * 8.0f * t));
    return std::pow(std::sin(pi * std::pow(t, 0.74f)), 0.9f) * wave;
  });
}

// A hazel shoot (Corylus avellana: leaves broad, nearly round, 6-12 cm, with a heart-shaped base,
// a doubly toothed margin and a short abrupt point; alternate in two ranks): three leaves on a
// hairy twig. The outline is a circle set on its base that narrows to the point in its last fifth;
// teeth on teeth double the margin. The heart: two round basal lobes reach back past where the
// petiole joins, either side of it, with the notch between them (rounds 22-23's readers found the
// leaves "less heart-shaped than real hazel leaves" when the blade began straight across).
void draw_hazel_spray(leaf_canvas& c, rng& g) {
  blade_style st;
  st.serration = 0.07f, st.teeth = 46, st.vein_angle = 44, st.veins = 7, st.dome = 0.14f;
  // Three broad side leaves, a quarter longer than the five they replace (about 7.5 cm on
  // species_bush's 0.15 m card), and a small blunt bud at the shoot's end (no tip leaf). Five
  // smaller ones in a row read "pinnate-like" and "smaller and more oval than hazel's broad
  // cordate leaves" (rounds 29-34).
  const spray_layout s{0.035f, 7.0f, 0.6f, 0.011f, 0.006f, 3, 0.16f, 0.66f, 48, 64, 0.035f, 0.035f, 0.004f, 0.0035f,
                       0.0f, 0.03f, 0.46f, 0.52f, 0.5f, 0, 0, 0, 0, 0, 0.03f};
  auto hazel = [](float t, int) {
    // A round blade that ends in an abrupt short point (cuspidate), with the larger teeth of the
    // double serration over the fine ones.
    const float round = std::sqrt(std::max(0.0f, 1 - std::pow((t - 0.38f) / 0.54f, 2.0f)));
    const float point = t > 0.66f ? 0.26f * (1 - t) / 0.34f : 0.0f;
    const float teeth2 = 1 - 0.08f * (0.5f + 0.5f * std::cos(2 * pi * 11.0f * t));
    return std::max(round, point) * teeth2;
  };
  leaf_spray(c, g, s, st, hazel, [&](vec2 base, float ang, float len, float width) {
    // The basal lobes: small round blades from just beside the petiole's end, turned back 135-150
    // degrees off the leaf's axis, without a midrib of their own.
    blade_style lobe = st;
    lobe.midrib = 0, lobe.veins = 2, lobe.serration = 0.05f;
    const vec2 across(-heading(ang).y, heading(ang).x);
    for (int k = -1; k <= 1; k += 2) {
      const float back = ang + float(k) * g.range(135, 150);
      const vec2 at = base + across * (float(k) * 0.18f * width) + heading(ang) * (0.06f * len);
      blade(c, at, back, 0.26f * len, 0.5f * width, [](float t, int) { return std::sqrt(std::max(0.0f, std::sin(pi * t))); }, lobe);
    }
  });
}

// A black poplar shoot (Populus nigra 'Italica': leaves deltoid to rhombic, 5-10 cm, with a broad
// truncate base, straight sides drawn out into a long point, a finely crenate margin, and long
// flattened petioles, so each leaf hangs at its own angle): five leaves on long stalks up a twig.
void draw_poplar_spray(leaf_canvas& c, rng& g) {
  blade_style st;
  st.serration = 0.045f, st.teeth = 34, st.vein_angle = 48, st.veins = 6, st.dome = 0.08f;
  const spray_layout s{0.02f, 5.0f, 0.55f, 0.009f, 0.005f, 5, 0.2f, 0.78f, 40, 62, 0.07f, 0.1f, 0.0032f, 0.0028f,
                       0.004f, 0.05f, 0.28f, 0.33f, 0.42f, 0.07f, 0.066f, 0.36f, 0.07f, 0.12f};
  // Widest a fifth of the way up, then straight sides to the point (deltoid).
  leaf_spray(c, g, s, st, [](float t, int) { return t < 0.2f ? std::pow(t / 0.2f, 0.45f) : std::pow(1 - (t - 0.2f) / 0.8f, 1.15f); });
}

}  // namespace sylva::archetype
