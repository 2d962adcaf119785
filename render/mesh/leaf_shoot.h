// Needle shoots as geometry (issue 52): the conifer archetypes' cards (pine fascicles, spruce and
// fir sprays, cedar rosettes, and the willow's hanging leafy shoot) become small twig prototypes
// whose needles (or narrow leaves, as flattened spikes) are thin closed
// three-sided spikes set round real shoot axes, so a close look shows needles standing all round
// the shoot (or in two ranks) instead of a flat frond. Like the leaf blades (leaf_blade.h), each
// prototype is made once per species shape and instanced: the viewport draws the coarse prototype
// (shoot_pieces_coarse spikes) in one instanced call, glTF's hero profile writes the fine one once.
//
// A spike has no picture of its own: all of its vertices carry one texture coordinate, the centre
// of an opaque texel of the archetype's picture in the needles' (or the twig's) colour, so the
// card's material draws it unchanged in the viewport, three.js and Blender (a constant coordinate
// has zero derivatives, so every reader samples the full-resolution texel and the spike never
// fades through the mips as a cut-out would).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>

#include "generators/archetypes.h"
#include "render/mesh/leaf_blade.h"

namespace sylva {

// Pine needles, spruce and fir sprays, cedar rosettes (generators/leaves.h archetype_is_needle_shoot)
// and the willow's lanceolate shoot: the archetypes drawn as shoots when blades are on.
bool archetype_is_shoot(leaf_archetype a);
// Bit k set: archetype k is a needle shoot (for the leaf shader).
uint32_t shoot_archetype_mask();

// A small instanced mesh in card units (render/mesh/leaf_blade.h's frame): triangles
// counter-clockwise seen from outside.
struct leaf_mesh {
  std::vector<blade_vertex> vertex;
  std::vector<uint16_t> index;
  bool closed = false;   // every side faces out (a shoot's spikes): no back face needed
};

// Every prototype is this many spikes of 4 vertices (a base triangle round the spike's root and its
// tip) and 3 side triangles, the unused ones collapsed to a point, so that all shoot archetypes
// share one index list and the viewport draws them in one call.
inline constexpr int shoot_pieces_coarse = 28, shoot_pieces_fine = 96;
inline constexpr int shoot_piece_vertices = 4, shoot_piece_triangles = 3;
inline constexpr int shoot_vertices_coarse = shoot_pieces_coarse * shoot_piece_vertices;
inline constexpr int shoot_triangles_coarse = shoot_pieces_coarse * shoot_piece_triangles;

// The picture's colours the spikes sample (texture coordinates of opaque texels' centres): three
// needle tones (light, middle, dark quartiles of the needle-coloured texels) and the twig's.
struct shoot_swatches {
  std::array<glm::vec2, 3> needle{};
  glm::vec2 twig{};
};
// From an RGBA picture; a picture with no opaque texel gives its centre.
shoot_swatches swatches_of(const image& rgba);
// Of archetype a's picture at `size` pixels and `seed` (render/assets/textures.h), made once per key.
const shoot_swatches& archetype_swatches(leaf_archetype a, int size = 512, uint64_t seed = 1);

// The shoot of archetype a with `pieces` spikes (shoot_pieces_coarse or shoot_pieces_fine; others
// are allowed), its needles spread round the shoot by s.needle_spread and its shoot curled by
// s.curl, sampling `sw`. Always exactly pieces * 4 vertices and pieces * 9 indices.
leaf_mesh shoot_prototype(leaf_archetype a, const leaf_blade_shape& s, int pieces, const shoot_swatches& sw);
// The index list shared by every prototype of `pieces` spikes.
std::vector<uint16_t> shoot_indices(int pieces);

}  // namespace sylva
