// Leaf and bark archetypes: the procedural texture sets species choose from (issue 11).
// Plain enums with their option names, shared by the foliage model (sylva_core), the texture
// generator, the renderer and the exporters.
#pragma once

namespace sylva {

// One card per leaf instance; leaf_instance::texture holds the archetype's index.
enum class leaf_archetype : int {
  ovate = 0,      // simple ovate blade with a serrated edge (birch, beech, aspen)
  lobed,          // oak
  palmate,        // maple
  pinnate,        // compound leaf, one card per leaf (ash, rowan)
  needles,        // pine needle fascicles: bundles of 2-5 long needles
  flat_spray,     // flat conifer sprays (spruce, fir)
  scale_spray,    // scale-leaf sprays (cypress, cedar)
  palm_frond,     // leaflets along a curved rachis
  twig_cluster,   // a broadleaf twig carrying several leaves (cluster cards)
};
inline constexpr int leaf_archetype_count = 9;
inline constexpr const char* leaf_archetype_names[] = {
    "ovate", "lobed", "palmate", "pinnate", "needles", "flat_spray", "scale_spray", "palm_frond", "twig_cluster", nullptr};

enum class bark_archetype : int {
  furrowed = 0,   // deep vertical furrows (oak)
  plated,         // flat plates between fissures (pine)
  smooth,         // smooth with lenticels and dark patches (birch white, beech grey: the tint decides)
  peeling,        // long peeling strips (cedar)
  ringed,         // rings of leaf scars (palm)
};
inline constexpr int bark_archetype_count = 5;
inline constexpr const char* bark_archetype_names[] = {"furrowed", "plated", "smooth", "peeling", "ringed", nullptr};

}  // namespace sylva
