// Leaves shaded as a volume (issue 23): a crown of cards lit card by card shows black slivers
// wherever a card turns its back or its edge to the light. Foliage is instead lit as the volume it
// forms. Each exported card is turned so that its front looks out of the crown, and its normal is
// bent toward the crown's outward direction at the leaf: a viewer outside the crown meets the lit
// front of the near leaves, and the turned-over normal a double-sided material gives the far
// leaves' backs points back toward the viewer. One face per card (a face per side would double
// the triangles and, in Cycles, the transparent layers every ray crosses). The viewport
// (render/gl/shaders.cpp) lights the side it sees and bends that; COLOR_0 carries the crown
// occlusion beside the normals.
#pragma once

#include <glm/vec3.hpp>

#include "render/mesh.h"

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

// The normal one side of a card is lit with: its own normal `side` (unit) bent toward `outward`
// by `blend` (0: the card's own, 1: the crown's), normalised; `side` where the mix cancels.
glm::vec3 blend_leaf_normal(const glm::vec3& side, const glm::vec3& outward, float blend);

}  // namespace sylva
