// Bark archetypes: periodic height and colour fields that tile both ways (u around the
// branch, v along it), from value noise, cellular noise and wandering lines.
#include <algorithm>
#include <cmath>
#include <vector>

#include "render/assets/archetype_canvas.h"

namespace sylva::archetype {
namespace {

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

}  // namespace

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

namespace {

// Thin, smooth grey bark: soft lighter and darker mottles and faint horizontal wrinkles; `spots`
// adds a few small dark spots (a young fir's resin blisters), `wrinkles` scales the wrinkles.
void smooth_grey(bark_field& f, uint64_t seed, bool spots_on, float wrinkles) {
  const lattice mottle(4, 3, seed + 1), mottle2(9, 7, seed + 2), wrinkle(4, 60, seed + 3), fine(90, 90, seed + 4);
  const cells spots(9, 12, seed + 5, 0.4f);
  const vec3 light = srgb_color(236, 236, 232), shadow = srgb_color(196, 194, 188), spot_col = srgb_color(120, 116, 110);
  const int n = f.n;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const float u = (float(x) + 0.5f) / float(n), v = (float(y) + 0.5f) / float(n);
      const float m = 0.65f * mottle(u, v) + 0.35f * mottle2(u, v);
      const float w = wrinkle(u, v), fn = fine(u, v);
      // One possible spot per cell, round and small around the cell's point (jitter 0.4 keeps it
      // inside its cell).
      float spot = 0;
      if (spots_on) {
        const float fx = u * float(spots.cx), fy = v * float(spots.cy);
        const int id = wrap(int(ffloor(fy)), spots.cy) * spots.cx + wrap(int(ffloor(fx)), spots.cx);
        const vec2 cell_pt = spots.points[size_t(id)];
        const float dx = fx - ffloor(fx) - cell_pt.x, dy = fy - ffloor(fy) - cell_pt.y;
        spot = unit(seed * 313 + uint64_t(id)) < 0.1f ? 1 - smooth(0.01f, 0.05f, dx * dx + dy * dy) : 0.0f;
      }
      const size_t k = size_t(y) * n + x;
      f.height[k] = 0.3f * wrinkles * w + 0.22f * fn + 0.2f * m - 0.3f * spot;  // thin bark: soft, shallow relief
      vec3 c = mix3(shadow, light, smooth(0.1f, 0.9f, m)) * (0.96f + 0.06f * wrinkles * w + 0.04f * fn);
      c = mix3(c, spot_col, 0.6f * spot);
      f.paint(k, c, 0.55f + 0.15f * (1 - m) + 0.1f * spot);
    }
}

}  // namespace

void bark_mottled(bark_field& f, uint64_t seed) {
  // Young Abies (and the beech until round 18): thin, smooth, silver-grey bark with no lenticel
  // dashes; soft lighter and darker mottles, faint horizontal wrinkles, a few small dark spots
  // (a fir's resin blisters).
  smooth_grey(f, seed, true, 1.0f);
}

void bark_silver(bark_field& f, uint64_t seed) {
  // Fagus sylvatica: smooth silver-grey "elephant skin" with no spots at all (round 18's reader
  // took the mottled bark's dots for "a young ash or cherry"); the horizontal wrinkles, where the
  // thin bark creases as the trunk widens, a little deeper than the fir's.
  smooth_grey(f, seed + 0x5EED, false, 1.4f);
}

void bark_fissured(bark_field& f, uint64_t seed) {
  // Fraxinus excelsior (old Cedrus too): grey bark cut by shallow fissures that lean left and right
  // and cross, leaving a network of narrow, elongated diamond ridges along the trunk.
  const int across = 9, along = 3;  // fissures around the tile; crossings along it
  const lattice warp(6, 5, seed + 1), jag(36, 24, seed + 2), grain(110, 20, seed + 3), tone(5, 4, seed + 4);
  const vec3 ridge = srgb_color(226, 224, 218), ridge2 = srgb_color(200, 196, 188), fissure = srgb_color(70, 66, 62);
  const int n = f.n;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const float u = (float(x) + 0.5f) / float(n), v = (float(y) + 0.5f) / float(n);
      const float wu = u + 0.09f * (warp(u, v) - 0.5f) + 0.012f * (jag(u, v) - 0.5f);
      const float wv = v + 0.08f * (warp(v, u) - 0.5f);
      // Two families of slanted lines, u * across +- v * along = integer: periodic in both.
      const float s1 = wu * float(across) + wv * float(along), s2 = wu * float(across) - wv * float(along);
      const float d1 = std::abs(s1 - fround(s1)), d2 = std::abs(s2 - fround(s2));
      const float d = std::min(d1, d2);                 // in line spacings
      const float open = smooth(0.02f, 0.1f + 0.08f * jag(v, u), d);  // 0 in a fissure, of uneven width
      const float g = grain(wu, v), t = tone(u, v);
      const size_t k = size_t(y) * n + x;
      f.height[k] = 0.7f * std::sqrt(open) + 0.12f * g;
      const vec3 top = mix3(ridge, ridge2, t) * (0.9f + 0.14f * g);
      f.paint(k, mix3(fissure, top, open), 0.95f - 0.1f * open);
    }
}

void bark_fibrous(bark_field& f, uint64_t seed) {
  // Cupressus / Thuja / Sequoia: soft bark of long stringy fibres in narrow shreds that wander,
  // merge and part along the trunk; loose shreds lift at their ends, reddish where fresh, greyer
  // where weathered, dark where one shred leaves a gap to the next.
  wandering_lines shreds(26, 1.5f, 7, seed + 1);
  const lattice fibre(160, 8, seed + 2), fibre2(60, 4, seed + 3), tone(5, 3, seed + 4), lift(26, 9, seed + 5);
  const vec3 fresh = srgb_color(222, 166, 132), weathered = srgb_color(196, 186, 174), gap_col = srgb_color(58, 42, 34);
  const int n = f.n;
  for (int y = 0; y < n; ++y) {
    const float v = (float(y) + 0.5f) / float(n);
    shreds.row(v);
    for (int x = 0; x < n; ++x) {
      const float u = (float(x) + 0.5f) / float(n);
      const float d = shreds.distance(u);                // 0 on a gap between shreds
      const float open = smooth(0.03f, 0.22f, d);
      const float fb = 0.6f * fibre(u, v) + 0.4f * fibre2(u, v), l = lift(u, v);
      const size_t k = size_t(y) * n + x;
      f.height[k] = open * (0.45f + 0.3f * l) + 0.35f * fb;
      const vec3 c = mix3(fresh, weathered, smooth(0.3f, 0.8f, 0.5f * tone(u, v) + 0.5f * l)) * (0.72f + 0.4f * fb);
      f.paint(k, mix3(gap_col, c, open), 0.93f - 0.05f * fb);
    }
  }
}

}  // namespace sylva::archetype
