// The editor's LOD choice (issue 17).
#include "app/editor_lod.h"

#include <chrono>
#include <cmath>
#include <cstdio>

#include <glm/geometric.hpp>

#include "generators/timing.h"

namespace sylva {

void editor_lod_new_tree(editor_lod& s) {
  s.chain.reset();
  s.built_for = nullptr;
  s.uploaded = 0;
  s.wanted = 0;
  s.impostor.reset();
  s.impostor_error.clear();
  s.tree_time = std::chrono::steady_clock::now();
}

void editor_lod_update(editor_lod& s, renderer_gpu& r, const tree_skeleton& t, const tree_mesh& m,
                       const mesh_params& mp, const render_params& rp, const orbit_camera& cam, int step) {
  const lod_params& p = rp.lod;
  const bool budgets_changed = p.lod1_budget != s.built_params.lod1_budget || p.lod2_budget != s.built_params.lod2_budget ||
                               p.lod3_budget != s.built_params.lod3_budget;
  const auto t0 = std::chrono::steady_clock::now();
  if (!s.chain && ms_between(s.tree_time, t0) < editor_lod_settle_ms) return;
  if (!s.chain || s.built_for != &m || budgets_changed) {
    s.chain = std::make_unique<lod_chain>(build_lods(t, m, mp, p));
    s.build_ms = ms_since(t0);
    s.built_for = &m;
    s.built_params = p;
    if (s.uploaded != 0) s.uploaded = -1;   // the uploaded level is stale: upload again
    s.impostor.reset();
    s.impostor_error.clear();
  }
  // The bounding sphere's size on screen picks the level; scrubbing the growth shows LOD0.
  const glm::vec3 half = 0.5f * (m.bounds_max - m.bounds_min);
  const glm::vec3 centre = 0.5f * (m.bounds_max + m.bounds_min);
  const float distance = glm::length(camera_eye(cam) - centre);
  const float coverage = screen_coverage(glm::length(half), distance, cam.fov);
  s.wanted = p.show >= 0 ? std::min(p.show, lod_levels) : pick_lod(*s.chain, coverage, p.bias);
  int level = step < t.steps ? 0 : s.wanted;
  const glm::vec3 eye = camera_eye(cam) - centre;
  const float azimuth = glm::degrees(std::atan2(eye.x, eye.z));   // from +Z toward +X, as the atlas's views
  // A new atlas when what it was rendered with changes (its views, size, tints or cut-off).
  const render_params& ip = s.impostor_params;
  if (s.impostor && (ip.lod.impostor_views != p.impostor_views || ip.lod.impostor_size != p.impostor_size ||
                     ip.leaf_color != rp.leaf_color || ip.bark_color != rp.bark_color || ip.alpha_cutoff != rp.alpha_cutoff)) {
    s.impostor.reset();
    s.impostor_error.clear();
    if (s.uploaded == lod_levels) s.uploaded = -1;
  }
  if (level == lod_levels && !s.impostor && s.impostor_error.empty()) {
    // Rendered once per chain from LOD0, then kept as leaf layers.
    upload_tree(r, m);
    set_tree_step(r, t, mp.min_radius, t.steps);
    s.atlas = render_impostor(r, rp, p.impostor_views, p.impostor_size);
    s.impostor_params = rp;
    s.uploaded = 0;
    if (s.atlas.error.empty()) s.impostor = impostor_layers(s.atlas);
    else s.impostor_error = s.atlas.error;
    s.atlas.color.clear(), s.atlas.color.shrink_to_fit(), s.atlas.normal.clear(), s.atlas.normal.shrink_to_fit();
  }
  // No impostor, or the user's own leaf texture replacing every leaf layer (the atlas views too):
  // LOD3 stands in.
  if (level == lod_levels && (!s.impostor || r.user_leaf)) level = lod_levels - 1;
  if (level == lod_levels) {
    // The card turns with the camera; a new upload only when it has turned by a degree.
    if (s.uploaded == level && std::abs(azimuth - s.impostor_azimuth) < 1.0f) return;
    upload_tree(r, impostor_mesh(s.atlas, s.impostor, m, azimuth));
    set_tree_step(r, t, mp.min_radius, step);
    s.impostor_azimuth = azimuth;
    s.uploaded = level;
    return;
  }
  if (level == s.uploaded) return;
  upload_tree(r, level == 0 ? m : s.chain->level[size_t(level) - 1]);
  set_tree_step(r, t, mp.min_radius, step);
  s.uploaded = level;
}

std::string editor_lod_status(const editor_lod& s) {
  if (!s.chain) return "";
  char buf[200];
  const auto& n = s.chain->triangles;
  if (s.uploaded == lod_levels)
    std::snprintf(buf, sizeof buf, "Impostor (2 triangles)   LOD0-3 triangles %zu / %zu / %zu / %zu", n[0], n[1], n[2], n[3]);
  else
    std::snprintf(buf, sizeof buf, "LOD%d%s   LOD0-3 triangles %zu / %zu / %zu / %zu", std::max(s.uploaded, 0),
                  s.wanted >= lod_levels ? " (impostor distance; no impostor)" : "", n[0], n[1], n[2], n[3]);
  // Clamped budgets or a tree too small to reduce (build_lods says which).
  std::string out(buf);
  if (!s.impostor_error.empty()) out += "   (impostor: " + s.impostor_error + ")";
  return s.chain->message.empty() ? out : out + "   (" + s.chain->message + ")";
}

}  // namespace sylva
