// Cone and fruit cards (generators/fruits.h places them; the list is generators/archetypes.h's):
// cones, samaras, keys, nuts, acorns, coconuts and cypress cones. Unlike the leaf cards they are drawn in their own
// colours (the leaf_look's two colours are final, not a pale base for the leaf tint):
// render/mesh/season.h archetype_is_fruit keeps the tint off them.
//
// Card coordinates as for the leaves (render/assets/archetype_canvas.h): the stalk enters at
// (0.5, 0) and the fruit runs up the card; the placement turns the card to hang or stand.
#include <algorithm>
#include <cmath>

#include "render/assets/archetype_canvas.h"

namespace sylva::archetype {
namespace {

inline float fract(float x) { return x - ffloor(x); }

// The outline of a cone's body: half-width along t in [0, 1] (base to apex), widest at `widest`,
// with rounded ends (exponent below 1: flat sides, as a cylinder seen from the side).
struct cone_shape {
  float length = 0.8f, width = 0.12f;   // card units: body length and greatest half-width
  float widest = 0.45f;                 // t of the greatest width
  float sides = 0.45f;                  // sin(pi t')^sides: smaller is more cylindrical
  float stalk = 0.06f;                  // stalk before the body
  float rows = 16, around = 11;         // scale rows along the body, scales around it
  float lip = 0.35f;                    // how far each scale's free edge lifts (relief)
  float bract = 0;                      // 0..1: a bract's pointed tip showing below each scale (Abies)
  bool shields = false;                 // Pinus: each scale ends in a rhombic shield (apophysis) with a central boss (umbo)
};

float cone_half_width(const cone_shape& s, float t) {
  if (t <= 0 || t >= 1) return 0;
  const float k = std::log(0.5f) / std::log(std::clamp(s.widest, 0.05f, 0.95f));
  return s.width * std::pow(std::sin(pi * std::pow(t, k)), s.sides);
}

// A seed cone seen from the side: a body of spirally set woody scales (Farjon 2010: Picea and
// Abies cones carry them in parastichies), each a rounded plate whose free edge points to the
// apex, with a dark shadow line under that edge. The body's roundness goes into the height (so the
// normal map curves it) and, as baked occlusion, into the shade toward its silhouette.
void draw_cone(leaf_canvas& c, rng& g, const cone_shape& s) {
  const vec2 base(0.5f, s.stalk);
  stroke(c, vec2(0.5f, 0.0f), base + vec2(0, 0.02f), 0.012f, 0.011f, twig_style);
  const float phase = g.range(0, 1);
  raster(c, base, vec2(0, 1), s.length, s.width, 0, [&](float a, float b) {
    sample out;
    const float t = a / s.length;
    const float w = cone_half_width(s, t);
    if (w <= 0) return out;
    out.cover = clamp01((w - std::abs(b)) / c.px + 0.5f);
    if (out.cover <= 0) return out;
    const float x = std::clamp(b / w, -0.999f, 0.999f);
    const float facing = std::sqrt(1 - x * x);   // cosine of the surface's turn away from the viewer
    const float phi = std::asin(x) / (2 * pi);    // turns around the axis, -0.25 .. 0.25 visible
    // Scales in staggered rows along the axis; the stagger makes the spiral rows.
    const float along = t * s.rows;
    const float row = ffloor(along);
    const float fr = along - row;                  // 0: the scale's base, 1: its free edge (apex side)
    const float q = fract(phi * s.around + 0.5f * row + phase) - 0.5f;   // -0.5 .. 0.5 across the scale
    // The scale's outline: full width at its base, rounding off toward its free edge; or a
    // rhombic shield with a boss in its middle.
    const float half = 0.5f * std::sqrt(std::max(0.0f, 1 - std::pow(fr, 2.5f)));
    // Shields: cells between two families of spirals (the cone's parastichies), 0.5 at a
    // shield's middle and 0 on its seams.
    const float fa = fract(phi * s.around + 0.5f * along + phase) - 0.5f, fb = fract(phi * s.around - 0.5f * along + phase) - 0.5f;
    const float rhomb = 0.5f - std::max(std::abs(fa), std::abs(fb));
    const float inside = s.shields ? clamp01(rhomb * 14.0f - 0.2f) : clamp01((half - std::abs(q)) * 6.0f);
    const float lift = s.shields ? std::max(0.0f, 2 * rhomb) : fr * fr;   // the plate rises toward its free edge
    out.height = 0.55f * w * facing + s.lip * 0.012f * (inside * lift - (1 - inside) * 0.6f);
    float shade = 0.42f + 0.58f * std::pow(facing, 0.6f);
    shade *= 0.45f + 0.55f * inside;               // the gaps between plates are in shadow
    if (!s.shields) shade *= 1 - 0.35f * smooth(0.0f, 0.25f, 0.25f - fr) * inside;   // under the row above's edge
    out.warm = inside * (0.25f + 0.75f * smooth(0.45f, 0.95f, fr));  // the exposed edges are paler
    if (s.shields) {   // the shield is pale, its boss and the seams between shields dark
      out.warm = inside * (0.35f + 0.65f * smooth(0.05f, 0.3f, rhomb));
      if (rhomb > 0.42f) shade *= 0.55f;
    }
    if (s.bract > 0) {   // Abies alba: the bract's pointed tip shows below the scale's edge
      const float tip = (1 - fr) * 0.12f * s.bract;
      if (fr < 0.3f && std::abs(q) < tip) out.warm = 1, shade = std::max(shade, 0.85f);
    }
    out.shade = shade;
    out.thin = 0.05f;   // woody: no light through it
    return out;
  });
  // The body's tip: the last scales close over the apex.
}

// A filled ellipse (nut, seed) with a dome: `warm` picks between the look's two colours.
void ellipse(leaf_canvas& c, vec2 centre, float degrees, float len, float width, float warm, float shade) {
  const vec2 dir = heading(degrees);
  const vec2 base = centre - dir * (0.5f * len);
  raster(c, base, dir, len, width, 0, [&](float a, float b) {
    sample s;
    const float t = a / len;
    if (t <= 0 || t >= 1) return s;
    const float w = width * std::sqrt(std::max(0.0f, 1 - (2 * t - 1) * (2 * t - 1)));
    s.cover = clamp01((w - std::abs(b)) / c.px + 0.5f);
    if (s.cover <= 0) return s;
    const float across = std::min(std::abs(b) / std::max(w, 1e-6f), 1.0f);
    const float round = std::sqrt(1 - across * across) * std::sqrt(std::max(0.0f, 1 - (2 * t - 1) * (2 * t - 1)));
    s.height = 0.6f * width * round;
    s.shade = shade * (0.55f + 0.45f * round) * (1 + 0.25f * smooth(0.6f, 0.95f, t) * (1 - across));  // a highlight toward the tip
    s.warm = warm;
    s.thin = 0.05f;
    return s;
  });
}

}  // namespace

void draw_cone_hanging(leaf_canvas& c, rng& g) {
  // Picea abies: cylindrical, 10-16 cm long and 3-4 cm wide, tapering a little to a blunt apex,
  // thin rhombic scales with a finely notched edge (Farjon 2010). Hung from the shoot tip.
  cone_shape s;
  s.length = 0.86f, s.width = 0.125f, s.widest = 0.4f, s.sides = 0.5f, s.stalk = 0.08f;
  s.rows = 17, s.around = 9, s.lip = 0.3f;
  draw_cone(c, g, s);
}

void draw_cone_upright(leaf_canvas& c, rng& g) {
  // Abies alba and Cedrus: upright, barrel-shaped to cylindrical, 10-15 cm by 4-6 cm, with a
  // rounded top, standing on the upper side of the shoot; A. alba's bract tips show below the
  // scales (Farjon 2010).
  cone_shape s;
  s.length = 0.8f, s.width = 0.17f, s.widest = 0.55f, s.sides = 0.32f, s.stalk = 0.04f;
  s.rows = 13, s.around = 8, s.lip = 0.2f, s.bract = 1.0f;
  draw_cone(c, g, s);
}

void draw_cone_barrel(leaf_canvas& c, rng& g) {
  // Cedrus libani: erect, barrel-shaped, 8-12 cm long and 5-6 cm wide, with a flat or slightly
  // sunken top, broad smooth scales pressed close and no bracts showing (Farjon 2010): squatter and
  // blunter than a fir's cone, which is why the cedar has its own card.
  cone_shape s;
  s.length = 0.6f, s.width = 0.21f, s.widest = 0.5f, s.sides = 0.18f, s.stalk = 0.05f;
  s.rows = 10, s.around = 7, s.lip = 0.12f;
  draw_cone(c, g, s);
}

void draw_cone_ovoid(leaf_canvas& c, rng& g) {
  // Pinus sylvestris: ovoid-conic, 3-7 cm, grey-brown when ripe, each scale ending in a flat
  // rhombic shield with a small central boss; pointing back down the shoot on a short stalk
  // (Farjon 2010).
  cone_shape s;
  s.length = 0.78f, s.width = 0.22f, s.widest = 0.35f, s.sides = 0.75f, s.stalk = 0.08f;
  s.rows = 9, s.around = 6, s.lip = 0.5f, s.shields = true;
  draw_cone(c, g, s);
}

void draw_samaras(leaf_canvas& c, rng& g) {
  // Acer: a hanging cluster of paired samaras (schizocarp halves), each a round nutlet with a
  // veined wing 3-5 cm long; the pairs spread their wings at 60-180 degrees (A. pseudoplatanus
  // near 90, A. platanoides near 180; Rushforth 1999). Three pairs on pedicels from one stalk; the
  // card hangs, so the wings point down from their nutlets.
  const vec2 top(0.5f, 0.0f);
  const vec2 hub(0.5f, 0.14f);
  stroke(c, top, hub, 0.007f, 0.006f, petiole_style);
  blade_style wing;
  wing.veins = 10, wing.vein_angle = 10, wing.midrib = 0.25f, wing.edge_dark = 0.3f, wing.dome = 0.03f;
  const float fans[3] = {-30, 2, 32}, reach[3] = {0.2f, 0.3f, 0.16f};
  for (int i = 0; i < 3; ++i) {
    const float fan = fans[i] + g.range(-5, 5);
    const vec2 d = heading(90 + fan);
    const vec2 nut = hub + d * reach[i];
    curve_stroke(c, [&](float t) { return bezier(hub, hub + d * (0.5f * reach[i]) + vec2(0.01f * fan / 30, 0), nut, t); }, 3, 0.0045f, 0.0035f, petiole_style);
    const float axis = 90 + fan * 0.5f;
    const float open = g.range(34, 44);   // half the angle between the wings
    for (int side : {-1, 1}) {
      const float deg = axis + float(side) * open;
      const vec2 wd = heading(deg);
      wing.bend = -0.1f * float(side);
      const float len = fit(nut, wd, g.range(0.3f, 0.36f), 0.02f);
      // A wing: narrow at the nutlet, broadest two thirds out, rounded at its end.
      blade(c, nut + wd * 0.025f, deg, len, 0.06f, [](float t, int) { return std::pow(std::sin(pi * std::pow(t, 1.4f)), 0.6f) * (0.3f + 0.7f * t); }, wing);
      ellipse(c, nut + wd * 0.035f, deg, 0.085f, 0.034f, 1.0f, 0.9f);   // the nutlet
    }
  }
}

void draw_hazelnuts(leaf_canvas& c, rng& g) {
  // Corylus avellana: nuts 1.5-2.5 cm in clusters of one to four, each held in a leafy husk
  // (involucre) with a torn, toothed rim that reaches about the nut's length (Rushforth 1999).
  const vec2 top(0.5f, 0.0f);
  const vec2 hub(0.5f, 0.14f);
  stroke(c, top, hub, 0.014f, 0.012f, petiole_style);
  blade_style husk;
  husk.serration = 0.6f, husk.teeth = 6, husk.veins = 5, husk.vein_angle = 22, husk.midrib = 0.3f, husk.dome = 0.14f;
  const float fans[3] = {2, -34, 32};   // the middle nut first: the side ones cover its husk
  const float lens[3] = {0.36f, 0.3f, 0.31f};
  for (int i = 0; i < 3; ++i) {
    const float deg = 90 + fans[i] + g.range(-5, 5);
    const vec2 d = heading(deg);
    const vec2 at = hub + d * 0.03f;
    const float len = lens[i] * g.range(0.92f, 1.05f);
    ellipse(c, at + d * (0.08f + 0.5f * len), deg, len, 0.115f, 1.0f, 1.0f);   // the nut, its tip out of the husk
    // The husk: two frilled bracts around the nut's lower part, their teeth splayed.
    for (int side : {-1, 1}) {
      husk.bend = 0.12f * float(side);
      blade(c, at, deg + float(side) * 8, 0.98f * len, 0.15f, [](float t, int) { return std::pow(std::sin(pi * std::pow(t, 0.45f)), 0.45f) * (0.6f + 0.4f * t); }, husk);
    }
  }
}

void draw_beechnuts(leaf_canvas& c, rng& g) {
  // Fagus sylvatica: a woody cupule 1.5-2.5 cm, covered in soft bristles, that splits into four
  // valves round two triangular brown nuts; in pairs on a short stalk (Rushforth 1999).
  const vec2 top(0.5f, 0.0f);
  const vec2 hub(0.5f, 0.18f);
  stroke(c, top, hub, 0.012f, 0.01f, petiole_style);
  const stroke_style bristle{0.75f, 0.2f, 0.1f, 0};
  for (float fan : {-24.0f, 22.0f}) {
    const float deg = 90 + fan + g.range(-5, 5);
    const vec2 d = heading(deg), n(-d.y, d.x);
    const vec2 base = hub + d * 0.05f;
    stroke(c, hub, base, 0.008f, 0.007f, petiole_style);
    const float len = 0.36f, width = 0.12f;
    const vec2 mid = base + d * (0.5f * len);
    // The bristles first, radiating from the cupule's outline, then its body over their roots.
    for (int k = 0; k < 70; ++k) {
      const float a = 2 * pi * float(k) / 70.0f + g.range(-0.04f, 0.04f);
      const float along = 0.5f * len * std::sin(a), across = width * std::cos(a);
      if (along > 0.32f * len) continue;   // the open valves' rim carries none
      const vec2 p = mid + d * along + n * across;
      const vec2 out = glm::normalize(d * (std::sin(a) / len) + n * (std::cos(a) / width));
      stroke(c, p - out * 0.01f, p + out * g.range(0.03f, 0.045f), 0.0035f, 0.001f, bristle);
    }
    ellipse(c, mid, deg, len, width, 0.25f, 0.85f);
    for (int k = 0; k < 45; ++k) {   // bristles over the body, pointing up and out
      const float u = g.range(-0.42f, 0.3f), w = g.range(-0.85f, 0.85f);
      const vec2 p = mid + d * (u * len) + n * (w * width * std::sqrt(std::max(0.0f, 1 - 4 * u * u)));
      const vec2 out = glm::normalize(d + n * (1.2f * w));
      stroke(c, p, p + out * g.range(0.02f, 0.03f), 0.003f, 0.001f, bristle);
    }
    // Four valves opening at the top, and the two nuts' points between them.
    for (int v = 0; v < 2; ++v) {
      const float side = v ? 1.0f : -1.0f;
      ellipse(c, base + d * (0.86f * len) + n * (side * 0.055f), deg + side * 28, 0.17f, 0.035f, 0.3f, 0.9f);
    }
    for (int v = 0; v < 2; ++v)
      ellipse(c, base + d * (0.9f * len) + n * ((v ? 1.0f : -1.0f) * 0.018f), deg + (v ? -6.0f : 6.0f), 0.16f, 0.03f, 1.0f, 0.8f);
  }
}

void draw_coconuts(leaf_canvas& c, rng& g) {
  // Cocos nucifera: fruits ovoid, obscurely three-sided, 20-30 cm long, green ripening to yellow
  // and brown, in bunches of five to twelve on a stout branched stalk that hangs from among the
  // frond bases (Riffle & Craft 2003). Seven nuts close together on short branches of one
  // peduncle: the stalks first, then the back nuts (darker) and the front ones over them.
  const vec2 top(0.5f, 0.0f), hub(0.5f, 0.2f);
  curve_stroke(c, [&](float t) { return bezier(top, vec2(0.47f, 0.1f), hub, t); }, 4, 0.024f, 0.02f, petiole_style);
  struct nut { float x, y, deg, ripe, shade; };
  const nut nuts[7] = {
      {0.31f, 0.5f, 108, 0.15f, 0.7f}, {0.69f, 0.5f, 72, 0.55f, 0.7f}, {0.5f, 0.6f, 92, 0.3f, 0.78f},   // back
      {0.37f, 0.7f, 100, 0.8f, 0.92f}, {0.64f, 0.72f, 80, 0.2f, 0.92f},                                  // lower pair
      {0.3f, 0.36f, 125, 0.45f, 1.0f}, {0.7f, 0.36f, 55, 0.05f, 1.0f},                                   // front, high
  };
  vec2 centre[7];
  float deg[7], len[7];
  for (int k = 0; k < 7; ++k) {
    deg[k] = nuts[k].deg + g.range(-6, 6);
    len[k] = g.range(0.27f, 0.31f);
    centre[k] = vec2(nuts[k].x + g.range(-0.012f, 0.012f), nuts[k].y + g.range(-0.012f, 0.012f));
    stroke(c, hub, centre[k] - heading(deg[k]) * (0.45f * len[k]), 0.012f, 0.01f, petiole_style);
  }
  for (int k = 0; k < 7; ++k) {
    const vec2 d = heading(deg[k]);
    ellipse(c, centre[k], deg[k], len[k], 0.118f, nuts[k].ripe, nuts[k].shade);
    ellipse(c, centre[k] - d * (0.47f * len[k]), deg[k], 0.05f, 0.05f, 1.0f, 0.5f * nuts[k].shade);   // the calyx's dry bracts
  }
}

void draw_ash_keys(leaf_canvas& c, rng& g) {
  // Fraxinus excelsior: keys (single samaras) 2.5-4.5 cm long and 5-8 mm wide, a narrow oblong
  // wing, blunt or notched at its end, beyond the slender seed at its base; hanging in dense bunches
  // of a dozen to thirty on a branched stalk, and kept on the tree into the winter (Rushforth 1999).
  // Four branches of the stalk leave it one after another, each with four or five keys on short
  // pedicels along it; the card hangs, so the keys hang in a loose tassel.
  const vec2 top(0.5f, 0.0f), hub(0.5f, 0.2f);
  curve_stroke(c, [&](float t) { return bezier(top, vec2(0.48f, 0.1f), hub, t); }, 3, 0.008f, 0.007f, petiole_style);
  blade_style wing;
  wing.veins = 7, wing.vein_angle = 5, wing.midrib = 0.35f, wing.edge_dark = 0.3f, wing.dome = 0.04f;
  const float fans[4] = {-30, 26, -9, 8};   // the outer branches first: the inner ones hang over them
  const float from[4] = {0.0f, 0.02f, 0.05f, 0.08f};
  for (int b = 0; b < 4; ++b) {
    const float bdeg = 90 + fans[b] + g.range(-4, 4);
    const vec2 bd = heading(bdeg);
    const vec2 start = hub + vec2(0, from[b]);
    const float blen = g.range(0.16f, 0.22f);
    stroke(c, start, start + bd * blen, 0.005f, 0.004f, petiole_style);
    const int keys = b < 2 ? 4 : 5;
    for (int k = 0; k < keys; ++k) {
      const vec2 at = start + bd * (blen * (0.3f + 0.7f * float(k) / float(keys - 1)));
      const float deg = 90 + 0.8f * fans[b] + g.range(-14, 14);
      const vec2 d = heading(deg);
      const vec2 base = at + d * 0.025f;
      stroke(c, at, base, 0.0035f, 0.003f, petiole_style);
      const float len = fit(base, d, g.range(0.34f, 0.42f), 0.02f);
      wing.bend = g.range(-0.08f, 0.08f);   // keys are a little twisted
      blade(c, base, deg, len, 0.028f, [](float t, int) { return std::pow(std::sin(pi * t), 0.35f) * (0.45f + 0.55f * smooth(0.1f, 0.55f, t)); }, wing);
      ellipse(c, base + d * (0.17f * len), deg, 0.3f * len, 0.013f, 0.7f, 0.95f);   // the seed
    }
  }
}

// Quercus robur: acorns 1.5-2.5 cm, ovoid-oblong with a short point, a third of each held in a
// shallow cup of close-pressed scales, one to three (to five) together on a long slender stalk, the
// peduncle, 3-8 cm: the "pedunculate" oak, as against the sessile oak's stalkless acorns (Rushforth
// 1999). Here three: one partway along the stalk and two at its end, pointing out.
void draw_acorns(leaf_canvas& c, rng& g) {
  auto stalk = [](float t) { return vec2(0.5f + 0.025f * std::sin(2.5f * t), 0.46f * t); };
  curve_stroke(c, stalk, 5, 0.0095f, 0.0075f, petiole_style);
  struct acorn { float t, deg, len; };
  const acorn nuts[3] = {{0.62f, 90 + 52, 0.24f}, {1.0f, 90 - 30, 0.27f}, {1.0f, 90 + 14, 0.26f}};
  const stroke_style scale_row{0.62f, 0.0f, 0.05f, 0};
  for (const acorn& a : nuts) {
    const float deg = a.deg + g.range(-5, 5), len = a.len * g.range(0.94f, 1.05f);
    const vec2 d = heading(deg), n(-d.y, d.x);
    const vec2 base = stalk(a.t) + d * 0.025f;
    stroke(c, stalk(a.t), base, 0.007f, 0.0065f, petiole_style);
    // The cup and its scale rows first, then the nut over the cup's upper half: the nut's narrow
    // base sits in the bowl, which shows round it.
    ellipse(c, base + d * 0.06f, deg, 0.15f, 0.1f, 0.0f, 0.9f);
    for (int k = 0; k < 3; ++k) {
      const vec2 m = base + d * (0.012f + 0.022f * float(k));
      const float w = 0.055f + 0.016f * float(k);
      stroke(c, m - n * w, m + n * w, 0.0028f, 0.0028f, scale_row);
    }
    ellipse(c, base + d * (0.06f + 0.5f * len), deg, len, 0.082f, 1.0f, 1.0f);
    const vec2 apex = base + d * (0.06f + len);
    stroke(c, apex - d * 0.012f, apex + d * 0.012f, 0.005f, 0.0015f, scale_row);
  }
}

void draw_cypress_cones(leaf_canvas& c, rng& g) {
  // Cupressus sempervirens: cones nearly round, 2-4 cm, of 8-14 woody peltate scales that meet
  // edge to edge, each with a small boss in its middle; green at first, grey-brown and glossy when
  // ripe in their second year; on short stout stalks, often several together on a branchlet
  // (Farjon 2010). Three cones on a short twig. Each ball's shields are the cells of ten points
  // spread evenly over the sphere (a Fibonacci lattice) turned at random: a seam where the nearest
  // two centres are about equally near, a boss where one is very near.
  const vec2 top(0.5f, 0.0f), fork(0.5f, 0.3f);
  stroke(c, top, fork, 0.014f, 0.011f, twig_style);
  constexpr int shields = 10;
  vec3 centre3[shields];
  for (int k = 0; k < shields; ++k) {
    const float z = 1 - 2 * (float(k) + 0.5f) / float(shields), rho = std::sqrt(1 - z * z);
    const float phi = 2.39996323f * float(k);   // the golden angle
    centre3[k] = vec3(rho * std::cos(phi), rho * std::sin(phi), z);
  }
  struct ball { float x, y, r, ripe; };
  const ball balls[3] = {{0.3f, 0.47f, 0.15f, 0.8f}, {0.71f, 0.5f, 0.16f, 0.95f}, {0.5f, 0.7f, 0.2f, 1.0f}};
  for (const ball& b : balls) {
    const vec2 centre(b.x + g.range(-0.01f, 0.01f), b.y + g.range(-0.01f, 0.01f));
    stroke(c, fork, centre, 0.012f, 0.01f, twig_style);
    const float ya = g.range(0, 2 * pi), xa = g.range(0, pi);
    const float cy = std::cos(ya), sy = std::sin(ya), cx = std::cos(xa), sx = std::sin(xa);
    const float r = b.r;
    raster(c, centre - vec2(0, r), vec2(0, 1), 2 * r, r, 0, [&](float a, float w) {
      sample s;
      const float u = (a - r) / r, v = w / r, rr = u * u + v * v;
      s.cover = clamp01((1 - std::sqrt(rr)) * r / c.px + 0.5f);
      if (s.cover <= 0) return s;
      const float facing = std::sqrt(std::max(0.0f, 1 - rr));
      // The surface point, turned about the view axis and then about the card's x axis.
      const float x1 = v * cy - u * sy, y1 = v * sy + u * cy;
      const vec3 n(x1, y1 * cx - facing * sx, y1 * sx + facing * cx);
      float best = -2, second = -2;
      for (const vec3& k : centre3) {
        const float d = n.x * k.x + n.y * k.y + n.z * k.z;
        if (d > best) second = best, best = d;
        else if (d > second) second = d;
      }
      const float in = clamp01(((best - second) / std::max(facing, 0.3f) - 0.02f) * 18.0f);   // 0 on a seam
      const float boss = clamp01((best - 0.985f) / 0.015f);
      s.height = 0.6f * r * facing + 0.012f * (in - 1) + 0.01f * boss;
      s.shade = (0.4f + 0.6f * std::pow(facing, 0.7f)) * (0.45f + 0.55f * in) * (1 - 0.4f * boss);
      s.warm = b.ripe * in * (0.75f + 0.25f * facing);
      s.thin = 0.05f;   // woody
      return s;
    });
  }
}

}  // namespace sylva::archetype
