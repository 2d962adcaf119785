// The frame renderer: programs, procedural textures, tree upload, and the passes of
// docs/design/08-renderer.md.
#include "render/gl/renderer.h"
#include "render/mesh/leaf_shoot.h"
#include "render/gl/shaders.h"
#include "render/gl/renderer_resources.h"

#include "generators/wood.h"
#include "render/gl/wind_gl.h"
#include "render/mesh/lod_cards.h"
#include "render/mesh/season.h"
#include "render/assets/textures.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

namespace sylva {

namespace {

using namespace glsl;   // the programs' sources (render/gl/shaders.h)

// ---------------------------------------------------------------- helpers

glm::mat4 light_viewproj(const renderer_gpu& r, const glm::vec3& sun, float* texel_world) {
  glm::vec3 lo = r.bounds_min, hi = r.bounds_max;
  glm::vec3 center = 0.5f * (lo + hi);
  float radius = std::max(glm::length(hi - lo) * 0.5f, 0.01f);
  glm::vec3 up = std::abs(sun.y) > 0.99f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  glm::mat4 view = glm::lookAt(center + sun * radius * 2.0f, center, up);
  glm::vec3 a(1e30f), b(-1e30f);
  for (int i = 0; i < 8; ++i) {
    glm::vec3 c((i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z);
    glm::vec3 v = glm::vec3(view * glm::vec4(c, 1));
    a = glm::min(a, v);
    b = glm::max(b, v);
  }
  const float pad = radius * 0.02f + r.wind_reach;   // the swaying crown stays inside the map
  glm::mat4 proj = glm::ortho(a.x - pad, b.x + pad, a.y - pad, b.y + pad, -b.z - pad, -a.z + pad);
  if (texel_world) *texel_world = std::max(b.x - a.x, b.y - a.y) / float(std::max(r.shadow_size, 1));
  return proj * view;
}

void set_lighting(const renderer_gpu& r, const gl_program& p, const render_params& rp, const glm::vec3& sun,
                  const glm::mat4& light, float texel_world) {
  set_uniform(p, "u_sun_dir", sun);
  // The sun's colour and the sky light come from the sky model (render/gl/sky.h); the sun dims as it sets.
  set_uniform(p, "u_sun_light", r.daylight.sun_light);
  static const char* const sh_names[4] = {"u_sh[0]", "u_sh[1]", "u_sh[2]", "u_sh[3]"};
  for (int k = 0; k < 4; ++k) set_uniform(p, sh_names[k], r.daylight.sh[k]);
  set_uniform(p, "u_shadows", rp.shadows && r.has_tree ? 1 : 0);
  set_uniform(p, "u_pcf", int(rp.shadow_pcf));
  set_uniform(p, "u_bias", rp.shadow_bias);
  set_uniform(p, "u_normal_offset", rp.shadow_normal_offset);
  set_uniform(p, "u_shadow_texel", texel_world);
  set_uniform(p, "u_light_viewproj", light);
  set_uniform(p, "u_shadow", 1);
}

// The parameters the sky model reads, compared and copied one by one (no string copies per frame).
bool same_sky_inputs(const render_params& a, const render_params& b) {
  return a.sun_azimuth == b.sun_azimuth && a.sun_elevation == b.sun_elevation && a.physical_sky == b.physical_sky &&
         a.turbidity == b.turbidity && a.sun_color == b.sun_color && a.sun_intensity == b.sun_intensity &&
         a.sky_zenith == b.sky_zenith && a.sky_horizon == b.sky_horizon && a.ambient == b.ambient &&
         a.ground_color == b.ground_color;
}

void update_sky(renderer_gpu& r, const render_params& rp) {
  if (r.sky_valid && same_sky_inputs(r.sky_inputs, rp)) return;
  render_params& k = r.sky_inputs;
  k.sun_azimuth = rp.sun_azimuth, k.sun_elevation = rp.sun_elevation, k.physical_sky = rp.physical_sky;
  k.turbidity = rp.turbidity, k.sun_color = rp.sun_color, k.sun_intensity = rp.sun_intensity;
  k.sky_zenith = rp.sky_zenith, k.sky_horizon = rp.sky_horizon, k.ambient = rp.ambient, k.ground_color = rp.ground_color;
  compute_sky(rp, r.daylight);
  r.sky_valid = true;
}

void set_sky_uniforms(const renderer_gpu& r, const gl_program& p) {
  static const char* const perez_names[5] = {"u_perez[0]", "u_perez[1]", "u_perez[2]", "u_perez[3]", "u_perez[4]"};
  set_uniform(p, "u_physical", r.daylight.physical ? 1 : 0);
  for (int k = 0; k < 5; ++k) set_uniform(p, perez_names[k], r.daylight.perez[k]);
  set_uniform(p, "u_zenith", r.daylight.zenith);
  set_uniform(p, "u_perez_zenith", r.daylight.perez_zenith);
  set_uniform(p, "u_sky_scale", r.daylight.scale);
  set_uniform(p, "u_sky_zenith", r.daylight.legacy_zenith);
  set_uniform(p, "u_sky_horizon", r.daylight.legacy_horizon);
}

double now_ms() {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

void bind_tree_textures(const renderer_gpu& r) {
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, r.bark_tex.id);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, r.shadow_tex.id);
  glActiveTexture(GL_TEXTURE2);
  glBindTexture(GL_TEXTURE_BUFFER, r.node_radius_tex.id);
  glActiveTexture(GL_TEXTURE3);
  glBindTexture(GL_TEXTURE_2D_ARRAY, r.leaf_tex.id);
  glActiveTexture(GL_TEXTURE4);
  glBindTexture(GL_TEXTURE_2D, r.bark_normal_tex.id);
  glActiveTexture(GL_TEXTURE5);
  glBindTexture(GL_TEXTURE_2D_ARRAY, r.leaf_normal_tex.id);
  glActiveTexture(GL_TEXTURE6);
  glBindTexture(GL_TEXTURE_2D_ARRAY, r.leaf_thickness_tex.id);
  glActiveTexture(GL_TEXTURE7);
  glBindTexture(GL_TEXTURE_2D, r.bark_rough_tex.id);
  glActiveTexture(GL_TEXTURE9);   // unit 8 is the wind's (render/gl/wind_gl.cpp)
  glBindTexture(GL_TEXTURE_BUFFER, r.blade_tex.id);
  glActiveTexture(GL_TEXTURE0);
}

void draw_bark(renderer_gpu& r) {
  uint32_t n = r.index_end.empty() ? 0 : r.index_end[std::clamp(r.step, 0, int(r.index_end.size()) - 1)];
  if (!n) return;
  ++r.counts.draw_calls;
  glBindVertexArray(r.bark_vao.id);
  glDrawElements(GL_TRIANGLES, GLsizei(n), GL_UNSIGNED_INT, nullptr);
}

uint32_t leaf_count(const renderer_gpu& r) {
  return r.leaf_end.empty() ? 0 : r.leaf_end[std::clamp(r.step, 0, int(r.leaf_end.size()) - 1)];
}

// All leaf textures live in one array texture, so every leaf is drawn in a single instanced call.
// The season's leaf colours, fallen share and size (render/mesh/season.h), for the leaf vertex shader.
void set_season_uniforms(const gl_program& p, const season_look& s) {
  set_uniform(p, "u_leaf_color", s.evergreen_color);
  set_uniform(p, "u_autumn_a", s.deciduous_color_a);
  set_uniform(p, "u_autumn_b", s.deciduous_color_b);
  glUniform2ui(glGetUniformLocation(p.id, "u_deciduous"), uint32_t(s.deciduous_mask), uint32_t(s.deciduous_mask >> 32));
  glUniform1ui(glGetUniformLocation(p.id, "u_fruit"), fruit_archetype_mask());
  set_uniform(p, "u_keep", s.deciduous_keep);
  set_uniform(p, "u_season_scale", s.deciduous_scale);
}

void draw_leaves(renderer_gpu& r, const gl_program& p) {
  uint32_t n = leaf_count(r);
  if (!n) return;
  ++r.counts.draw_calls;
  ++r.counts.leaf_draw_calls;
  glBindVertexArray(r.leaf_vao.id);
  const bool bent = r.blade_shown.on && !r.blade_flat_shown, shoots = bent && r.has_shoots;
  glUniform1ui(glGetUniformLocation(p.id, "u_shoots"), shoots ? shoot_archetype_mask() : 0u);
  glUniform1i(glGetUniformLocation(p.id, "u_shoot_pass"), 0);
  // Every leaf is its archetype's coarse blade grid (render/mesh/leaf_blade.h); when none bends, the flat
  // card's two triangles after the grid's in the same index buffer.
  constexpr size_t grid = 3 * coarse_blade_triangles, card = 6;
  if (bent)
    glDrawElementsInstanced(GL_TRIANGLES, GLsizei(grid), GL_UNSIGNED_SHORT, nullptr, GLsizei(n));
  else
    glDrawElementsInstanced(GL_TRIANGLES, GLsizei(card), GL_UNSIGNED_SHORT, (void*)(sizeof(uint16_t) * grid), GLsizei(n));
  if (!shoots) return;
  // The needle shoots (render/mesh/leaf_shoot.h): a second call with their spikes, where the first
  // collapsed them and this one collapses every other leaf.
  ++r.counts.draw_calls;
  ++r.counts.leaf_draw_calls;
  glUniform1i(glGetUniformLocation(p.id, "u_shoot_pass"), 1);
  glDrawElementsInstanced(GL_TRIANGLES, 3 * shoot_triangles_coarse, GL_UNSIGNED_SHORT, (void*)(sizeof(uint16_t) * (grid + card)), GLsizei(n));
}

// ---------------------------------------------------------------- passes of the frame

// Pass times for renderer_gpu::timings: each mark closes a pass with glFinish (benchmarks only).
struct pass_clock {
  bool on = false;
  double t0 = 0;
  void mark(double& slot) {
    if (!on) return;
    glFinish();
    const double t = now_ms();
    slot = t - t0;
    t0 = t;
  }
};

// What every pass of one frame shares: the camera, the sun and its shadow map, the fog.
struct frame_setup {
  glm::vec3 sun{0}, eye{0};
  float scene = 1, ground_extent = 30, far_plane = 100;
  glm::mat4 viewproj{1}, inv_viewproj{1}, light{1};
  float texel_world = 0;
  bool lit_ok = false;
  season_look season;
  float sky_distance = 0, fog_density = 0, haze = 0, fog_height = 1;
  int width = 0, height = 0, hw = 1, hh = 1;   // the frame, and the shafts' half resolution
  wind_frame wind;                              // the sway of this frame, for every program that sways
  mutable pass_clock clock;
};

frame_setup setup_frame(renderer_gpu& r, const render_params& rp, const orbit_camera& cam, int width, int height) {
  frame_setup f;
  f.clock.on = r.measure_passes;
  f.clock.t0 = now_ms();
  f.width = width, f.height = height;
  f.sun = sun_direction(rp);
  f.eye = camera_eye(cam);
  f.scene = std::max(glm::length(r.bounds_max - r.bounds_min), 1.0f);
  f.ground_extent = std::max(30.0f, f.scene * 10.0f);
  const float near_plane = std::max(cam.distance * 0.01f, 0.005f);
  f.far_plane = cam.distance + f.ground_extent * 3.0f;
  f.viewproj = camera_projection(cam, float(width) / float(height), near_plane, f.far_plane) * camera_view(cam);
  f.inv_viewproj = glm::inverse(f.viewproj);
  f.wind = wind_frame_of(r, rp);
  r.wind_reach = wind_reach(r, f.wind);
  f.light = light_viewproj(r, f.sun, &f.texel_world);
  f.lit_ok = !r.shared->bark.failed && !r.shared->leaf.failed;
  f.season = with_card_seasons(season_leaf_look(rp), r.cards.get());   // baked cards fall with their leaves
  // Rays that meet no surface cross fog only to a little past the tree: the sky model already holds
  // the atmosphere beyond.
  f.sky_distance = cam.distance + f.scene;
  f.fog_density = std::clamp(rp.fog_density, 0.0f, 1.0f), f.haze = std::clamp(rp.haze, 0.0f, 0.1f);
  f.fog_height = std::clamp(rp.fog_height, 0.1f, 100.0f);
  f.hw = std::max(1, width / 2), f.hh = std::max(1, height / 2);
  return f;
}

// Which light shafts this frame draws, and where the sun is on screen for the radial ones.
struct shaft_choice {
  bool rays = false, volumetric = false;
  float ray_fade = 0;
  glm::vec4 sun_clip{0};
};

shaft_choice choose_shafts(const renderer_gpu& r, const render_params& rp, const orbit_camera& cam, const frame_setup& f) {
  shaft_choice sh;
  sh.sun_clip = f.viewproj * glm::vec4(f.eye + f.sun * f.far_plane * 0.5f, 1.0f);
  const glm::vec3 fwd = camera_basis_of(cam).forward;
  // Rays fade out as the sun leaves the view or goes behind the camera.
  sh.ray_fade = std::clamp((glm::dot(fwd, f.sun) - 0.1f) / 0.4f, 0.0f, 1.0f);
  sh.ray_fade *= std::clamp((f.sun.y + 0.05f) / 0.1f, 0.0f, 1.0f);
  sh.rays = rp.shafts == light_shafts::radial && sh.ray_fade > 0 && sh.sun_clip.w > 0 && !r.shared->occlusion.failed &&
            !r.shared->radial.failed;
  sh.volumetric = rp.shafts == light_shafts::volumetric && !r.shared->march.failed;
  return sh;
}

// 1. Shadow pass: depth from the sun, back faces, slope-scaled bias.
void draw_shadow_pass(renderer_gpu& r, const render_params& rp, const frame_setup& f) {
  const glm::mat4& light = f.light;
  const bool lit_ok = f.lit_ok;
  const season_look& season = f.season;
  glBindFramebuffer(GL_FRAMEBUFFER, r.shadow_fbo.id);
  glViewport(0, 0, r.shadow_size, r.shadow_size);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glClear(GL_DEPTH_BUFFER_BIT);
  if (rp.shadows && r.has_tree && lit_ok) {
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(rp.shadow_slope_bias, 1.0f);
    glEnable(GL_CULL_FACE);
    glCullFace(GL_FRONT);
    glUseProgram(r.shared->bark_depth.id);
    set_uniform(r.shared->bark_depth, "u_viewproj", light);
    set_uniform(r.shared->bark_depth, "u_radius", 2);
    set_wind_uniforms(r, r.shared->bark_depth, f.wind);
    draw_bark(r);
    glDisable(GL_CULL_FACE);
    glUseProgram(r.shared->leaf_depth.id);   // leaves cast alpha-tested shadows
    set_uniform(r.shared->leaf_depth, "u_viewproj", light);
    set_uniform(r.shared->leaf_depth, "u_step", r.step);
    set_uniform(r.shared->leaf_depth, "u_radius", 2);
    set_uniform(r.shared->leaf_depth, "u_leaf", 3);
    set_uniform(r.shared->leaf_depth, "u_blade", 9);
    set_uniform(r.shared->leaf_depth, "u_layers", r.leaf_layers);
    set_uniform(r.shared->leaf_depth, "u_cutoff", rp.alpha_cutoff);
    set_uniform(r.shared->leaf_depth, "u_shadow_pass", 1);   // the impostor's sun card casts (render/gl/impostor.h)
    set_wind_uniforms(r, r.shared->leaf_depth, f.wind);
    set_season_uniforms(r.shared->leaf_depth, season);
    draw_leaves(r, r.shared->leaf_depth);
    glDisable(GL_POLYGON_OFFSET_FILL);
  }
  f.clock.mark(r.timings.shadow);
}

// 2. Lit pass into the linear HDR target (multisampled, then resolved, when MSAA is on): sky, ground,
// tree and the growth-debug overlays.
void draw_lit_pass(renderer_gpu& r, const render_params& rp, const frame_setup& f, const overlay_view* overlays) {
  const glm::vec3& sun = f.sun;
  const glm::vec3& eye = f.eye;
  const float ground_extent = f.ground_extent;
  const glm::mat4& viewproj = f.viewproj;
  const glm::mat4& inv_viewproj = f.inv_viewproj;
  const glm::mat4& light = f.light;
  const float texel_world = f.texel_world;
  const bool lit_ok = f.lit_ok;
  const season_look& season = f.season;
  const int width = f.width;
  const int height = f.height;
  glBindFramebuffer(GL_FRAMEBUFFER, r.samples > 1 ? r.msaa_fbo.id : r.hdr_fbo.id);
  glViewport(0, 0, width, height);
  glClearColor(0, 0, 0, 1);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  if (!r.shared->sky.failed) {   // sky first, without depth, so the depth buffer stays 1 where sky shows
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glUseProgram(r.shared->sky.id);
    set_uniform(r.shared->sky, "u_inv_viewproj", inv_viewproj);
    set_uniform(r.shared->sky, "u_eye", eye);
    set_uniform(r.shared->sky, "u_sun_dir", sun);
    set_sky_uniforms(r, r.shared->sky);
    set_uniform(r.shared->sky, "u_sun_light", r.daylight.sun_light);
    glBindVertexArray(r.empty_vao.id);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    ++r.counts.draw_calls;
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
  }
  if (rp.ground && !r.shared->ground.failed) {
    glUseProgram(r.shared->ground.id);
    set_lighting(r, r.shared->ground, rp, sun, light, texel_world);
    set_uniform(r.shared->ground, "u_viewproj", viewproj);
    glm::vec3 center = 0.5f * (r.bounds_min + r.bounds_max);
    set_uniform(r.shared->ground, "u_center", center);
    set_uniform(r.shared->ground, "u_extent", ground_extent);
    set_uniform(r.shared->ground, "u_sky_horizon", r.daylight.horizon);
    set_uniform(r.shared->ground, "u_ground_color", rp.ground_color);
    set_uniform(r.shared->ground, "u_root", r.root);
    set_uniform(r.shared->ground, "u_root_radius", r.has_tree ? r.root_radius : 0.0f);
    const glm::vec3 half = 0.5f * (r.bounds_max - r.bounds_min);
    set_uniform(r.shared->ground, "u_crown_radius", r.has_tree ? glm::vec2(half.x, half.z) : glm::vec2(0.0f));
    glBindVertexArray(r.empty_vao.id);
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    glDisable(GL_BLEND);
    ++r.counts.draw_calls;
  }
  if (r.has_tree) {
    if (lit_ok) {
      glEnable(GL_CULL_FACE);
      glCullFace(GL_BACK);
      glUseProgram(r.shared->bark.id);
      set_lighting(r, r.shared->bark, rp, sun, light, texel_world);
      set_uniform(r.shared->bark, "u_viewproj", viewproj);
      set_uniform(r.shared->bark, "u_radius", 2);
      set_uniform(r.shared->bark, "u_bark", 0);
      set_uniform(r.shared->bark, "u_bark_normal", 4);
      set_uniform(r.shared->bark, "u_bark_rough", 7);
      set_uniform(r.shared->bark, "u_eye", eye);
      set_bark_tint_uniforms(r.shared->bark, rp);
      set_wind_uniforms(r, r.shared->bark, f.wind);
      draw_bark(r);
      glDisable(GL_CULL_FACE);
      glUseProgram(r.shared->leaf.id);
      set_lighting(r, r.shared->leaf, rp, sun, light, texel_world);
      set_uniform(r.shared->leaf, "u_viewproj", viewproj);
      set_uniform(r.shared->leaf, "u_step", r.step);
      set_uniform(r.shared->leaf, "u_radius", 2);
      set_uniform(r.shared->leaf, "u_variation", rp.leaf_color_variation);
      set_uniform(r.shared->leaf, "u_sun_tone", rp.leaf_sun_tone);
      set_uniform(r.shared->leaf, "u_leaf", 3);
      set_uniform(r.shared->leaf, "u_blade", 9);
      set_uniform(r.shared->leaf, "u_layers", r.leaf_layers);
      set_uniform(r.shared->leaf, "u_leaf_normal", 5);
      set_uniform(r.shared->leaf, "u_leaf_thickness", 6);
      set_season_uniforms(r.shared->leaf, season);
      set_uniform(r.shared->leaf, "u_cutoff", rp.alpha_cutoff);
      set_uniform(r.shared->leaf, "u_translucency", rp.leaf_translucency);
      set_uniform(r.shared->leaf, "u_crown_centre", r.crown_centre);
      set_uniform(r.shared->leaf, "u_crown_radii", r.crown_radii);
      set_uniform(r.shared->leaf, "u_normal_blend", rp.leaf_normal_blend);
      set_wind_uniforms(r, r.shared->leaf, f.wind);
      draw_leaves(r, r.shared->leaf);
    } else if (!r.shared->fallback.failed) {   // a lit shader failed: flat bark, still a tree
      glUseProgram(r.shared->fallback.id);
      set_uniform(r.shared->fallback, "u_viewproj", viewproj);
      set_uniform(r.shared->fallback, "u_radius", 2);
      set_uniform(r.shared->fallback, "u_color", rp.bark_color);
      set_wind_uniforms(r, r.shared->fallback, f.wind);
      draw_bark(r);
    }
  }
  if (overlays) {   // the caller's choice of growth-debug layers
    if (sync_overlays(r.overlay)) ++r.uploads_total;
    r.counts.draw_calls += draw_overlays(r.overlay, *overlays, viewproj, r.step);
  }
  if (r.samples > 1) {   // resolve colour and depth: the occlusion pass reads the depth
    glBindFramebuffer(GL_READ_FRAMEBUFFER, r.msaa_fbo.id);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, r.hdr_fbo.id);
    glBlitFramebuffer(0, 0, width, height, 0, 0, width, height, GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
  }
  f.clock.mark(r.timings.lit);
}

// 3a. Radial shafts: occlusion at half resolution, then the blur toward the sun (only while the sun is
// in view).
void draw_radial_shafts(renderer_gpu& r, const render_params& rp, const frame_setup& f, const shaft_choice& sh) {
  const glm::vec3& sun = f.sun;
  const glm::vec3& eye = f.eye;
  const glm::mat4& inv_viewproj = f.inv_viewproj;
  const int hw = f.hw;
  const int hh = f.hh;
  const glm::vec2 light_uv = glm::vec2(sh.sun_clip.x, sh.sun_clip.y) / sh.sun_clip.w * 0.5f + 0.5f;
  glBindFramebuffer(GL_FRAMEBUFFER, r.occlusion_fbo.id);
  glViewport(0, 0, hw, hh);
  glUseProgram(r.shared->occlusion.id);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, r.hdr_depth.id);
  set_uniform(r.shared->occlusion, "u_depth", 0);
  set_uniform(r.shared->occlusion, "u_inv_viewproj", inv_viewproj);
  set_uniform(r.shared->occlusion, "u_eye", eye);
  set_uniform(r.shared->occlusion, "u_sun_dir", sun);
  const float sun_max = std::max({r.daylight.sun_light.x, r.daylight.sun_light.y, r.daylight.sun_light.z, 1e-6f});
  set_uniform(r.shared->occlusion, "u_sun_color", r.daylight.sun_light / sun_max);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  ++r.counts.draw_calls;
  f.clock.mark(r.timings.occlusion);

