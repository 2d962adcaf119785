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

// X(name): one card per leaf instance; leaf_instance::texture holds the archetype's index.
#define SYLVA_LEAF_ARCHETYPES(X)                                               \
  X(ovate)        /* simple ovate blade with a serrated edge (birch, beech) */ \
  X(lobed)        /* oak */                                                    \
  X(palmate)      /* maple */                                                  \
  X(pinnate)      /* compound leaf, one card per leaf (ash, rowan) */          \
  X(needles)      /* pine shoot: fascicles of two fine needles */              \
  X(flat_spray)   /* spruce and fir shoots: needles on twigs, sky between */  \
  X(scale_spray)  /* scale-leaf sprays (cypress, thuja) */                     \
  X(palm_frond)   /* a fan of four palm leaflets: one card per rachis side */ \
  X(twig_cluster) /* a broadleaf twig carrying several leaves (cluster cards) */ \
  X(needle_tufts) /* true cedar (Cedrus): rosettes of short needles on spurs */ \
  X(lanceolate)   /* willow shoot: long narrow leaves, finely toothed, long-pointed */ \
  X(beech_spray)  /* beech: flat two-ranked spray of elliptic, wavy-edged leaves (cluster card) */ \
  X(hazel_spray)  /* hazel: round, heart-based, doubly toothed leaves on a shoot (cluster card) */ \
  X(poplar_spray) /* black poplar: deltoid leaves on long petioles (cluster card) */ \
  X(cone_hanging) /* spruce: a pendent cylindrical seed cone (fruit card, generators/fruits.h) */ \
  X(cone_upright) /* fir: an upright barrel-shaped seed cone, bract tips showing (fruit card) */ \
  X(samaras)      /* maple: a hanging cluster of paired winged fruits (fruit card) */ \
  X(hazelnuts)    /* hazel: nuts in leafy, toothed husks (fruit card) */ \
  X(cone_ovoid)   /* pine: an ovoid cone of rhombic scale shields (fruit card) */ \
  X(beechnuts)    /* beech: bristly cupules opening round their nuts (fruit card) */ \
  X(coconuts)     /* palm: a bunch of coconuts on a stout branched stalk (fruit card) */ \
  X(maple_spray)  /* maple: opposite pairs of palmate leaves on a shoot (cluster card) */ \
  X(ash_keys)     /* ash: a hanging bunch of single-winged keys (fruit card) */ \
  X(cone_barrel)  /* true cedar (Cedrus): a squat upright barrel, flat-topped (fruit card) */ \
  X(acorns)       /* pedunculate oak: acorns in scaly cups on a long stalk (fruit card) */

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

#define SYLVA_ARCHETYPE_ENUM(n) n,
#define SYLVA_ARCHETYPE_NAME(n) #n,
#define SYLVA_ARCHETYPE_ONE(n) +1
enum class leaf_archetype : int { SYLVA_LEAF_ARCHETYPES(SYLVA_ARCHETYPE_ENUM) };
inline constexpr int leaf_archetype_count = 0 SYLVA_LEAF_ARCHETYPES(SYLVA_ARCHETYPE_ONE);
inline constexpr const char* leaf_archetype_names[] = {SYLVA_LEAF_ARCHETYPES(SYLVA_ARCHETYPE_NAME) nullptr};

enum class bark_archetype : int { SYLVA_BARK_ARCHETYPES(SYLVA_ARCHETYPE_ENUM) };
inline constexpr int bark_archetype_count = 0 SYLVA_BARK_ARCHETYPES(SYLVA_ARCHETYPE_ONE);
inline constexpr const char* bark_archetype_names[] = {SYLVA_BARK_ARCHETYPES(SYLVA_ARCHETYPE_NAME) nullptr};
#undef SYLVA_ARCHETYPE_ENUM
#undef SYLVA_ARCHETYPE_NAME
#undef SYLVA_ARCHETYPE_ONE

static_assert(sizeof(leaf_archetype_names) / sizeof(leaf_archetype_names[0]) == leaf_archetype_count + 1);
static_assert(sizeof(bark_archetype_names) / sizeof(bark_archetype_names[0]) == bark_archetype_count + 1);

}  // namespace sylva
