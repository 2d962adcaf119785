// Leaf blades as geometry (render/mesh/leaf_blade.h): grids cut to their pictures' outlines that
// never cut into a picture, the fold and the curl, and the exporters' coarser grid.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "render/assets/textures.h"
#include "render/mesh/leaf_blade.h"
#include "render/mesh/season.h"

using namespace sylva;

namespace {

// The flat grid's half widths at height y (card units), interpolated between its vertex rows as the
// triangles are; false when y lies outside the blade.
template <size_t N>
bool span_at(const std::array<blade_vertex, N>& g, int rows, int columns, float y, float& left, float& right) {
  const int stride = columns + 1;
  for (int r = 0; r < rows; ++r) {
    const blade_vertex &a0 = g[size_t(r * stride)], &b0 = g[size_t((r + 1) * stride)];
    const blade_vertex &a1 = g[size_t(r * stride + columns)], &b1 = g[size_t((r + 1) * stride + columns)];
    const float ya = a0.position.y, yb = b0.position.y;
    if (y < ya - 1e-6f || y > yb + 1e-6f) continue;
    const float t = yb > ya ? std::clamp((y - ya) / (yb - ya), 0.0f, 1.0f) : 0.0f;
    left = a0.position.x + t * (b0.position.x - a0.position.x);
    right = a1.position.x + t * (b1.position.x - a1.position.x);
    return true;
  }
  return false;
}

// Every texel of the picture at or above the cutoff lies inside the flat grid (texel centres).
template <size_t N>
size_t texels_outside(const image& im, const std::array<blade_vertex, N>& g, int rows, int columns) {
  size_t outside = 0;
  for (int j = 0; j < im.height; ++j)
    for (int x = 0; x < im.width; ++x) {
      if (im.pixels[(size_t(j) * size_t(im.width) + size_t(x)) * 4 + 3] < 128) continue;
      const float cx = (float(x) + 0.5f) / float(im.width) - 0.5f, cy = 1.0f - (float(j) + 0.5f) / float(im.height);
      float l = 0, r = 0;
      if (!span_at(g, rows, columns, cy, l, r) || cx < l - 1e-5f || cx > r + 1e-5f) ++outside;
    }
  return outside;
}

// Area of the flat grid in card units (the card is 1).
template <size_t N>
float flat_area(const std::array<blade_vertex, N>& g, int rows, int columns) {
  float area = 0;
  for (int r = 0; r < rows; ++r) {
    const float h = g[size_t((r + 1) * (columns + 1))].position.y - g[size_t(r * (columns + 1))].position.y;
    const float w0 = g[size_t(r * (columns + 1) + columns)].position.x - g[size_t(r * (columns + 1))].position.x;
    const float w1 = g[size_t((r + 1) * (columns + 1) + columns)].position.x - g[size_t((r + 1) * (columns + 1))].position.x;
    area += 0.5f * (w0 + w1) * h;
  }
  return area;
}

}  // namespace

// The outline of every leaf archetype's picture holds every covered texel, in the viewport's grid
// and in the exporters' coarser one, and a simple blade is cut well inside its card.
TEST(LeafBlade, OutlinesHoldEveryCoveredTexelOfEveryArchetype) {
  const leaf_blade_shape flat;
  for (int k = 0; k < leaf_archetype_count; ++k) {
    if (archetype_is_fruit(leaf_archetype(k))) continue;
    SCOPED_TRACE(leaf_archetype_names[k]);
    const image& im = leaf_archetype_textures(leaf_archetype(k), 512).color;
    const blade_outline& o = archetype_outline(leaf_archetype(k));
    EXPECT_EQ(texels_outside(im, blade_prototype(o, flat), blade_rows, blade_columns), size_t(0));
    EXPECT_EQ(texels_outside(im, coarse_blade(o, flat), coarse_blade_rows, coarse_blade_columns), size_t(0));
    for (int r = 0; r <= blade_rows; ++r) {
      EXPECT_LT(o.left[size_t(r)], 0.0f);
      EXPECT_GT(o.right[size_t(r)], 0.0f);
    }
  }
  // Single blades take well under the card: the flat square's fringe is gone.
  for (leaf_archetype a : {leaf_archetype::ovate, leaf_archetype::lanceolate, leaf_archetype::lobed}) {
    SCOPED_TRACE(leaf_archetype_names[int(a)]);
    EXPECT_LT(flat_area(blade_prototype(archetype_outline(a), flat), blade_rows, blade_columns), 0.75f);
  }
}

