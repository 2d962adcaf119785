// Lighting and post-process settings; plain data saved in presets under "render" (DESIGN §8).
#pragma once

#include <cmath>
#include <string>

#include <glm/vec3.hpp>

#include "generators/archetypes.h"
#include "generators/params.h"
#include "render/mesh/lod_params.h"
#include "render/mesh/wind.h"

namespace sylva {

enum class shadow_filter : int { pcf3 = 0, pcf5 = 1, poisson = 2 };
inline constexpr const char* shadow_filter_names[] = {"3x3", "5x5", "poisson", nullptr};

// Light shafts (DESIGN §8 pass 3): none, the screen-space radial blur (Mitchell, GPU Gems 3 ch. 13;
// cheap, only while the sun is on screen) or single scattering ray-marched through the sun's shadow
// map (light in the air wherever the sun is).
enum class light_shafts : int { off = 0, radial = 1, volumetric = 2 };
inline constexpr const char* light_shafts_names[] = {"off", "radial", "volumetric", nullptr};

// The season of the leaves (render/mesh/season.h turns it into colours, sizes and bare twigs).
// It never regrows: only the leaves' look and which of them are drawn or exported change.
enum class leaf_season : int { spring = 0, summer = 1, autumn = 2, winter = 3 };
inline constexpr const char* leaf_season_names[] = {"spring", "summer", "autumn", "winter", nullptr};
// Which leaves fall in autumn: by archetype (needles, sprays and palm fronds stay; blades fall), or
// every leaf of the preset (a larch's needles fall; a holly's blades stay).
enum class leaf_habit : int { by_archetype = 0, deciduous = 1, evergreen = 2 };
inline constexpr const char* leaf_habit_names[] = {"by_archetype", "deciduous", "evergreen", nullptr};

struct render_params {
  // The first view: a low sun behind the tree, 15° to the side of the default camera's line of sight
  // (yaw 35°), so that long shadows come toward the viewer and shafts fan out under the crown.
  float sun_azimuth = -160;     // degrees, from +Z toward +X
  float sun_elevation = 9;      // degrees above the horizon
  // Physical sky (Preetham et al. 1999): the sky, the sun's colour and the ambient light all follow
  // the sun and the turbidity. Off: the colours below are used as given.
  bool physical_sky = true;
  float turbidity = 3.0f;
  glm::vec3 sun_color{1.0f, 0.95f, 0.85f};
  float sun_intensity = 2.2f;
  glm::vec3 sky_zenith{0.25f, 0.45f, 0.85f};
  glm::vec3 sky_horizon{0.75f, 0.85f, 0.95f};
  float ambient = 1.0f;
  float exposure = 1.0f;
  bool auto_exposure = true;
  bark_archetype bark = bark_archetype::furrowed;   // procedural bark texture set
  glm::vec3 bark_color{0.45f, 0.34f, 0.25f};
  glm::vec3 bark_base_color{0.3f, 0.28f, 0.26f};  // the bark at the ground, shading to bark_color
  float bark_base_height = 0;                     // ... by this height (m); 0: one colour (render/mesh/bark_tint.h)
  glm::vec3 leaf_color{0.30f, 0.55f, 0.18f};
  bool ground = true;
  glm::vec3 ground_color{0.16f, 0.20f, 0.09f};
  // Leaves (seed 001 names opaque leaves its main flaw: light passes through these).
  float leaf_translucency = 0.6f;
  float leaf_normal_blend = 0.6f;   // leaf normals bent toward the crown (render/mesh/leaf_shading.h)
  float alpha_cutoff = 0.5f;
  float leaf_color_variation = 0.15f;
  float leaf_sun_tone = 0.6f;       // sun leaves lighter, shade leaves darker (render/mesh/leaf_shading.h)
  // Season (render/mesh/season.h): the autumn colour runs from autumn_color to autumn_color_2 per leaf.
  leaf_season season = leaf_season::summer;
  leaf_habit habit = leaf_habit::by_archetype;
  glm::vec3 autumn_color{0.62f, 0.36f, 0.04f};
  glm::vec3 autumn_color_2{0.55f, 0.12f, 0.03f};
  // Sun shadow map (DESIGN §8 pass 1).
  bool shadows = true;
  int shadow_resolution = 2048;
  float shadow_bias = 0.0005f;
  float shadow_slope_bias = 2.0f;
  float shadow_normal_offset = 1.5f;
  shadow_filter shadow_pcf = shadow_filter::pcf5;
  // Light shafts and fog.
  light_shafts shafts = light_shafts::volumetric;
  float fog_density = 0.018f;      // ground fog at y = 0, per metre; it thins with height
  float fog_height = 8.0f;        // metres over which the ground fog thins by 1/e
  float haze = 0.0005f;           // aerial perspective: uniform haze, per metre
  float scattering_g = 0.7f;      // Henyey-Greenstein asymmetry of the fog
  int shaft_samples = 32;         // ray-march samples per pixel (at half resolution)
  // Radial blur: Mitchell, GPU Gems 3 ch. 13; defaults from seed 001 appendix A.
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
  lod_params lod;                 // level of detail (render/mesh/lod.h): budgets, viewport choice, impostor
  wind_params wind;   // sway in the viewport, baked by `sylva export --wind` (render/mesh/wind.h)
  bool operator==(const render_params&) const = default;
};

template <params_of<render_params> P, class V>
void visit_params(P& p, V&& visitor) {
  auto v = declare_class(visitor, param_render);   // the renderer and exporters read them, mesh_tree never
  v(p.sun_azimuth, param_info{"sun_azimuth", "Sun azimuth", "", -180, 180, "Compass direction of the sun", param_degrees, "Sun and sky"});
  v(p.sun_elevation, param_info{"sun_elevation", "Sun elevation", "", -10, 90, "Height of the sun above the horizon", param_degrees});
  v(p.physical_sky, param_info{"physical_sky", "Physical sky", "", 0, 1, "Analytic daylight sky (Preetham et al. 1999): it also sets the sun's colour and the sky light; off: the colours below"});
  v(p.turbidity, param_info{"turbidity", "Turbidity", "", 1.7f, 10, "Haziness of the air: 2 clear, 3 typical, 6+ hazy (physical sky)"});
  v(p.sun_color, param_info{"sun_color", "Sun colour", "", 0, 1, "Colour of direct sunlight (linear RGB; without the physical sky)"});
  v(p.sun_intensity, param_info{"sun_intensity", "Sun intensity", "", 0, 20, "Strength of direct sunlight (above the atmosphere with the physical sky)"});
  v(p.sky_zenith, param_info{"sky_zenith", "Sky zenith", "", 0, 1, "Sky colour overhead (linear RGB; without the physical sky)"});
  v(p.sky_horizon, param_info{"sky_horizon", "Sky horizon", "", 0, 1, "Sky colour at the horizon (linear RGB; without the physical sky)"});
  v(p.ambient, param_info{"ambient", "Ambient", "", 0, 2, "Strength of the sky light on the tree and ground (1: the sky's own)"});
  v(p.exposure, param_info{"exposure", "Exposure", "", 0.05f, 8, "Exposure before tonemapping (times the automatic one when on)", param_log});
  v(p.auto_exposure, param_info{"auto_exposure", "Auto exposure", "", 0, 1, "Expose for the frame's mean log luminance, so noon and golden hour both read"});
  v(p.bark, param_info{"bark_archetype", "Bark", "", 0, bark_archetype_count - 1, "Procedural bark: furrowed (oak), plated (pine), smooth with lenticels (birch), peeling strips, ringed leaf scars (palm), mottled smooth grey with resin spots (fir), fissured grey (ash, true cedar), fibrous shreds (cypress, thuja), silver smooth creased grey (beech)", 0, "Materials", bark_archetype_names});
  v(p.bark_color, param_info{"bark_color", "Bark colour", "", 0, 1, "Bark tint (linear RGB)"});
  v(p.bark_base_height, param_info{"bark_base_height", "Base bark height", "", 0, 30, "The bark shades from the base colour at the ground to the bark colour by this height (metres), as a Scots pine's grey foot turns to orange bark up the stem (0: one colour)"});
  v(p.bark_base_color, param_info{"bark_base_color", "Base bark colour", "", 0, 1, "Bark tint at the ground when the base bark height is above 0 (linear RGB)"});
  v(p.leaf_color, param_info{"leaf_color", "Leaf colour", "", 0, 1, "Leaf tint (linear RGB)"});
  v(p.ground, param_info{"ground", "Ground", "", 0, 1, "Draw the ground plane"});
  v(p.ground_color, param_info{"ground_color", "Ground colour", "", 0, 1, "Ground albedo (linear RGB)"});
  v(p.msaa, param_info{"msaa", "MSAA samples", "", 0, 8, "Multisample anti-aliasing of the lit pass (0 or 1: off)", param_on_release});
  v(p.leaf_translucency, param_info{"leaf_translucency", "Leaf translucency", "", 0, 1, "Share of sunlight that glows through a leaf lit from behind"});
  v(p.leaf_normal_blend, param_info{"leaf_normal_blend", "Crown normals", "", 0, 1, "Leaves are lit as a volume: each card's normal bends toward the crown's outward direction by this share (0: flat cards, 1: the crown's shape alone), in the viewport and in exports"});
  v(p.alpha_cutoff, param_info{"alpha_cutoff", "Leaf alpha cutoff", "", 0.05f, 0.95f, "Leaf texels below this opacity are cut away"});
  v(p.leaf_color_variation, param_info{"leaf_color_variation", "Leaf colour variation", "", 0, 1, "Seeded variation of the leaves' tint, mostly shared by the leaves of one twig, in the viewport and in exports"});
  v(p.leaf_sun_tone, param_info{"leaf_sun_tone", "Sun and shade tone", "", 0, 1, "Leaves under open sky are lighter and yellower, leaves deep in the crown darker and bluer, as sun and shade leaves differ (0: one tone), in the viewport and in exports"});
  v(p.season, param_info{"season", "Season", "", 0, 3, "Spring: fresh light green, smaller leaves still unfolding; summer: the leaf colour; autumn: the autumn colours, some leaves fallen; winter: deciduous trees bare (conifers and palms keep theirs). Only the leaves change: no regrow", 0, "Season", leaf_season_names});
  v(p.habit, param_info{"leaf_habit", "Leaf habit", "", 0, 2, "Which leaves turn and fall: by archetype (needles, conifer sprays and palm fronds stay, blades fall), all (deciduous) or none (evergreen)", 0, nullptr, leaf_habit_names});
  v(p.autumn_color, param_info{"autumn_color", "Autumn colour", "", 0, 1, "Autumn leaf tint at one end of the per-leaf range (linear RGB)"});
  v(p.autumn_color_2, param_info{"autumn_color_2", "Autumn colour 2", "", 0, 1, "Autumn leaf tint at the other end of the per-leaf range (linear RGB)"});
  v(p.bark_texture, param_info{"bark_texture", "Bark texture", "", 0, 0, "Your own bark colour PNG (tiles: x around the branch, y along it); empty: procedural", param_path, "Textures"});
  v(p.leaf_texture, param_info{"leaf_texture", "Leaf texture", "", 0, 0, "Your own leaf colour PNG (petiole at the bottom edge; alpha is the outline unless an opacity map is given; it replaces every leaf archetype); empty: the procedural archetype cards", param_path});
  v(p.leaf_opacity, param_info{"leaf_opacity", "Leaf opacity", "", 0, 0, "Optional greyscale PNG, same size as the leaf texture: white is leaf, black is cut away", param_path});
  v(p.shadows, param_info{"shadows", "Shadows", "", 0, 1, "Sun shadow map (orthographic, fitted to the tree)", 0, "Shadows"});
  v(p.shadow_resolution, param_info{"shadow_resolution", "Resolution", "", 1024, 8192, "Shadow map size in texels", param_log | param_on_release});
  v(p.shadow_bias, param_info{"shadow_bias", "Depth bias", "", 0, 0.01f, "Constant depth bias against shadow acne (depth units)", param_advanced});
  v(p.shadow_slope_bias, param_info{"shadow_slope_bias", "Slope bias", "", 0, 10, "Slope-scaled bias (glPolygonOffset factor)", param_advanced});
  v(p.shadow_normal_offset, param_info{"shadow_normal_offset", "Normal offset", "", 0, 5, "Lookups move this many texels along the normal: less acne, little peter-panning", param_advanced});
  v(p.shadow_pcf, param_info{"shadow_pcf", "Filter", "", 0, 2, "Percentage-closer filtering kernel: 3x3, 5x5 or a 16-tap Poisson disc (soft)", 0, nullptr, shadow_filter_names});
  v(p.shafts, param_info{"light_shafts", "Light shafts", "", 0, 2, "off; radial: screen-space blur toward the sun (Mitchell; cheap, sun on screen only); volumetric: sunlight scattered by the fog, ray-marched through the shadow map", 0, "Light shafts and fog", light_shafts_names});
  v(p.fog_density, param_info{"fog_density", "Fog density", "", 0, 1, "Ground fog at the ground, per metre (it thins with height); what the shafts light up", param_log});
  v(p.fog_height, param_info{"fog_height", "Fog height", "", 0.1f, 100, "Height over which the ground fog thins by 1/e (metres)", param_log});
  v(p.haze, param_info{"haze", "Haze", "", 0, 0.1f, "Aerial perspective: uniform haze per metre, tinted by the sky, so distance fades", param_log});
  v(p.scattering_g, param_info{"scattering_g", "Forward scattering", "", -0.9f, 0.95f, "Henyey-Greenstein g of the fog: 0 scatters evenly, toward 1 the light stays near the sun's direction"});
  v(p.shaft_samples, param_info{"shaft_samples", "Shaft samples", "", 4, 128, "Volumetric: shadow-map samples along each view ray (half resolution)"});
  v(p.ray_samples, param_info{"ray_samples", "Radial samples", "", 8, 256, "Radial: samples along each ray toward the sun"});
  v(p.ray_density, param_info{"ray_density", "Radial density", "", 0, 1, "Radial: fraction of the way to the sun the samples span"});
  v(p.ray_weight, param_info{"ray_weight", "Radial weight", "", 0, 5, "Radial: weight of each sample"});
  v(p.ray_decay, param_info{"ray_decay", "Radial decay", "", 0.9f, 1, "Radial: per-sample falloff of the samples' weight"});
  v(p.ray_exposure, param_info{"ray_exposure", "Radial exposure", "", 0, 0.5f, "Radial: overall strength of the rays"});
  visit_params(p.lod, v);
  visit_params(p.wind, v);
}

// The sun low and straight behind the tree as seen from a camera at `camera_yaw` degrees, so that
// shadows come toward the viewer and shafts fan out under the crown: the editor's "Backlit rays"
// and `sylva bench --render`'s default light.
inline void place_sun_behind(render_params& p, float camera_yaw) {
  p.sun_azimuth = std::remainder(camera_yaw + 180.0f, 360.0f);
  p.sun_elevation = 12;
}

// Sliders that do not apply to the chosen sky or shaft mode are hidden (presets still save them).
inline bool param_relevant(const render_params& p, const void* field, const param_info& info) {
  const char* w = reinterpret_cast<const char*>(&p.wind);
  if (static_cast<const char*>(field) >= w && static_cast<const char*>(field) < w + sizeof(wind_params))
    return param_relevant(p.wind, field, info);
  if (field == &p.turbidity) return p.physical_sky;
  if (field == &p.sun_color || field == &p.sky_zenith || field == &p.sky_horizon) return !p.physical_sky;
  if (field == &p.shaft_samples) return p.shafts == light_shafts::volumetric;
  if (field == &p.ray_samples || field == &p.ray_density || field == &p.ray_weight || field == &p.ray_decay ||
      field == &p.ray_exposure)
    return p.shafts == light_shafts::radial;
  return true;
}

}  // namespace sylva
