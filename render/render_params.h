// Lighting and post-process settings; plain data saved in presets under "render" (DESIGN §8).
#pragma once

#include <string>

#include <glm/vec3.hpp>

#include "generators/archetypes.h"
#include "generators/params.h"

namespace sylva {

enum class shadow_filter : int { pcf3 = 0, pcf5 = 1, poisson = 2 };
inline constexpr const char* shadow_filter_names[] = {"3x3", "5x5", "poisson", nullptr};

struct render_params {
  float sun_azimuth = 35;       // degrees, from +Z toward +X
  float sun_elevation = 40;     // degrees above the horizon
  glm::vec3 sun_color{1.0f, 0.95f, 0.85f};
  float sun_intensity = 2.2f;
  glm::vec3 sky_zenith{0.25f, 0.45f, 0.85f};
  glm::vec3 sky_horizon{0.75f, 0.85f, 0.95f};
  float ambient = 0.35f;
  float exposure = 1.0f;
  bark_archetype bark = bark_archetype::furrowed;   // procedural bark texture set
  glm::vec3 bark_color{0.45f, 0.34f, 0.25f};
  glm::vec3 leaf_color{0.30f, 0.55f, 0.18f};
  bool ground = true;
  glm::vec3 ground_color{0.16f, 0.20f, 0.09f};
  // Leaves (seed 001 names opaque leaves its main flaw: light passes through these).
  float leaf_translucency = 0.6f;
  float alpha_cutoff = 0.5f;
  float leaf_color_variation = 0.15f;
  // Sun shadow map (DESIGN §8 pass 1).
  bool shadows = true;
  int shadow_resolution = 2048;
  float shadow_bias = 0.0005f;
  float shadow_slope_bias = 2.0f;
  float shadow_normal_offset = 1.5f;
  shadow_filter shadow_pcf = shadow_filter::pcf5;
  // God rays: Mitchell, GPU Gems 3 ch. 13; defaults from seed 001 appendix A.
  bool god_rays = true;
  int ray_samples = 170;
  float ray_density = 0.9f;
  float ray_weight = 1.5f;
  float ray_decay = 0.99f;
  float ray_exposure = 0.05f;
  int msaa = 4;
  // The user's own textures (PNG); "" uses the procedural ones.
  std::string bark_texture;
  std::string leaf_texture;
  std::string leaf_opacity;
  bool operator==(const render_params&) const = default;
};

template <params_of<render_params> P, class V>
void visit_params(P& p, V&& v) {
  v(p.sun_azimuth, param_info{"sun_azimuth", "Sun azimuth", "", -180, 180, "Compass direction of the sun", param_degrees, "Sun and sky"});
  v(p.sun_elevation, param_info{"sun_elevation", "Sun elevation", "", -10, 90, "Height of the sun above the horizon", param_degrees});
  v(p.sun_color, param_info{"sun_color", "Sun colour", "", 0, 1, "Colour of direct sunlight (linear RGB)"});
  v(p.sun_intensity, param_info{"sun_intensity", "Sun intensity", "", 0, 20, "Strength of direct sunlight"});
  v(p.sky_zenith, param_info{"sky_zenith", "Sky zenith", "", 0, 1, "Sky colour overhead (linear RGB)"});
  v(p.sky_horizon, param_info{"sky_horizon", "Sky horizon", "", 0, 1, "Sky colour at the horizon (linear RGB)"});
  v(p.ambient, param_info{"ambient", "Ambient", "", 0, 2, "Hemispheric sky light"});
  v(p.exposure, param_info{"exposure", "Exposure", "", 0.05f, 8, "Exposure before tonemapping", param_log});
  v(p.bark, param_info{"bark_archetype", "Bark", "", 0, 4, "Procedural bark: furrowed (oak), plated (pine), smooth with lenticels (birch, beech), peeling strips (cedar), ringed leaf scars (palm)", 0, "Materials", bark_archetype_names});
  v(p.bark_color, param_info{"bark_color", "Bark colour", "", 0, 1, "Bark tint (linear RGB)"});
  v(p.leaf_color, param_info{"leaf_color", "Leaf colour", "", 0, 1, "Leaf tint (linear RGB)"});
  v(p.ground, param_info{"ground", "Ground", "", 0, 1, "Draw the ground plane"});
  v(p.ground_color, param_info{"ground_color", "Ground colour", "", 0, 1, "Ground albedo (linear RGB)"});
  v(p.msaa, param_info{"msaa", "MSAA samples", "", 0, 8, "Multisample anti-aliasing of the lit pass (0 or 1: off)", param_on_release});
  v(p.leaf_translucency, param_info{"leaf_translucency", "Leaf translucency", "", 0, 1, "Share of sunlight that glows through a leaf lit from behind"});
  v(p.alpha_cutoff, param_info{"alpha_cutoff", "Leaf alpha cutoff", "", 0.05f, 0.95f, "Leaf texels below this opacity are cut away"});
  v(p.leaf_color_variation, param_info{"leaf_color_variation", "Leaf colour variation", "", 0, 1, "Random per-leaf variation of the tint"});
  v(p.bark_texture, param_info{"bark_texture", "Bark texture", "", 0, 0, "Your own bark colour PNG (tiles: x around the branch, y along it); empty: procedural", param_path, "Textures"});
  v(p.leaf_texture, param_info{"leaf_texture", "Leaf texture", "", 0, 0, "Your own leaf colour PNG (petiole at the bottom edge; alpha is the outline unless an opacity map is given; it replaces every leaf archetype); empty: the procedural archetype cards", param_path});
  v(p.leaf_opacity, param_info{"leaf_opacity", "Leaf opacity", "", 0, 0, "Optional greyscale PNG, same size as the leaf texture: white is leaf, black is cut away", param_path});
  v(p.shadows, param_info{"shadows", "Shadows", "", 0, 1, "Sun shadow map (orthographic, fitted to the tree)", 0, "Shadows"});
  v(p.shadow_resolution, param_info{"shadow_resolution", "Resolution", "", 1024, 8192, "Shadow map size in texels", param_log | param_on_release});
  v(p.shadow_bias, param_info{"shadow_bias", "Depth bias", "", 0, 0.01f, "Constant depth bias against shadow acne (depth units)", param_advanced});
  v(p.shadow_slope_bias, param_info{"shadow_slope_bias", "Slope bias", "", 0, 10, "Slope-scaled bias (glPolygonOffset factor)", param_advanced});
  v(p.shadow_normal_offset, param_info{"shadow_normal_offset", "Normal offset", "", 0, 5, "Lookups move this many texels along the normal: less acne, little peter-panning", param_advanced});
  v(p.shadow_pcf, param_info{"shadow_pcf", "Filter", "", 0, 2, "Percentage-closer filtering kernel: 3x3, 5x5 or a 16-tap Poisson disc (soft)", 0, nullptr, shadow_filter_names});
  v(p.god_rays, param_info{"god_rays", "God rays", "", 0, 1, "Radial blur of the sun's occlusion image (Mitchell, GPU Gems 3 ch. 13)", 0, "God rays"});
  v(p.ray_samples, param_info{"ray_samples", "Samples", "", 8, 256, "Samples along each ray toward the sun"});
  v(p.ray_density, param_info{"ray_density", "Density", "", 0, 1, "Fraction of the way to the sun the samples span"});
  v(p.ray_weight, param_info{"ray_weight", "Weight", "", 0, 5, "Weight of each sample"});
  v(p.ray_decay, param_info{"ray_decay", "Decay", "", 0.9f, 1, "Per-sample falloff of the samples' weight"});
  v(p.ray_exposure, param_info{"ray_exposure", "Exposure", "", 0, 0.5f, "Overall strength of the rays"});
}

}  // namespace sylva
