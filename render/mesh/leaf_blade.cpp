#include "render/mesh/leaf_blade.h"

#include <algorithm>
#include <cmath>
#include <mutex>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "render/assets/textures.h"

namespace sylva {

namespace {

constexpr float min_half_width = 0.004f;   // a row with nothing covered keeps a sliver round the midrib

void keep_midrib_inside(blade_outline& o) {
  for (int r = 0; r <= blade_rows; ++r) {
    o.left[size_t(r)] = std::clamp(std::min(o.left[size_t(r)], -min_half_width), -0.5f, 0.0f);
    o.right[size_t(r)] = std::clamp(std::max(o.right[size_t(r)], min_half_width), 0.0f, 0.5f);
  }
}

}  // namespace

blade_outline full_card_outline() {
  blade_outline o;
  o.left.fill(-0.5f);
  o.right.fill(0.5f);
  return o;
}

blade_outline outline_of(const image& im, float cutoff) {
  const int w = im.width, h = im.height, ch = im.channels;
  if (w <= 0 || h <= 0 || ch != 4 || im.pixels.size() < size_t(w) * size_t(h) * 4) return full_card_outline();
  const int limit = int(std::lround(std::clamp(cutoff, 0.0f, 1.0f) * 255.0f));
  auto covered = [&](int x, int j) { return int(im.pixels[(size_t(j) * size_t(w) + size_t(x)) * 4 + 3]) >= limit; };
  // Per image row: the covered span in card x, or none. Row j (0 at the top) lies at height 1 - (j + 0.5) / h.
  std::vector<float> lo(size_t(h), 1.0f), hi(size_t(h), -1.0f);
  int top = h, bottom = -1;
  for (int j = 0; j < h; ++j) {
    int a = -1, b = -1;
    for (int x = 0; x < w; ++x)
      if (covered(x, j)) {
        if (a < 0) a = x;
        b = x;
      }
    if (a < 0) continue;
    lo[size_t(j)] = float(a) / float(w) - 0.5f;
    hi[size_t(j)] = float(b + 1) / float(w) - 0.5f;
    top = std::min(top, j), bottom = std::max(bottom, j);
  }
  if (bottom < 0) return full_card_outline();
  const float texel = 1.0f / float(std::max(w, h));
  blade_outline o;
  o.y0 = std::max(0.0f, 1.0f - float(bottom + 1) / float(h) - texel);
  o.y1 = std::min(1.0f, 1.0f - float(top) / float(h) + texel);
  // Each band between two vertex rows: the widest covered span of its image rows.
  std::array<float, blade_rows> band_lo, band_hi;
  band_lo.fill(0.0f), band_hi.fill(0.0f);
  for (int j = top; j <= bottom; ++j) {
    if (hi[size_t(j)] < lo[size_t(j)]) continue;
    const float y = 1.0f - (float(j) + 0.5f) / float(h);
    const int b = std::clamp(int((y - o.y0) / std::max(o.y1 - o.y0, 1e-6f) * float(blade_rows)), 0, blade_rows - 1);
    band_lo[size_t(b)] = std::min(band_lo[size_t(b)], lo[size_t(j)]);
    band_hi[size_t(b)] = std::max(band_hi[size_t(b)], hi[size_t(j)]);
  }
  for (int r = 0; r <= blade_rows; ++r) {
    const int below = std::max(r - 1, 0), above = std::min(r, blade_rows - 1);
    o.left[size_t(r)] = std::min(band_lo[size_t(below)], band_lo[size_t(above)]) - texel;
    o.right[size_t(r)] = std::max(band_hi[size_t(below)], band_hi[size_t(above)]) + texel;
  }
  keep_midrib_inside(o);
  return o;
}

const blade_outline& archetype_outline(leaf_archetype a) {
  static std::array<blade_outline, leaf_archetype_count> outlines;
  static std::array<std::once_flag, leaf_archetype_count> made;
  const size_t k = size_t(std::clamp(int(a), 0, leaf_archetype_count - 1));
  std::call_once(made[k], [&] { outlines[k] = outline_of(leaf_archetype_textures(leaf_archetype(k), 512).color); });
  return outlines[k];
}

std::array<blade_vertex, blade_vertices> blade_prototype(const blade_outline& o, const leaf_blade_shape& s) {
  std::array<blade_vertex, blade_vertices> out{};
  const float fold = s.on ? std::tan(glm::radians(std::clamp(s.fold, 0.0f, 60.0f))) : 0.0f;
  const float length = std::max(o.y1 - o.y0, 1e-4f);
  // The midrib bends along a circular arc of the blade's length through the curl angle (constant
  // curvature k = angle / length), starting at the petiole's end; the section (x, fold height) is
  // carried in the arc's frame.
  const float angle = s.on ? glm::radians(std::clamp(s.curl, -120.0f, 120.0f)) : 0.0f;
  const float k = angle / length;
  for (int r = 0; r <= blade_rows; ++r) {
    const float y = o.y0 + length * float(r) / float(blade_rows);
    const float arc = y - o.y0, phi = k * arc;
    // Midrib point in (y, z) and the section's up direction, turned by phi about the card's x.
    const float my = std::abs(k) > 1e-5f ? o.y0 + std::sin(phi) / k : y;
    const float mz = std::abs(k) > 1e-5f ? -(1.0f - std::cos(phi)) / k : 0.0f;
    const glm::vec2 up(std::sin(phi), std::cos(phi));
    for (int c = 0; c <= blade_columns; ++c) {
      const float t = float(c) / float(blade_columns) * 2.0f - 1.0f;   // -1 left edge, 0 midrib, 1 right edge
      const float x = t < 0 ? -t * o.left[size_t(r)] : t * o.right[size_t(r)];
      const float lift = std::abs(x) * fold;
      blade_vertex& v = out[size_t(r * blade_row_vertices + c)];
      v.position = glm::vec3(x, my + lift * up.x, mz + lift * up.y);
      v.uv = glm::vec2(x + 0.5f, 1.0f - y);
    }
  }
  // Normals: across (next column minus previous) x along (next row minus previous), the +Z side.
  for (int r = 0; r <= blade_rows; ++r)
    for (int c = 0; c <= blade_columns; ++c) {
      auto at = [&](int rr, int cc) {
        return out[size_t(std::clamp(rr, 0, blade_rows) * blade_row_vertices + std::clamp(cc, 0, blade_columns))].position;
      };
      const glm::vec3 across = at(r, c + 1) - at(r, c - 1), along = at(r + 1, c) - at(r - 1, c);
      glm::vec3 n = glm::cross(across, along);
      const float len = glm::length(n);
      out[size_t(r * blade_row_vertices + c)].normal = len > 1e-9f ? n / len : glm::vec3(0, 0, 1);
    }
  return out;
}

namespace {

template <int Rows, int Columns>
std::array<uint16_t, 6 * Rows * Columns> grid_indices() {
  std::array<uint16_t, 6 * Rows * Columns> out{};
  size_t k = 0;
  for (int r = 0; r < Rows; ++r)
    for (int c = 0; c < Columns; ++c) {
      const auto v = [&](int rr, int cc) { return uint16_t(rr * (Columns + 1) + cc); };
      // Counter-clockwise seen from +Z: x right, y up.
      for (uint16_t i : {v(r, c), v(r, c + 1), v(r + 1, c + 1), v(r, c), v(r + 1, c + 1), v(r + 1, c)}) out[k++] = i;
    }
  return out;
}

}  // namespace

const std::array<uint16_t, 3 * blade_triangles>& blade_indices() {
  static const auto indices = grid_indices<blade_rows, blade_columns>();
  return indices;
}

std::array<blade_vertex, coarse_blade_vertices> coarse_blade(const blade_outline& o, const leaf_blade_shape& s) {
  static_assert(blade_rows == 2 * coarse_blade_rows && blade_columns == 2 * coarse_blade_columns);
  // Each kept row widened to its skipped neighbours' spans, so the longer straight edges still
  // never cut into the picture; then the same fold and curl.
  blade_outline wide = o;
  for (int r = 0; r <= blade_rows; r += 2)
    for (int d : {-1, 1}) {
      const int n = std::clamp(r + d, 0, blade_rows);
      wide.left[size_t(r)] = std::min(wide.left[size_t(r)], o.left[size_t(n)]);
      wide.right[size_t(r)] = std::max(wide.right[size_t(r)], o.right[size_t(n)]);
    }
  const auto full = blade_prototype(wide, s);
  std::array<blade_vertex, coarse_blade_vertices> out{};
  for (int r = 0; r <= coarse_blade_rows; ++r)
    for (int c = 0; c <= coarse_blade_columns; ++c)
      out[size_t(r * (coarse_blade_columns + 1) + c)] = full[size_t(2 * r * blade_row_vertices + 2 * c)];
  return out;
}

const std::array<uint16_t, 3 * coarse_blade_triangles>& coarse_blade_indices() {
  static const auto indices = grid_indices<coarse_blade_rows, coarse_blade_columns>();
  return indices;
}

}  // namespace sylva