  glBindFramebuffer(GL_FRAMEBUFFER, r.rays_fbo.id);
  glUseProgram(r.shared->radial.id);
  glBindTexture(GL_TEXTURE_2D, r.occlusion_tex.id);
  set_uniform(r.shared->radial, "u_occlusion", 0);
  set_uniform(r.shared->radial, "u_light_uv", light_uv);
  set_uniform(r.shared->radial, "u_samples", std::clamp(rp.ray_samples, 1, 256));
  set_uniform(r.shared->radial, "u_density", rp.ray_density);
  set_uniform(r.shared->radial, "u_weight", rp.ray_weight);
  set_uniform(r.shared->radial, "u_decay", rp.ray_decay);
  set_uniform(r.shared->radial, "u_exposure", rp.ray_exposure);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  ++r.counts.draw_calls;
  f.clock.mark(r.timings.blur);
}

// 3b. Volumetric shafts: the fog's shadowed optical depth per half-resolution pixel.
void draw_volumetric_shafts(renderer_gpu& r, const render_params& rp, const frame_setup& f) {
  const glm::vec3& sun = f.sun;
  const glm::vec3& eye = f.eye;
  const glm::mat4& inv_viewproj = f.inv_viewproj;
  const glm::mat4& light = f.light;
  const float sky_distance = f.sky_distance;
  const float fog_density = f.fog_density;
  const float haze = f.haze;
  const float fog_height = f.fog_height;
  const int hw = f.hw;
  const int hh = f.hh;
  glBindFramebuffer(GL_FRAMEBUFFER, r.march_fbo.id);
  glViewport(0, 0, hw, hh);
  glUseProgram(r.shared->march.id);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, r.hdr_depth.id);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, r.shadow_tex.id);
  set_uniform(r.shared->march, "u_depth", 0);
  set_uniform(r.shared->march, "u_shadow", 1);
  set_uniform(r.shared->march, "u_inv_viewproj", inv_viewproj);
  set_uniform(r.shared->march, "u_eye", eye);
  set_uniform(r.shared->march, "u_sun_dir", sun);
  set_uniform(r.shared->march, "u_light_viewproj", light);
  // Without shadows nothing is shadowed: zero samples leave the fog uniformly lit.
  set_uniform(r.shared->march, "u_samples", rp.shadows && r.has_tree ? std::clamp(rp.shaft_samples, 1, 256) : 0);
  set_uniform(r.shared->march, "u_fog_density", fog_density);
  set_uniform(r.shared->march, "u_fog_height", fog_height);
  set_uniform(r.shared->march, "u_haze", haze);
  set_uniform(r.shared->march, "u_sky_distance", sky_distance);
  set_uniform(r.shared->march, "u_bias", rp.shadow_bias);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  ++r.counts.draw_calls;
  f.clock.mark(r.timings.march);
}

