// Leaf blades as geometry (issue 52): each leaf archetype's card becomes a small grid mesh cut to
// the outline of its picture, folded along the midrib and curled along its length, so a close look
// shows a bent blade with depth instead of a flat cut-out square. The viewport and the baked exports
// draw the coarse grid (3 x 2 cells, 12 triangles: the fine grid's every second row and column), the
// viewport in one instanced call whose vertices are looked up per archetype; glTF's instanced
// prototype, written once, is the fine grid (6 x 4, 48 triangles). Fruit, a LOD level's baked cards
// and the impostor keep the flat card (the full-card outline, unfolded).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "generators/archetypes.h"

namespace sylva {

struct image;   // render/assets/textures.h

// The species' blade shape, from leaf_params (generators/leaves.h) via mesh_tree.
struct leaf_blade_shape {
  bool on = false;    // false: every leaf is the flat card
  float fold = 0;     // degrees each half of the blade rises about the midrib (a V section)
  float curl = 0;     // degrees the blade turns down over its length (negative: up)
  float needle_spread = 360;   // needle shoots (leaf_shoot.h): degrees round the shoot the needles fill
  bool operator==(const leaf_blade_shape&) const = default;
};

// The grid: blade_rows intervals from the petiole to the tip, blade_columns across (the middle
// vertex column is the midrib). Vertex (r, c) is r * (blade_columns + 1) + c.
inline constexpr int blade_rows = 6, blade_columns = 4;
inline constexpr int blade_row_vertices = blade_columns + 1;
inline constexpr int blade_vertices = (blade_rows + 1) * blade_row_vertices;
inline constexpr int blade_triangles = 2 * blade_rows * blade_columns;

// The picture's outline in card units (x across, -0.5..0.5; y from the petiole, 0..1): the blade's
// lowest and highest covered heights, and at each vertex row the leftmost and rightmost covered x of
// the two bands of image rows beside it, padded by a texel, so the straight edges between two rows
// never cut into the picture. The midrib column stays at x = 0.
struct blade_outline {
  float y0 = 0, y1 = 1;
  std::array<float, blade_rows + 1> left{}, right{};
};
blade_outline full_card_outline();
// From an RGBA picture (rows top = tip to bottom = petiole), covered where alpha >= cutoff (0..1).
// A picture with no covered texel gives the full card.
blade_outline outline_of(const image& rgba, float cutoff = 0.5f);
// The outline of archetype a's 512 px picture (render/assets/textures.h), made once per process.
const blade_outline& archetype_outline(leaf_archetype a);

struct blade_vertex {
  glm::vec3 position;   // in card units: multiply by the leaf's size, then turn by its orientation
  glm::vec3 normal;     // unit, the upper (+Z) side
  glm::vec2 uv;         // the picture's coordinates of the flat card (v = 0 at the tip's edge)
};

// The grid of `o` with `s`'s fold and curl (flat when !s.on). Normals from the grid's neighbours.
std::array<blade_vertex, blade_vertices> blade_prototype(const blade_outline& o, const leaf_blade_shape& s);
// Triangles of the grid, counter-clockwise seen from +Z: 3 * blade_triangles vertex numbers.
const std::array<uint16_t, 3 * blade_triangles>& blade_indices();

// The renderer's table: one coarse grid per leaf archetype, then the flat card (fruit, baked cards,
// the impostor, and every leaf when the user's picture replaces the archetypes).
inline constexpr int blade_prototypes = leaf_archetype_count + 1;

// The coarse grid: every second vertex row and column of the fine one (4 rows of 3: the edges and
// the midrib at the petiole, a third, two thirds and the tip), 12 vertices and 12 triangles a face,
// so a blade costs six times a card's two triangles, not the fine grid's 48. On llvmpipe the fine
// grid made species_oak's frame 3.4 times slower (docs/design/03-foliage.md).
inline constexpr int coarse_blade_rows = 3, coarse_blade_columns = 2;
inline constexpr int coarse_blade_vertices = (coarse_blade_rows + 1) * (coarse_blade_columns + 1);
inline constexpr int coarse_blade_triangles = 2 * coarse_blade_rows * coarse_blade_columns;
std::array<blade_vertex, coarse_blade_vertices> coarse_blade(const blade_outline& o, const leaf_blade_shape& s);
const std::array<uint16_t, 3 * coarse_blade_triangles>& coarse_blade_indices();

}  // namespace sylva
