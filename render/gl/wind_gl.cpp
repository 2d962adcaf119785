// Wind in the viewport: the per-node table upload and the per-frame uniforms.
#include "render/gl/wind_gl.h"

#include <algorithm>
#include <string>

#include "render/gl/renderer.h"
#include "render/mesh/wind.h"

namespace sylva {

constexpr int wind_texture_unit = 8;   // units 0-7 hold the tree's textures and the shadow map

void upload_wind(renderer_gpu& r, const tree_skeleton& t) {
  const wind_rig rig = build_wind_rig(t);
  if (!r.wind_nodes.id) glGenBuffers(1, &r.wind_nodes.id);
  if (!r.wind_tex.id) glGenTextures(1, &r.wind_tex.id);
  glBindBuffer(GL_TEXTURE_BUFFER, r.wind_nodes.id);
  const size_t bytes = rig.nodes.size() * sizeof(wind_node);
  glBufferData(GL_TEXTURE_BUFFER, std::max<size_t>(bytes, 48), bytes ? rig.nodes.data() : nullptr, GL_STATIC_DRAW);
  glBindTexture(GL_TEXTURE_BUFFER, r.wind_tex.id);
  glTexBuffer(GL_TEXTURE_BUFFER, GL_RGBA32F, r.wind_nodes.id);
  glBindTexture(GL_TEXTURE_BUFFER, 0);
  glBindBuffer(GL_TEXTURE_BUFFER, 0);
  ++r.uploads_total;
  r.wind_node_count = int(rig.nodes.size());
  r.wind_ground = rig.ground;
  r.wind_height = rig.height;
  check_gl("upload wind");
}

std::string with_wind_glsl(const char* vertex_src) {
  std::string s(vertex_src);
  const size_t eol = s.find('\n');
  return eol == std::string::npos ? s : s.substr(0, eol + 1) + wind_glsl() + s.substr(eol + 1);
}

wind_frame wind_frame_of(renderer_gpu& r, const render_params& rp) {
  wind_frame w;
  w.motion = make_wind_motion(rp.wind);
  ++r.counts.wind_motions;
  const wind_motion& m = w.motion;
  w.on = m.strength > 0 && r.wind_node_count >= r.node_count && r.wind_node_count > 0 && r.wind_tex.id;
  w.time = r.wind_time;
  if (w.on) {
    w.gust = wind_gust(m, w.time);
    w.trunk = wind_trunk_angle(m, w.time);
  }
  return w;
}

float wind_reach(const renderer_gpu& r, const wind_frame& w) {
  const wind_motion& m = w.motion;
  if (m.strength <= 0 || r.wind_node_count == 0) return 0.0f;
  // Trunk: tip offset theta H / 2 at the strongest gust; branches: a share of the height that
  // grows with the strength (their angles are capped at 0.8 rad, their lengths well under H).
  const float gust = 1.0f + m.gustiness;
  return r.wind_height * std::min(0.5f, 0.05f * m.strength * gust * 0.5f + 0.08f * m.strength * gust);
}

void set_wind_uniforms(const renderer_gpu& r, const gl_program& p, const wind_frame& w) {
  const wind_motion& m = w.motion;
  set_uniform(p, "u_wind_on", w.on ? 1 : 0);
  set_uniform(p, "u_wind", wind_texture_unit);   // always: a buffer sampler may not share unit 0 with a 2D one
  if (!w.on) return;
  glActiveTexture(GL_TEXTURE0 + wind_texture_unit);
  glBindTexture(GL_TEXTURE_BUFFER, r.wind_tex.id);
  glActiveTexture(GL_TEXTURE0);
  set_uniform(p, "u_wind_time", w.time);
  set_uniform(p, "u_wind_strength", m.strength);
  set_uniform(p, "u_wind_gust", w.gust);
  set_uniform(p, "u_wind_trunk", w.trunk);
  set_uniform(p, "u_wind_toward", m.toward);
  set_uniform(p, "u_wind_axis", m.bend_axis);
  set_uniform(p, "u_wind_branch_hz", m.branch_hz);
  set_uniform(p, "u_wind_leaf_hz", m.leaf_hz);
  set_uniform(p, "u_wind_flutter", m.flutter);
  set_uniform(p, "u_wind_ground", r.wind_ground);
  set_uniform(p, "u_wind_height", r.wind_height);
}

}  // namespace sylva