// 4. The frame's log-average luminance, 1 x 1, for auto exposure.
void draw_exposure_pass(renderer_gpu& r, const frame_setup& f) {
  glBindFramebuffer(GL_FRAMEBUFFER, r.average_fbo.id);
  glViewport(0, 0, 1, 1);
  glUseProgram(r.shared->exposure.id);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, r.hdr_color.id);
  set_uniform(r.shared->exposure, "u_hdr", 0);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  ++r.counts.draw_calls;
  f.clock.mark(r.timings.exposure);
}

// 5. Composite: fog and shafts, exposure, tonemap, into the target.
void draw_composite_pass(renderer_gpu& r, const render_params& rp, const frame_setup& f,
                         const shaft_choice& sh, gl_framebuffer target, glm::ivec2 origin) {
  const glm::vec3& sun = f.sun;
  const glm::vec3& eye = f.eye;
  const glm::mat4& inv_viewproj = f.inv_viewproj;
  const float sky_distance = f.sky_distance;
  const float fog_density = f.fog_density;
  const float haze = f.haze;
  const float fog_height = f.fog_height;
  const int width = f.width;
  const int height = f.height;
  glBindFramebuffer(GL_FRAMEBUFFER, target.id);
  glViewport(origin.x, origin.y, width, height);
  glUseProgram(r.shared->composite.id);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, r.hdr_color.id);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, r.rays_tex.id);
  glActiveTexture(GL_TEXTURE2);
  glBindTexture(GL_TEXTURE_2D, r.march_tex.id);
  glActiveTexture(GL_TEXTURE3);
  glBindTexture(GL_TEXTURE_2D, r.hdr_depth.id);
  glActiveTexture(GL_TEXTURE4);
  glBindTexture(GL_TEXTURE_2D, r.average_tex.id);
  set_uniform(r.shared->composite, "u_hdr", 0);
  set_uniform(r.shared->composite, "u_rays", 1);
  set_uniform(r.shared->composite, "u_march", 2);
  set_uniform(r.shared->composite, "u_depth", 3);
  set_uniform(r.shared->composite, "u_average", 4);
  set_uniform(r.shared->composite, "u_ray_strength", sh.rays ? sh.ray_fade : 0.0f);
  set_uniform(r.shared->composite, "u_exposure", rp.exposure);
  set_uniform(r.shared->composite, "u_auto_exposure", rp.auto_exposure && !r.shared->exposure.failed ? 1 : 0);
  set_uniform(r.shared->composite, "u_volumetric", sh.volumetric ? 1 : 0);
  set_uniform(r.shared->composite, "u_inv_viewproj", inv_viewproj);
  set_uniform(r.shared->composite, "u_eye", eye);
  set_uniform(r.shared->composite, "u_sun_dir", sun);
  set_uniform(r.shared->composite, "u_fog_density", fog_density);
  set_uniform(r.shared->composite, "u_fog_height", fog_height);
  set_uniform(r.shared->composite, "u_haze", haze);
  set_uniform(r.shared->composite, "u_sky_distance", sky_distance);
  set_uniform(r.shared->composite, "u_g", std::clamp(rp.scattering_g, -0.95f, 0.95f));
  set_uniform(r.shared->composite, "u_sun_light", r.daylight.sun_light);
  set_uniform(r.shared->composite, "u_fog_ambient", r.daylight.fog_ambient);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  ++r.counts.draw_calls;
  glActiveTexture(GL_TEXTURE0);
  glUseProgram(0);
  glBindVertexArray(0);
  f.clock.mark(r.timings.composite);
}

}  // namespace

