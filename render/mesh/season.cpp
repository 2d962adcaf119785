// Season looks (render/mesh/season.h): colours, sizes and fallen leaves for spring, summer, autumn, winter.
#include "render/mesh/season.h"

#include "render/mesh/lod_cards.h"

#include <algorithm>

#include <glm/common.hpp>

namespace sylva {

bool archetype_is_evergreen(leaf_archetype a) {
  return a == leaf_archetype::needles || a == leaf_archetype::flat_spray || a == leaf_archetype::scale_spray ||
         a == leaf_archetype::palm_frond || a == leaf_archetype::needle_tufts;
}

bool archetype_is_fruit(leaf_archetype a) {
  const int k = int(a);
  return k >= 0 && k < leaf_archetype_count && leaf_archetype_fruit[k];   // the kind in generators/archetypes.h
}

uint32_t fruit_archetype_mask() {
  static_assert(leaf_archetype_count <= 32, "the leaf shader's u_fruit holds one bit per archetype");
  static const uint32_t mask = [] {   // made once: the renderer sets it with every frame's uniforms
    uint32_t m = 0;
    for (int k = 0; k < leaf_archetype_count; ++k)
      if (archetype_is_fruit(leaf_archetype(k))) m |= 1u << k;
    return m;
  }();
  return mask;
}

season_look season_leaf_look(const render_params& rp) {
  season_look s;
  const glm::vec3 summer = rp.leaf_color;
  s.evergreen_color = summer;
  s.deciduous_color_a = s.deciduous_color_b = summer;
  for (int k = 0; k < leaf_archetype_count; ++k) {
    const bool evergreen = rp.habit == leaf_habit::evergreen || archetype_is_fruit(leaf_archetype(k)) ||
                           (rp.habit != leaf_habit::deciduous && archetype_is_evergreen(leaf_archetype(k)));
    if (!evergreen) s.deciduous_mask |= uint64_t(1) << k;
  }
  switch (leaf_season(std::clamp(int(rp.season), 0, 3))) {
    case leaf_season::spring: {
      // New leaves are paler and yellower (less chlorophyll, more carotenoid showing) and not yet
      // full size: a fresh yellow-green between the summer tint and a bright one.
      const glm::vec3 fresh{0.42f, 0.66f, 0.10f};
      s.deciduous_color_a = glm::mix(summer, fresh, 0.55f);
      s.deciduous_color_b = glm::mix(summer, fresh * glm::vec3(1.1f, 1.05f, 0.8f), 0.75f);
      s.deciduous_keep = 0.85f;   // some buds have not broken yet
      s.deciduous_scale = 0.7f;
      break;
    }
    case leaf_season::summer: break;
    case leaf_season::autumn:
      s.deciduous_color_a = rp.autumn_color;
      s.deciduous_color_b = rp.autumn_color_2;
      s.deciduous_keep = 0.75f;   // the first leaves are down
      break;
    case leaf_season::winter:
      s.deciduous_keep = 0.0f;
      s.evergreen_color = summer * 0.85f;   // winter needles darken a little
      break;
  }
  return s;
}

float season_leaf_random(uint32_t leaf_index, uint32_t salt) {
  // lowbias32 (C. Wellons' integer hash); the leaf shader runs the same lines on gl_InstanceID.
  uint32_t x = leaf_index ^ (salt * 0x9e3779b9u);
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return float(x >> 8) * (1.0f / 16777216.0f);
}

bool season_changes_leaves(const season_look& s) {
  return s.deciduous_mask != 0 && (s.deciduous_keep < 1.0f || s.deciduous_scale != 1.0f);
}

season_look with_card_seasons(season_look s, const baked_card_textures* cards) {
  if (!cards) return s;
  const season_look archetypes = s;
  for (size_t k = 0; k < cards->source.size() && leaf_archetype_count + k < 64; ++k)
    if (season_deciduous(archetypes, cards->source[k])) s.deciduous_mask |= uint64_t(1) << (leaf_archetype_count + k);
  return s;
}

tree_mesh apply_season(const tree_mesh& m, const season_look& look) {
  const season_look s = with_card_seasons(look, m.cards.get());
  tree_mesh out = m;
  if (!season_changes_leaves(s)) return out;
  out.leaves.clear();
  std::vector<uint32_t> kept_before(m.leaves.size() + 1, 0);   // leaves kept among the first i
  for (size_t i = 0; i < m.leaves.size(); ++i) {
    leaf_instance l = m.leaves[i];
    const bool deciduous = season_deciduous(s, l.texture);
    kept_before[i] = uint32_t(out.leaves.size());
    if (deciduous) {
      if (season_leaf_random(uint32_t(i), 0) >= s.deciduous_keep) continue;
      l.size *= s.deciduous_scale;
    }
    out.leaves.push_back(l);
  }
  kept_before[m.leaves.size()] = uint32_t(out.leaves.size());
  for (uint32_t& e : out.leaf_end) e = kept_before[std::min<size_t>(e, m.leaves.size())];
  return out;
}

}  // namespace sylva
