// Cluster cards baked from the tree's own leaves (LOD silhouette): a merged card of a LOD
// level shows, in its alpha, the pattern of real leaves (with their gaps) projected orthographically
// onto its plane, instead of a generic cluster texture scaled to the same area.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "render/mesh/mesh.h"
#include "render/assets/textures.h"

namespace sylva {

// Edge in pixels of a baked card texture; the renderer scales it to its 512 px leaf layers.
inline constexpr int card_texture_size = 128;
// Cards per LOD level and in all: leaf_instance::texture = leaf_archetype_count + k stays below 32,
// the width of the season's deciduous mask (render/mesh/season.h).
inline constexpr int cards_per_level = 6;
inline constexpr int max_baked_cards = 3 * cards_per_level;

struct baked_card_textures {
  std::vector<leaf_texture_set> sets;   // card k: colour RGBA (sRGB, untinted), normal RGB, thickness RGB
  std::vector<uint8_t> source;          // card k's leaves' archetype (most of them): season and export tint
  std::vector<float> opaque;            // card k's opaque share (texels with alpha >= 128)
};

// Share of an RGBA image's texels with alpha >= 128 (the renderer's cut-out); at least 0.01.
float opaque_share(const image& rgba);
// opaque_share of a leaf archetype's colour texture at the renderer's 512 px, measured once.
float archetype_opaque_share(int archetype);

// A card standing for leaves: the plane of one of them, a square spanning their extent on it.
struct card_fit {
  glm::vec4 orientation{0, 0, 0, 1};
  glm::vec3 position{0};   // petiole point: the bottom edge's centre (skeleton.h's leaf frame)
  float size = 0;          // side (metres)
  float coverage = 0;      // expected share of the square the leaves cover (Poisson overlap estimate)
};

// The card for leaves[0..n) with the given orientation: a square centred on their projected extent.
card_fit fit_card(const leaf_instance* leaves, size_t n, const glm::vec4& orientation);

// Rasterises leaves[0..n) (their archetype textures, alpha cut-out at 128) orthographically along
// the card's normal onto the card's square: colour, alpha and the leaves' normals in the card's
// tangent frame. With shape.on each leaf is its archetype's coarse blade or needle shoot, bent as
// the viewport draws it (render/mesh/leaf_blade.h, leaf_shoot.h); otherwise its flat card. O(texels
// the leaves cover).
leaf_texture_set bake_card(const leaf_instance* leaves, size_t n, const card_fit& c, int size = card_texture_size,
                           const leaf_blade_shape& shape = {});

}  // namespace sylva
