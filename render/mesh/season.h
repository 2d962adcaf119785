// The season control: how a render_params' season turns into leaf colours, sizes and
// fallen leaves, shared by the viewport's leaf shader and the exporters. Leaves only: no regrow.
#pragma once

#include <cstdint>

#include <glm/vec3.hpp>

#include "render/mesh/mesh.h"
#include "render/mesh/render_params.h"

namespace sylva {

// What the season does to the leaves. Evergreen leaves keep `evergreen_color` at full size; each
// deciduous leaf takes a colour between deciduous_color_a and _b (its own random mix), is drawn at
// `deciduous_scale` of its size, and is on the tree only when its random number is below
// `deciduous_keep` (0 in winter). The default is summer with nothing deciduous: no change.
struct season_look {
  glm::vec3 evergreen_color{0.30f, 0.55f, 0.18f};
  glm::vec3 deciduous_color_a{0.30f, 0.55f, 0.18f}, deciduous_color_b{0.30f, 0.55f, 0.18f};
  uint64_t deciduous_mask = 0;   // bit k: leaves of texture k (leaf_instance::texture: archetypes, then baked cards) are deciduous
  float deciduous_keep = 1.0f;
  float deciduous_scale = 1.0f;
  bool operator==(const season_look&) const = default;
};

// True for the archetypes that stay green through winter: needles, conifer sprays, needle tufts (Cedrus), palm fronds.
bool archetype_is_evergreen(leaf_archetype a);

// True for the cards of cones and fruit (generators/fruits.h): drawn in their own colours (no leaf
// tint, in the viewport and the exports), never deciduous, and left out of the LOD cards.
bool archetype_is_fruit(leaf_archetype a);
// Bit k set where archetype k is a fruit's (the leaf shader's u_fruit).
uint32_t fruit_archetype_mask();

// Whether leaves of texture k (leaf_instance::texture) follow the deciduous colours, size and fall.
inline bool season_deciduous(const season_look& s, int texture) {
  return texture >= 0 && texture < 64 && ((s.deciduous_mask >> texture) & 1u) != 0;
}

// The look of `rp.season` for this preset's leaf colour, autumn colours and leaf habit. An
// out-of-range season (a corrupt value) is clamped to the nearest one.
season_look season_leaf_look(const render_params& rp);

// The per-leaf random numbers in [0, 1) the shader also computes from gl_InstanceID (the leaf's
// index in tree_mesh::leaves): `salt` 0 decides whether the leaf is on the tree, 1 its colour mix.
float season_leaf_random(uint32_t leaf_index, uint32_t salt);

// The look with the baked cluster cards of a LOD level (render/mesh/lod_cards.h) added to the deciduous
// mask where the leaves a card was baked from are deciduous (`cards` may be null: no change). The
// viewport's leaf shader and apply_season use the same rule, so a winter LOD drops its broadleaf
// cards as LOD0 drops its leaves.
season_look with_card_seasons(season_look s, const baked_card_textures* cards);

// True when the look changes which leaves exist or their size (then exports need apply_season).
bool season_changes_leaves(const season_look& s);

// The mesh with the season's leaves: fallen deciduous leaves removed (leaf_end recounted, so
// scrubbing still works) and the rest scaled. Bark is copied unchanged.
tree_mesh apply_season(const tree_mesh& m, const season_look& s);

}  // namespace sylva
