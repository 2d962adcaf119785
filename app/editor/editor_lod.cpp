// The editor's LOD choice.
#include "app/editor/editor_lod.h"

#include <chrono>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glm/geometric.hpp>

#include "generators/timing.h"

namespace sylva {
namespace {

// Forgets the impostor and any atlas in progress.
void drop_impostor(editor_lod& s) {
  impostor_cancel(s.build);
  s.build_read = false;
  s.impostor.reset();
  s.impostor_error.clear();
}

// One frame's share of the atlas: begin, one view, the read-back, or the layers; all that is left
// when `force` ("Show LOD" 4 wants it now).
void advance_impostor(editor_lod& s, renderer_gpu& r, const tree_mesh& m, const render_params& rp, bool force) {
  using st = impostor_build::state;
  const auto t0 = std::chrono::steady_clock::now();
  const bool fresh = s.build.st == st::idle && !s.build_read;
  do {
    if (s.build_read) {
      s.atlas = std::move(s.build.atlas);
      s.impostor = impostor_layers(s.atlas);
      s.atlas.color.clear(), s.atlas.color.shrink_to_fit(), s.atlas.normal.clear(), s.atlas.normal.shrink_to_fit();
      s.build = impostor_build{};
      s.build_read = false;
    } else if (s.build.st == st::idle) {
      s.impostor_params = rp;
      impostor_begin(s.build, r, rp, rp.lod.impostor_views, rp.lod.impostor_size, &m);
    } else {
      impostor_step(s.build, r);
    }
    if (s.build.st == st::complete) s.build_read = true;
    if (s.build.st == st::failed) {
      s.impostor_error = s.build.atlas.error.empty() ? "impostor atlas failed" : s.build.atlas.error;
      impostor_cancel(s.build);
      s.build_read = false;
      return;
    }
  } while (force && !s.impostor);
  // This frame's share of the atlas work (the status bar shows the frames and the longest).
  if (fresh) s.atlas_frames = 0, s.atlas_worst_ms = 0;
  ++s.atlas_frames;
  s.atlas_worst_ms = std::max(s.atlas_worst_ms, ms_since(t0));
}

bool same_budgets(const lod_params& a, const lod_params& b) {
  return a.lod1_budget == b.lod1_budget && a.lod2_budget == b.lod2_budget && a.lod3_budget == b.lod3_budget;
}

}  // namespace

void editor_lod_new_tree(editor_lod& s) {
  s.chain.reset();
  s.built_for = nullptr;
  s.building = 0;   // a chain still building for the previous tree is dropped when it arrives
  s.building_for = nullptr;
  s.uploaded = 0;
  s.wanted = 0;
  drop_impostor(s);
  s.tree_time = std::chrono::steady_clock::now();
}

void editor_lod_update(editor_lod& s, renderer_gpu& r, const std::shared_ptr<const grow_result>& tree,
                       const render_params& rp, const orbit_camera& cam, int step) {
  const tree_skeleton& t = *tree->skeleton;
  const tree_mesh& m = tree->mesh;
  const mesh_params& mp = tree->mesh_settings;
  const lod_params& p = rp.lod;
  // A chain built off the UI thread has arrived: it replaces the one shown.
  if (s.building && s.builder)
    if (std::shared_ptr<const lod_result> res = take_lod_result(*s.builder); res && res->id == s.building) {
      s.chain = res->chain;
      s.build_ms = res->build_ms;
      s.built_for = s.building_for;
      s.built_params = s.building_params;
      s.building = 0;
      s.building_for = nullptr;
      if (s.uploaded != 0) s.uploaded = -1;   // the uploaded level is stale: upload again
      drop_impostor(s);
    }
  const auto t0 = std::chrono::steady_clock::now();
  if (!s.chain && ms_between(s.tree_time, t0) < editor_lod_settle_ms) return;
  const bool this_tree = s.chain && s.built_for == &m;
  if (!this_tree || !same_budgets(p, s.built_params)) {
    if (!(s.building && s.building_for == &m && same_budgets(p, s.building_params))) {   // not asked for yet
      if (!s.builder) s.builder = std::make_unique<lod_worker>();
      s.building = post_lod_request(*s.builder, tree->skeleton, std::shared_ptr<const tree_mesh>(tree, &tree->mesh), mp, p);
      s.building_for = &m;
      s.building_params = p;
    }
    if (!this_tree) return;   // LOD0 shows until this tree's chain arrives; new budgets keep the previous chain
  }
  // The bounding sphere's size on screen picks the level; scrubbing the growth shows LOD0.
  const glm::vec3 half = 0.5f * (m.bounds_max - m.bounds_min);
  const glm::vec3 centre = 0.5f * (m.bounds_max + m.bounds_min);
  const float distance = glm::length(camera_eye(cam) - centre);
  const float coverage = screen_coverage(glm::length(half), distance, cam.fov);
  const int pick = pick_lod(*s.chain, coverage, p.bias);
  s.wanted = p.show >= 0 ? std::min(p.show, lod_levels) : pick;
  int level = step < t.steps ? 0 : s.wanted;
  const glm::vec3 eye = camera_eye(cam) - centre;
  const float azimuth = glm::degrees(std::atan2(eye.x, eye.z));   // from +Z toward +X, as the atlas's views
  const float sun = impostor_sun_azimuth(rp);
  // A new atlas when what it was (or is being) rendered with changes (its views, size, tints, cut-off or season).
  const render_params& ip = s.impostor_params;
  const bool atlas_started = s.impostor || s.build.st != impostor_build::state::idle;
  if (atlas_started && (ip.lod.impostor_views != p.impostor_views || ip.lod.impostor_size != p.impostor_size ||
                        ip.leaf_color != rp.leaf_color || ip.bark_color != rp.bark_color || ip.alpha_cutoff != rp.alpha_cutoff ||
                        // the season colours, thins and shrinks the leaves the atlas shows
                        ip.season != rp.season || ip.habit != rp.habit || ip.autumn_color != rp.autumn_color ||
                        ip.autumn_color_2 != rp.autumn_color_2)) {
    drop_impostor(s);
    if (s.uploaded == lod_levels) s.uploaded = -1;
  }
  // The atlas is built a view per frame from LOD2's distance on (coverage below LOD2's takeover), so
  // it is usually complete before LOD3 hands over; "Show LOD" 4 finishes it at once.
  const bool want_atlas = step >= t.steps && ((p.show < 0 && pick >= lod_levels - 2) || p.show == lod_levels);
  if (want_atlas && !s.impostor && s.impostor_error.empty())
    advance_impostor(s, r, m, rp, level == lod_levels && p.show == lod_levels);
  // No impostor, or the user's own leaf texture replacing every leaf layer (the atlas views too):
  // LOD3 stands in.
  if (level == lod_levels && (!s.impostor || r.user_leaf)) level = lod_levels - 1;
  if (level == lod_levels) {
    // The card turns with the camera, its shadow card with the sun; a new upload only when either
    // has turned by a degree.
    if (s.uploaded == level && std::abs(azimuth - s.impostor_azimuth) < 1.0f && std::abs(sun - s.impostor_sun) < 1.0f) return;
    upload_tree(r, impostor_mesh(s.atlas, s.impostor, m, azimuth, sun));
    set_tree_step(r, t, mp.min_radius, step);
    s.impostor_azimuth = azimuth;
    s.impostor_sun = sun;
    s.uploaded = level;
    return;
  }
  if (level == s.uploaded) return;
  upload_tree(r, level == 0 ? m : s.chain->level[size_t(level) - 1]);
  set_tree_step(r, t, mp.min_radius, step);
  s.uploaded = level;
}

std::string editor_lod_status(const editor_lod& s) {
  if (!s.chain) return s.building ? "LOD0   (building the LOD chain...)" : "";
  // The counts the exported file's _LODn meshes hold (lod_summary, as `sylva export --lods` prints).
  const std::string counts = lod_summary(*s.chain);
  char buf[200];
  if (s.uploaded == lod_levels)
    std::snprintf(buf, sizeof buf, "Impostor (2 triangles)   %s", counts.c_str());
  else
    std::snprintf(buf, sizeof buf, "LOD%d%s   %s", std::max(s.uploaded, 0),
                  s.wanted >= lod_levels ? " (impostor distance; no impostor)" : "", counts.c_str());
  // Clamped budgets or a tree too small to reduce (build_lods says which).
  std::string out(buf);
  if (!s.impostor_error.empty()) out += "   (impostor: " + s.impostor_error + ")";
  if (s.impostor && s.atlas_frames > 0) {
    char a[96];
    std::snprintf(a, sizeof a, "   (impostor atlas: %d frame%s, longest %.0f ms)", s.atlas_frames, s.atlas_frames == 1 ? "" : "s",
                  s.atlas_worst_ms);
    out += a;
  }
  if (s.build.st == impostor_build::state::rendering)
    out += "   (impostor atlas: " + std::to_string(s.build.next) + " of " + std::to_string(s.build.atlas.views) + " views)";
  if (s.building) out += "   (building the LOD chain...)";
  return s.chain->message.empty() ? out : out + "   (" + s.chain->message + ")";
}

bool editor_lod_wait(editor_lod& s, double timeout_ms) {
  return s.building && s.builder && wait_lod_result(*s.builder, s.building, timeout_ms);
}

}  // namespace sylva
