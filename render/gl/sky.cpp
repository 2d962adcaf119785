// Preetham et al. 1999 daylight: Perez sky distribution, zenith values and sun transmittance.
#include "render/gl/sky.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

namespace sylva {

namespace {

constexpr float pi = 3.14159265358979f;

// Perez et al. 1993 all-weather luminance distribution, as used by Preetham et al. 1999 (eq. 3):
// F(θ, γ) = (1 + A e^(B / cos θ)) (1 + C e^(D γ) + E cos² γ).
glm::vec3 perez(const glm::vec3 c[5], float cos_theta, float gamma, float cos_gamma) {
  const float ct = std::max(cos_theta, 0.01f);
  glm::vec3 f;
  for (int i = 0; i < 3; ++i)
    f[i] = (1.0f + c[0][i] * std::exp(c[1][i] / ct)) * (1.0f + c[2][i] * std::exp(c[3][i] * gamma) + c[4][i] * cos_gamma * cos_gamma);
  return f;
}

// CIE xyY to linear sRGB (Rec. 709 primaries, D65).
glm::vec3 xyY_to_rgb(float x, float y, float Y) {
  y = std::max(y, 1e-4f);
  const float X = x / y * Y, Z = (1.0f - x - y) / y * Y;
  return glm::max(glm::vec3(3.2406f * X - 1.5372f * Y - 0.4986f * Z, -0.9689f * X + 1.8758f * Y + 0.0415f * Z,
                            0.0557f * X - 0.2040f * Y + 1.0570f * Z),
                  glm::vec3(0.0f));
}

}  // namespace

glm::vec3 sky_radiance(const sky_model& s, const glm::vec3& d) {
  if (!s.physical) {
    const float up = std::max(d.y, 0.0f);
    return d.y >= 0 ? glm::mix(s.legacy_horizon, s.legacy_zenith, std::pow(up, 0.45f)) : s.legacy_horizon * 0.9f;
  }
  const float cos_gamma = std::clamp(glm::dot(d, s.sun_dir), -1.0f, 1.0f);
  const glm::vec3 f = perez(s.perez, d.y, std::acos(cos_gamma), cos_gamma);
  const glm::vec3 Yxy = s.zenith * f / s.perez_zenith;
  return xyY_to_rgb(Yxy.y, Yxy.z, Yxy.x) * s.scale;
}

void compute_sky(const render_params& p, sky_model& s) {
  const float az = p.sun_azimuth * pi / 180.0f, el = std::clamp(p.sun_elevation, -90.0f, 90.0f) * pi / 180.0f;
  s.sun_dir = glm::vec3(std::sin(az) * std::cos(el), std::sin(el), std::cos(az) * std::cos(el));
  s.physical = p.physical_sky;
  const float amb = std::max(p.ambient, 0.0f);
  const float above = std::clamp((s.sun_dir.y + 0.05f) / 0.15f, 0.0f, 1.0f);   // nothing lights from below the horizon

  if (!p.physical_sky) {   // the hand-set gradient and hemispheric ambient of earlier versions
    s.legacy_zenith = p.sky_zenith;
    s.legacy_horizon = p.sky_horizon;
    s.sun_light = p.sun_color * std::max(p.sun_intensity, 0.0f) * above;
    const glm::vec3 g = p.ground_color * 0.6f, z = p.sky_zenith;
    const float k = 0.35f * amb;   // the old default ambient strength, now that 1 means "the sky's own"
    s.sh[0] = 0.5f * (g + z) * k;
    s.sh[1] = s.sh[3] = glm::vec3(0);
    s.sh[2] = 0.5f * (z - g) * k;
    s.fog_ambient = 0.5f * (p.sky_zenith + p.sky_horizon) * amb;
    s.horizon = p.sky_horizon * 0.9f;
    return;
  }

  // Preetham et al. 1999, appendix A.2. The model holds for the sun above the horizon and
  // turbidity 2..10 (we allow 1.7): below the horizon the sky keeps the sun-on-the-horizon
  // distribution and fades (twilight), never to black.
  const float T = std::clamp(p.turbidity, 1.7f, 10.0f);
  const float theta_s = pi / 2 - std::max(el, 0.0f);
  const glm::vec3 A(0.1787f * T - 1.4630f, -0.0193f * T - 0.2592f, -0.0167f * T - 0.2608f);
  const glm::vec3 B(-0.3554f * T + 0.4275f, -0.0665f * T + 0.0008f, -0.0950f * T + 0.0092f);
  const glm::vec3 C(-0.0227f * T + 5.3251f, -0.0004f * T + 0.2125f, -0.0079f * T + 0.2102f);
  const glm::vec3 D(0.1206f * T - 2.5771f, -0.0641f * T - 0.8989f, -0.0441f * T - 1.6537f);
  const glm::vec3 E(-0.0670f * T + 0.3703f, -0.0033f * T + 0.0452f, -0.0109f * T + 0.0529f);
  s.perez[0] = A, s.perez[1] = B, s.perez[2] = C, s.perez[3] = D, s.perez[4] = E;
  const float chi = (4.0f / 9.0f - T / 120.0f) * (pi - 2.0f * theta_s);
  const float Yz = std::max((4.0453f * T - 4.9710f) * std::tan(chi) - 0.2155f * T + 2.4192f, 0.05f);   // kcd/m²
  const float t3 = theta_s * theta_s * theta_s, t2 = theta_s * theta_s, t1 = theta_s;
  const float xz = (0.00166f * t3 - 0.00375f * t2 + 0.00209f * t1) * T * T +
                   (-0.02903f * t3 + 0.06377f * t2 - 0.03202f * t1 + 0.00394f) * T +
                   (0.11693f * t3 - 0.21196f * t2 + 0.06052f * t1 + 0.25886f);
  const float yz = (0.00275f * t3 - 0.00610f * t2 + 0.00317f * t1) * T * T +
                   (-0.04214f * t3 + 0.08970f * t2 - 0.04153f * t1 + 0.00516f) * T +
                   (0.15346f * t3 - 0.26756f * t2 + 0.06670f * t1 + 0.26688f);
  s.zenith = glm::vec3(Yz, xz, yz);
  s.perez_zenith = perez(s.perez, 1.0f, theta_s, std::cos(theta_s));

  // Units: the sun's `sun_intensity` is the renderer's radiance of a white surface facing the sun
  // above the atmosphere, whose illuminance is ~128 klux; a sky of L cd/m² then reads
  // L · π · sun_intensity / 128000. Below the horizon the sky dims over 8° of depression.
  const float intensity = std::max(p.sun_intensity, 0.0f);
  const float twilight = el >= 0 ? 1.0f : std::max(std::exp(el * 180.0f / pi / 3.0f), 0.02f);
  s.scale = 1000.0f * pi * intensity / 128000.0f * twilight;

  // The sun's colour: spectral transmittance of the atmosphere (Preetham et al. 1999, appendix A.1),
  // Rayleigh τ_r = 0.008735 λ^-4.08 and Ångström aerosol τ_a = β λ^-α with β = 0.04608 T - 0.04586,
  // α = 1.3, over the relative optical air mass of Kasten & Young 1989. Ozone and water vapour are
  // left out; λ are representative wavelengths of the sRGB primaries (µm).
  const float zenith_deg = std::min(theta_s * 180.0f / pi, 93.0f);
  const float mass = 1.0f / (std::cos(theta_s) + 0.50572f * std::pow(96.07995f - zenith_deg, -1.6364f));
  const float beta = std::max(0.04608f * T - 0.04586f, 0.0f);
  const glm::vec3 lambda(0.65f, 0.57f, 0.475f);
  glm::vec3 transmit;
  for (int i = 0; i < 3; ++i) {
    const float tr = 0.008735f * std::pow(lambda[i], -4.08f), ta = beta * std::pow(lambda[i], -1.3f);
    transmit[i] = std::exp(-mass * (tr + ta));
  }
  s.sun_light = transmit * intensity * above;

  // Irradiance from the sky and the sunlit ground below the horizon, projected onto the first two
  // SH bands by a fixed 24 x 48 quadrature (Ramamoorthi & Hanrahan 2001: E = π L00 Y00 + 2π/3 L1m Y1m).
  constexpr int nt = 24, np = 48;
  glm::vec3 L[4]{}, up_irr(0), horizon(0);
  for (int pass = 0; pass < 2; ++pass) {
    // First pass: sky only, for the irradiance on the ground; second: the whole sphere.
    const glm::vec3 ground = p.ground_color * (s.sun_light * std::max(s.sun_dir.y, 0.0f) + up_irr / pi);
    glm::vec3 acc[4]{}, up(0);
    for (int i = 0; i < nt; ++i) {
      const float th = (float(i) + 0.5f) / nt * pi, dth = pi / nt;
      for (int j = 0; j < np; ++j) {
        const float ph = (float(j) + 0.5f) / np * 2.0f * pi, dph = 2.0f * pi / np;
        const glm::vec3 d(std::sin(th) * std::sin(ph), std::cos(th), std::sin(th) * std::cos(ph));
        const float dw = std::sin(th) * dth * dph;
        const glm::vec3 rad = d.y >= 0 ? sky_radiance(s, d) : (pass ? ground : glm::vec3(0));
        up += rad * std::max(d.y, 0.0f) * dw;
        acc[0] += rad * 0.282095f * dw;
        acc[1] += rad * 0.488603f * d.x * dw;
        acc[2] += rad * 0.488603f * d.y * dw;
        acc[3] += rad * 0.488603f * d.z * dw;
        if (pass && i == nt / 2 - 1) horizon += rad / float(np);
      }
    }
    up_irr = up;
    for (int k = 0; k < 4; ++k) L[k] = acc[k];
    s.horizon = horizon;
  }
  // Irradiance / π, times the user's ambient strength.
  s.sh[0] = amb * 0.282095f * L[0];
  for (int k = 1; k < 4; ++k) s.sh[k] = amb * (2.0f / 3.0f) * 0.488603f * L[k];
  s.fog_ambient = amb * 0.282095f * L[0];
}

glm::vec3 sun_direction(const render_params& p) {
  float a = glm::radians(p.sun_azimuth), e = glm::radians(p.sun_elevation);
  return glm::vec3(std::sin(a) * std::cos(e), std::sin(e), std::cos(a) * std::cos(e));
}

}  // namespace sylva