// A picture with nothing covered, or not RGBA, keeps the whole card; a drawn diamond is followed.
TEST(LeafBlade, OutlineOfEmptyAndDrawnPictures) {
  image empty{16, 16, 4, std::vector<uint8_t>(16 * 16 * 4, 0)};
  const blade_outline e = outline_of(empty);
  EXPECT_EQ(e.left[0], -0.5f);
  EXPECT_EQ(e.right[size_t(blade_rows)], 0.5f);
  EXPECT_EQ(outline_of(image{4, 4, 3, std::vector<uint8_t>(48, 255)}).right[0], 0.5f);
  // A diamond: widest at mid height, narrow at both ends, between rows 16 and 47 of 64.
  image d{64, 64, 4, std::vector<uint8_t>(64 * 64 * 4, 0)};
  for (int j = 16; j < 48; ++j)
    for (int x = 0; x < 64; ++x)
      if (std::abs(x - 32 + 0.5f) + std::abs(j - 32 + 0.5f) < 16) d.pixels[(size_t(j) * 64 + size_t(x)) * 4 + 3] = 255;
  const blade_outline o = outline_of(d);
  EXPECT_NEAR(o.y0, 0.25f, 0.03f);
  EXPECT_NEAR(o.y1, 0.75f, 0.03f);
  const float mid = o.right[size_t(blade_rows / 2)] - o.left[size_t(blade_rows / 2)];
  EXPECT_NEAR(mid, 0.5f, 0.06f);
  EXPECT_LT(o.right[0] - o.left[0], mid / 2);
  EXPECT_LT(o.right[size_t(blade_rows)] - o.left[size_t(blade_rows)], mid / 2);
  EXPECT_EQ(texels_outside(d, blade_prototype(o, {}), blade_rows, blade_columns), size_t(0));
}

// The fold lifts each half about the midrib by |x| tan(fold); the curl bends the midrib along an arc
// of the blade's own length, the tip down for a positive angle; normals are unit and face +Z-ward.
TEST(LeafBlade, FoldAndCurl) {
  const blade_outline o = full_card_outline();
  const auto flat = blade_prototype(o, leaf_blade_shape{true, 0, 0});
  for (const blade_vertex& v : flat) {
    EXPECT_FLOAT_EQ(v.position.z, 0.0f);
    EXPECT_NEAR(v.normal.z, 1.0f, 1e-6f);
    EXPECT_NEAR(v.uv.x, v.position.x + 0.5f, 1e-6f);
    EXPECT_NEAR(v.uv.y, 1.0f - v.position.y, 1e-6f);
  }
  const auto folded = blade_prototype(o, leaf_blade_shape{true, 30, 0});
  for (const blade_vertex& v : folded) EXPECT_NEAR(v.position.z, std::abs(v.position.x) * std::tan(glm::radians(30.0f)), 1e-5f);
  // Off: no fold or curl whatever the angles say.
  for (const blade_vertex& v : blade_prototype(o, leaf_blade_shape{false, 30, 40})) EXPECT_FLOAT_EQ(v.position.z, 0.0f);
  const auto curled = blade_prototype(o, leaf_blade_shape{true, 0, 60});
  const blade_vertex& tip = curled[size_t(blade_rows * blade_row_vertices + blade_columns / 2)];
  EXPECT_LT(tip.position.z, -0.2f);
  EXPECT_LT(tip.position.y, 1.0f);
  float midrib = 0;
  for (int r = 0; r < blade_rows; ++r)
    midrib += glm::length(curled[size_t((r + 1) * blade_row_vertices + 2)].position - curled[size_t(r * blade_row_vertices + 2)].position);
  EXPECT_NEAR(midrib, 1.0f, 0.01f);   // chords of the arc: a little under its length
  EXPECT_LE(midrib, 1.0f);
  // The tip's direction has turned by the curl: its row runs at 60 degrees below the base's.
  const glm::vec3 last = tip.position - curled[size_t((blade_rows - 1) * blade_row_vertices + 2)].position;
  EXPECT_NEAR(glm::degrees(std::atan2(-last.z, last.y)), 60.0f * (1.0f - 0.5f / blade_rows), 1.0f);
  for (const auto* g : {&folded, &curled})
    for (const blade_vertex& v : *g) {
      EXPECT_NEAR(glm::length(v.normal), 1.0f, 1e-5f);
      EXPECT_GT(v.normal.z, 0.3f);
    }
  // Every triangle of the grid faces +Z-ward on the flat blade (counter-clockwise from +Z).
  const auto& ix = blade_indices();
  for (size_t t = 0; t < ix.size(); t += 3) {
    const glm::vec3 a = flat[ix[t]].position, b = flat[ix[t + 1]].position, c = flat[ix[t + 2]].position;
    EXPECT_GT(glm::cross(b - a, c - a).z, 0.0f);
  }
  const auto& ex = coarse_blade_indices();
  const auto coarse = coarse_blade(o, {});
  for (size_t t = 0; t < ex.size(); t += 3) {
    const glm::vec3 a = coarse[ex[t]].position, b = coarse[ex[t + 1]].position, c = coarse[ex[t + 2]].position;
    EXPECT_GT(glm::cross(b - a, c - a).z, 0.0f);
  }
}
