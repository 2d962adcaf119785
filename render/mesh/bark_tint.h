// Bark colour by height (issue 23): many trunks change colour up the stem, e.g. a Scots pine's
// grey-brown, deeply fissured foot under the thin orange bark of its upper trunk and limbs
// (Rushforth 1999). The tint is the base colour at the ground and shades to the bark colour by
// `height` metres (smoothstep); height 0: one colour. The viewport's bark shader evaluates the same
// blend per fragment (render/gl/shaders.cpp); exports tint the bark texture with peak() and carry
// ratio(y), times the crown occlusion, as the bark's COLOR_0, since glTF multiplies a material's
// base colour by COLOR_0, which cannot exceed 1 (render/io/export_parts.cpp).
#pragma once

#include <algorithm>

#include <glm/common.hpp>
#include <glm/vec3.hpp>

namespace sylva {

struct bark_tint {
  glm::vec3 color{0.45f, 0.34f, 0.25f};  // above `height`
  glm::vec3 base{0.45f, 0.34f, 0.25f};   // at the ground
  float height = 0;                       // metres; 0 (or NaN): no blend

  bool blends() const { return height > 0; }
  // The tint at height y (metres above the ground, the tree's local y).
  glm::vec3 at(float y) const {
    if (!blends()) return color;
    const float t = std::clamp(y / height, 0.0f, 1.0f);
    return glm::mix(base, color, t * t * (3.0f - 2.0f * t));
  }
  // The brighter of the two in each channel: the texture's tint in exports.
  glm::vec3 peak() const { return blends() ? glm::max(color, base) : color; }
  // at(y) / peak(), each channel in [0, 1] (0 where the peak is 0).
  glm::vec3 ratio(float y) const {
    const glm::vec3 p = peak(), c = at(y);
    glm::vec3 r;
    for (int k = 0; k < 3; ++k) r[k] = p[k] > 1e-6f ? std::clamp(c[k] / p[k], 0.0f, 1.0f) : 0.0f;
    return r;
  }
};

}  // namespace sylva
