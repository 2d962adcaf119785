// The editor's level of detail: has the LOD chain of the shown tree built off the UI thread
// (app/common/worker.h lod_worker), picks the level by the tree's size on screen (or the "Show LOD"
// override) and keeps that level uploaded.
#pragma once

#include <chrono>
#include <memory>
#include <string>

#include "app/common/worker.h"
#include "render/gl/impostor.h"
#include "render/gl/renderer.h"
#include "render/mesh/lod.h"

namespace sylva {

struct editor_lod {
  std::shared_ptr<const lod_chain> chain;   // of `built_for`; rebuilt when the tree or the budgets change
  const tree_mesh* built_for = nullptr;
  lod_params built_params;
  // The chain being built off the UI thread: until it arrives, a new tree shows LOD0 and new
  // budgets the previous chain (the status bar says it is building).
  std::unique_ptr<lod_worker> builder;   // started with the first build
  uint32_t building = 0;                 // the request in progress (0: none)
  const tree_mesh* building_for = nullptr;
  lod_params building_params;
  int uploaded = 0;                   // the level in the renderer (0: the tree's own mesh; lod_levels: impostor)
  int wanted = 0;                     // the pick, lod_levels meaning the impostor
  // The impostor (render/gl/impostor.h), rendered from LOD0 a view per frame once the tree is seen
  // from LOD2's distance or farther (or "Show LOD" 4 asks for it); LOD3 shows until it is complete.
  impostor_build build;               // the atlas in progress (state idle once made or dropped)
  bool build_read = false;            // the atlas is read back; its layers are made the next frame
  impostor_atlas atlas;               // pixels dropped once the layers are made; geometry kept
  std::shared_ptr<const baked_card_textures> impostor;   // the atlas views as leaf layers
  float impostor_azimuth = 1e9f;      // the camera azimuth the uploaded card faces (degrees)
  float impostor_sun = 1e9f;          // the sun azimuth its shadow card faces (degrees)
  int atlas_frames = 0;               // frames the last atlas took (begin, views, read-back, layers)
  double atlas_worst_ms = 0;          // the longest of those frames' atlas work
  std::string impostor_error;         // why the impostor could not be made (LOD3 shows instead)
  render_params impostor_params;      // what the atlas was rendered with (views, size, tints, cut-off)
  double build_ms = 0;                // the last chain's build, on the builder's thread
  // The chain is built once a new tree has been shown this long, so that dragging a slider (a new
  // tree every few frames) does not rebuild it for each one; until then LOD0 shows.
  std::chrono::steady_clock::time_point tree_time{};
};
inline constexpr double editor_lod_settle_ms = 300;

// Call after upload_tree of a new tree: the renderer now holds LOD0 and the chain is stale. A
// half-built atlas is dropped (needs the GL context current).
void editor_lod_new_tree(editor_lod& s);
// Once a frame before drawing, with the tree shown (its skeleton, mesh and mesh settings; the
// chain's build keeps it alive). Levels apply at the final step only (scrubbing shows LOD0).
void editor_lod_update(editor_lod& s, renderer_gpu& r, const std::shared_ptr<const grow_result>& tree,
                       const render_params& rp, const orbit_camera& cam, int step);
// Waits up to `timeout_ms` for the chain being built (tests); the next update takes it.
bool editor_lod_wait(editor_lod& s, double timeout_ms);
// Below LOD3's coverage (or with "Show LOD" 4) the impostor shows: a card facing the camera, and
// for the shadow pass one facing the sun.
// "LOD1 of 0-3: 120k 48k 18k 6k triangles" for the status bar ("" before the first build is asked for).
std::string editor_lod_status(const editor_lod& s);

}  // namespace sylva
