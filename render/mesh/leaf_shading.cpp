// Leaves shaded as a volume (render/mesh/leaf_shading.h).
#include "render/mesh/leaf_shading.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "render/mesh/season.h"

namespace sylva {

void crown_box::add(const glm::vec3& p) {
  if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return;
  lo = glm::min(lo, p);
  hi = glm::max(hi, p);
}

crown_ellipsoid crown_box::ellipsoid() const {
  if (lo.x > hi.x) return {};
  return {0.5f * (lo + hi), glm::max(0.5f * (hi - lo), glm::vec3(0.05f))};
}

crown_ellipsoid leaf_crown(const tree_mesh& m) {
  crown_box b;
  for (const leaf_instance& l : m.leaves) b.add(l.position);
  return b.ellipsoid();
}

glm::vec3 crown_outward(const crown_ellipsoid& c, const glm::vec3& p) {
  const glm::vec3 g = (p - c.centre) / (c.radii * c.radii);
  const float len = glm::length(g);
  if (!(len > 1e-6f) || !std::isfinite(len)) return {0, 1, 0};
  return g / len;
}

glm::vec3 blend_leaf_normal(const glm::vec3& side, const glm::vec3& outward, float blend) {
  const float b = std::clamp(std::isfinite(blend) ? blend : 0.0f, 0.0f, 1.0f);
  glm::vec3 n = (1.0f - b) * side + b * outward;
  const float len = glm::length(n);
  if (!(len > 1e-4f)) return side;
  n /= len;
  // Kept on its own side (within about 75 degrees of it): a face bent past its edge would be lit
  // from behind, which is the black card this is meant to cure.
  const float c = glm::dot(n, side);
  if (c >= min_leaf_normal_cos) return n;
  const glm::vec3 across = n - c * side;   // the bend's direction, kept; its angle capped
  const float a = glm::length(across);
  if (!(a > 1e-4f)) return side;
  return min_leaf_normal_cos * side + std::sqrt(1.0f - min_leaf_normal_cos * min_leaf_normal_cos) * (across / a);
}

glm::vec3 leaf_color_factor(uint32_t node, uint32_t index, float visibility, float variation, float sun_tone) {
  const float v = std::isfinite(visibility) ? visibility : 1.0f;
  const float t = std::clamp((v - 0.35f) / 0.65f, 0.0f, 1.0f);   // 0 deep in the crown, 1 open sky
  const float tone = std::clamp(std::isfinite(sun_tone) ? sun_tone : 0.0f, 0.0f, 1.0f);
  const glm::vec3 light = glm::mix(glm::vec3(1.0f), glm::mix(glm::vec3(0.8f, 0.84f, 0.92f), glm::vec3(1.12f, 1.1f, 0.9f), t), tone);
  // Seeded offsets (season_leaf_random, the shader's leaf_random), 70 % the twig's, 30 % the leaf's.
  const float hue = 0.7f * (season_leaf_random(node, 11) - 0.5f) + 0.3f * (season_leaf_random(index, 12) - 0.5f);
  const float lightness = 0.7f * (season_leaf_random(node, 13) - 0.5f) + 0.3f * (season_leaf_random(index, 14) - 0.5f);
  const float var = std::clamp(std::isfinite(variation) ? variation : 0.0f, 0.0f, 1.0f);
  const glm::vec3 twig = glm::vec3(1.0f) + var * glm::vec3(hue + lightness, 0.6f * hue + lightness, -0.5f * hue + lightness);
  return light * glm::max(twig, glm::vec3(0.0f));
}

}  // namespace sylva
