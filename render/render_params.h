// Lighting and post-process settings; plain data saved in presets under "render" (DESIGN §8).
#pragma once

#include <glm/vec3.hpp>

#include "generators/params.h"

namespace sylva {

struct render_params {
  float sun_azimuth = 35;       // degrees, from +Z toward +X
  float sun_elevation = 40;     // degrees above the horizon
  glm::vec3 sun_color{1.0f, 0.95f, 0.85f};
  float sun_intensity = 3.0f;
  glm::vec3 sky_zenith{0.25f, 0.45f, 0.85f};
  glm::vec3 sky_horizon{0.75f, 0.85f, 0.95f};
  float ambient = 0.35f;
  float exposure = 1.0f;
  glm::vec3 bark_color{0.45f, 0.34f, 0.25f};
  glm::vec3 leaf_color{0.30f, 0.55f, 0.18f};
  bool ground = true;
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
  v(p.bark_color, param_info{"bark_color", "Bark colour", "", 0, 1, "Bark tint (linear RGB)", 0, "Materials"});
  v(p.leaf_color, param_info{"leaf_color", "Leaf colour", "", 0, 1, "Leaf tint (linear RGB)"});
  v(p.ground, param_info{"ground", "Ground", "", 0, 1, "Draw the ground plane"});
}

}  // namespace sylva
