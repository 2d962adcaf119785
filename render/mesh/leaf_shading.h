// Leaves shaded as a volume: a crown of cards lit card by card shows black slivers
// wherever a card turns its back or its edge to the light. Foliage is instead lit as the volume it
// forms: each side of a card is a single-sided face of its own with its own normal (not one
// double-sided face, whose normal a viewer turns over on the back), and each normal is bent toward
// the crown's outward direction at the leaf. A card seen from behind is then lit like a leaf
// facing the viewer, never black, in the viewport (render/gl/shaders.cpp picks the side it sees),
// three.js, engines and Blender. COLOR_0 carries the crown occlusion beside the normals.
#pragma once

#include <glm/vec3.hpp>

#include "render/mesh/mesh.h"

namespace sylva {

// The crown as an ellipsoid: the box of the leaves' positions (centre, half extents; each half
// extent at least 0.05 m), the shape bake_crown_occlusion also darkens by.
struct crown_ellipsoid {
  glm::vec3 centre{0};
  glm::vec3 radii{1};
};

// A box accumulated leaf by leaf, then turned into the ellipsoid (empty: centre 0, radii 1).
struct crown_box {
  glm::vec3 lo{1e30f}, hi{-1e30f};
  void add(const glm::vec3& p);
  crown_ellipsoid ellipsoid() const;
};

// The crown of every leaf of `m` (all steps).
crown_ellipsoid leaf_crown(const tree_mesh& m);

// The outward direction of the crown at `p`: the normal of the ellipsoid's level surface through
// p, the gradient of |(p - c) / r|^2; straight up at the centre. Unit length.
glm::vec3 crown_outward(const crown_ellipsoid& c, const glm::vec3& p);

// How far a card's inner face sits behind its outer one, as a share of the leaf's size: enough
// that a ray tracer (Cycles treats every face as two-sided) meets the face turned toward it
// first, far too little to see.
inline constexpr float leaf_back_offset = 0.002f;

// The normal one side of a card is lit with: its own normal `side` (unit) bent toward `outward`
// by `blend` (0: the card's own, 1: the crown's), normalised, its angle from `side` capped at
// acos(min_leaf_normal_cos) (about 75 degrees) so it stays on its own side; `side` where the mix
// cancels.
inline constexpr float min_leaf_normal_cos = 0.25f;
glm::vec3 blend_leaf_normal(const glm::vec3& side, const glm::vec3& outward, float blend);

// A leaf's colour factor (issue 52), multiplied into its tinted picture in the viewport's leaf
// shader (render/gl/shaders.cpp, the same lines) and into every exported blade's COLOR_0:
// - light: a leaf under open sky (sky visibility 1, leaf_instance::occlusion / 255) is lighter and
//   yellower, one deep in the crown (0.35) darker and bluer, as sun and shade leaves differ;
//   sun_tone 0 leaves the colour alone;
// - twig and leaf: a seeded offset in hue and lightness, mostly shared by the leaves of one node
//   (a twig's leaves grew together) and partly each leaf's own, scaled by variation.
// `index` is the leaf's place in tree_mesh::leaves (the shader's gl_InstanceID).
glm::vec3 leaf_color_factor(uint32_t node, uint32_t index, float visibility, float variation, float sun_tone);

}  // namespace sylva