// ---------------------------------------------------------------- the frame

void draw_frame(renderer_gpu& r, const render_params& rp, const orbit_camera& cam, int width, int height,
                gl_framebuffer target, const overlay_view* overlays, glm::ivec2 origin) {
  if (width <= 0 || height <= 0 || !r.shared) return;
  r.counts = {};
  const uint64_t uploads_before = r.uploads_total;
  resize_targets(r, width, height, rp.msaa);
  update_user_textures(r, rp);
  resize_shadow(r, std::clamp(rp.shadow_resolution, 256, 8192));
  update_sky(r, rp);
  const frame_setup f = setup_frame(r, rp, cam, width, height);
  r.triangles_drawn = r.index_end.empty() ? 0 : r.index_end[std::clamp(r.step, 0, int(r.index_end.size()) - 1)] / 3;
  r.leaves_drawn = leaf_count(r);
  glBindVertexArray(r.empty_vao.id);
  bind_tree_textures(r);
  if (!(r.keep_shadow && r.shadow_drawn)) draw_shadow_pass(r, rp, f);
  r.shadow_drawn = true;
  draw_lit_pass(r, rp, f, overlays);
  glDisable(GL_DEPTH_TEST);   // the passes from here on draw full-screen triangles
  glBindVertexArray(r.empty_vao.id);
  const shaft_choice sh = choose_shafts(r, rp, cam, f);
  r.timings.occlusion = r.timings.blur = r.timings.march = r.timings.exposure = 0;
  if (sh.rays) draw_radial_shafts(r, rp, f, sh);
  if (sh.volumetric) draw_volumetric_shafts(r, rp, f);
  if (rp.auto_exposure && !r.shared->exposure.failed) draw_exposure_pass(r, f);
  draw_composite_pass(r, rp, f, sh, target, origin);
  r.counts.uploads = int(r.uploads_total - uploads_before);
  check_gl("draw frame");
}

}  // namespace sylva
