// Leaf and bark archetypes: the procedural texture sets species choose from.
// Plain enums with their option names, shared by the foliage model (sylva_core), the texture
// generator, the renderer and the exporters.
//
// One list each (the X-macros below) makes the enum, the count and the option names, so they
// cannot disagree; every other per-archetype table (the drawing functions and looks in
// render/assets/archetype_textures.cpp, the contact sheet's tints and labels in app/cli/cli_textures.cpp) is
// an unsized array with a static_assert on its length, so a forgotten entry fails to compile.
// Append new archetypes at the end: presets store names, but old files and tests store indices.
#pragma once

namespace sylva {

// X(name, kind): one card per leaf instance; leaf_instance::texture holds the archetype's index.
// kind is leaf (tinted by the leaf colour, turns with the seasons) or fruit (a cone's or fruit's
// card in its own colours, kept through winter; generators/fruits.h places them): the one place
// that says which, read by archetype_is_fruit (render/mesh/season.h).
#define SYLVA_LEAF_ARCHETYPES(X)                                               \
  X(ovate, leaf)         /* simple ovate blade with a serrated edge (birch, beech) */ \
  X(lobed, leaf)         /* oak */                                                    \
  X(palmate, leaf)       /* maple */                                                  \
  X(pinnate, leaf)       /* compound leaf, one card per leaf (ash, rowan) */          \
  X(needles, leaf)       /* pine shoot: fascicles of two fine needles */              \
  X(flat_spray, leaf)    /* spruce and fir shoots: needles on twigs, sky between */  \
  X(scale_spray, leaf)   /* scale-leaf sprays (cypress, thuja) */                     \
  X(palm_frond, leaf)    /* a fan of four palm leaflets: one card per rachis side */ \
  X(twig_cluster, leaf)  /* a broadleaf twig carrying several leaves (cluster cards) */ \
  X(needle_tufts, leaf)  /* true cedar (Cedrus): rosettes of short needles on spurs */ \
  X(lanceolate, leaf)    /* willow shoot: long narrow leaves, finely toothed, long-pointed */ \
  X(beech_spray, leaf)   /* beech: flat two-ranked spray of elliptic, wavy-edged leaves (cluster card) */ \
  X(hazel_spray, leaf)   /* hazel: round, heart-based, doubly toothed leaves on a shoot (cluster card) */ \
  X(poplar_spray, leaf)  /* black poplar: deltoid leaves on long petioles (cluster card) */ \
  X(cone_hanging, fruit) /* spruce: a pendent cylindrical seed cone (fruit card, generators/fruits.h) */ \
  X(cone_upright, fruit) /* fir: an upright barrel-shaped seed cone, bract tips showing (fruit card) */ \
  X(samaras, fruit)      /* maple: a hanging cluster of paired winged fruits (fruit card) */ \
  X(hazelnuts, fruit)    /* hazel: nuts in leafy, toothed husks (fruit card) */ \
  X(cone_ovoid, fruit)   /* pine: an ovoid cone of rhombic scale shields (fruit card) */ \
  X(beechnuts, fruit)    /* beech: bristly cupules opening round their nuts (fruit card) */ \
  X(coconuts, fruit)     /* palm: a bunch of coconuts on a stout branched stalk (fruit card) */ \
  X(maple_spray, leaf)   /* maple: opposite pairs of palmate leaves on a shoot (cluster card) */ \
  X(ash_keys, fruit)     /* ash: a hanging bunch of single-winged keys (fruit card) */ \
  X(cone_barrel, fruit)  /* true cedar (Cedrus): a squat upright barrel, flat-topped (fruit card) */ \
  X(acorns, fruit)       /* pedunculate oak: acorns in scaly cups on a long stalk (fruit card) */ \
  X(horse_chestnut, leaf) /* horse chestnut: seven obovate leaflets fanned from a long petiole */ \
  X(cypress_cones, fruit) /* Italian cypress: three round cones of shield-shaped scales on a twig (fruit card) */ \
  X(birch, leaf)         /* silver birch: triangular-ovate, doubly serrate, long-pointed, slender petiole */

// X(name): bark tiles.
#define SYLVA_BARK_ARCHETYPES(X)                                              \
  X(furrowed) /* deep vertical furrows (oak) */                               \
  X(plated)   /* flat plates between fissures (pine) */                       \
  X(smooth)   /* smooth with lenticel dashes and dark patches (birch) */      \
  X(peeling)  /* long peeling strips */                                       \
  X(ringed)   /* rings of leaf scars (palm) */                                \
  X(mottled)  /* smooth, faintly mottled, resin spots, no lenticels (fir) */        \
  X(fissured) /* a network of shallow fissures between narrow ridges (ash, Cedrus) */ \
  X(fibrous)  /* soft stringy fibres in long shreds (cypress, thuja) */         \
  X(silver)   /* smooth silver-grey, creased, no spots (beech) */

#define SYLVA_ARCHETYPE_ENUM(n, ...) n,
#define SYLVA_ARCHETYPE_NAME(n, ...) #n,
#define SYLVA_ARCHETYPE_ONE(n, ...) +1
#define SYLVA_ARCHETYPE_IS_FRUIT(n, kind) SYLVA_ARCHETYPE_KIND_##kind,
#define SYLVA_ARCHETYPE_KIND_leaf false
#define SYLVA_ARCHETYPE_KIND_fruit true
enum class leaf_archetype : int { SYLVA_LEAF_ARCHETYPES(SYLVA_ARCHETYPE_ENUM) };
inline constexpr int leaf_archetype_count = 0 SYLVA_LEAF_ARCHETYPES(SYLVA_ARCHETYPE_ONE);
inline constexpr const char* leaf_archetype_names[] = {SYLVA_LEAF_ARCHETYPES(SYLVA_ARCHETYPE_NAME) nullptr};
inline constexpr bool leaf_archetype_fruit[] = {SYLVA_LEAF_ARCHETYPES(SYLVA_ARCHETYPE_IS_FRUIT)};

enum class bark_archetype : int { SYLVA_BARK_ARCHETYPES(SYLVA_ARCHETYPE_ENUM) };
inline constexpr int bark_archetype_count = 0 SYLVA_BARK_ARCHETYPES(SYLVA_ARCHETYPE_ONE);
inline constexpr const char* bark_archetype_names[] = {SYLVA_BARK_ARCHETYPES(SYLVA_ARCHETYPE_NAME) nullptr};
#undef SYLVA_ARCHETYPE_ENUM
#undef SYLVA_ARCHETYPE_NAME
#undef SYLVA_ARCHETYPE_ONE
#undef SYLVA_ARCHETYPE_IS_FRUIT
#undef SYLVA_ARCHETYPE_KIND_leaf
#undef SYLVA_ARCHETYPE_KIND_fruit

static_assert(sizeof(leaf_archetype_names) / sizeof(leaf_archetype_names[0]) == leaf_archetype_count + 1);
static_assert(sizeof(leaf_archetype_fruit) / sizeof(leaf_archetype_fruit[0]) == leaf_archetype_count);
static_assert(sizeof(bark_archetype_names) / sizeof(bark_archetype_names[0]) == bark_archetype_count + 1);

}  // namespace sylva
