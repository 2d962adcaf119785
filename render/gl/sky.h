// The analytic daylight sky of Preetham, Shirley & Smits 1999, "A Practical Analytic Model for
// Daylight": sky radiance, the sun's colour after the atmosphere, and the sky's irradiance as
// first-order spherical harmonics for the ambient light (docs/SCENE.md, "What a frame draws"). CPU only.
#pragma once

#include <glm/vec3.hpp>

#include "render/mesh/render_params.h"

namespace sylva {

struct sky_model {
  glm::vec3 sun_dir{0, 1, 0};     // unit, toward the sun (its elevation as given, even below the horizon)
  bool physical = true;
  // Perez et al. 1993 coefficients A..E for (Y, x, y), the zenith (Y in kcd/m², x, y) and
  // F(0, θs) per channel: radiance(θ, γ) = zenith · F(θ, γ) / F(0, θs).
  glm::vec3 perez[5]{};
  glm::vec3 zenith{0};
  glm::vec3 perez_zenith{1};
  float scale = 0;                // renderer radiance per kcd/m², including the twilight fade
  glm::vec3 sun_light{0};         // direct sun at the ground, renderer units (albedo · this · cos = radiance)
  // Irradiance / π for a surface with normal n: sh[0] + sh[1] n.x + sh[2] n.y + sh[3] n.z
  // (Ramamoorthi & Hanrahan 2001, first two bands), already times render_params::ambient.
  glm::vec3 sh[4]{};
  glm::vec3 fog_ambient{0};       // mean radiance over the sphere: what fog scatters from the sky
  glm::vec3 horizon{0};           // mean radiance at the horizon, where the ground fades
  glm::vec3 legacy_zenith{0}, legacy_horizon{0};   // the gradient when physical is off
};

glm::vec3 sun_direction(const render_params& p);   // unit vector toward the sun

// Everything the frame needs from the sky; the renderer recomputes it only when its inputs change.
void compute_sky(const render_params& p, sky_model& out);
// Radiance of the sky in direction d (unit), renderer units, without the sun disc.
glm::vec3 sky_radiance(const sky_model& s, const glm::vec3& d);

}  // namespace sylva
