// File > Export in the editor: format, scope, growth animation, a size estimate, progress and cancel.
#pragma once

#include <atomic>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "app/common/worker.h"
#include "render/io/export.h"
#include "render/io/preset.h"

namespace sylva {

struct renderer_gpu;
struct orbit_camera;

struct export_dialog_state {
  bool open = false;
  std::string path = "tree.glb";
  bool final_tree = false;          // scope: the final tree, or the timeline's current step
  bool animation = false;           // glTF only: steps 0..N as a growth animation
  float seconds_per_step = 0.5f;
  bool compact = false;             // glTF only: quantized, meshopt-compressed, JPEG textures
  int profile = 0;                  // export_profile: plain, hero or hero-baked (game is the CLI's --lods)
  // The LOD chain (as `sylva export --lods`): LOD1-3 built from the final tree at the preset's
  // budgets, written as glTF MSFT_lod, an FBX LOD group or one OBJ per level. glTF also gets the
  // impostor, its atlas rendered on the UI thread (the editor's GL context) when Export is pressed.
  bool lods = false;
  std::string impostor_note;               // why the last glTF LOD export has no impostor ("" when it has one)
  // The exporter runs on its own thread: a dry run for the size estimate, or the real export.
  std::thread thread;
  std::atomic<uint32_t> cancel{0};
  std::atomic<float> progress{0};
  std::atomic<bool> running{false};
  bool job_dry = false;
  std::mutex mutex;
  std::optional<export_result> finished;   // set by the thread, taken by the UI
  std::string finished_lods;               // with `finished`: lod_summary of the chain written ("" without)
  std::string lod_counts;                  // the last LOD export's (or estimate's) lod_summary, shown in the dialog
  std::string estimate_key;                // what the shown estimate was computed for
  std::string estimate;                    // "", "estimating...", "about 1.2 MiB, 34,000 triangles"
  std::string warning;                     // the last export's warning (a user texture it could not use)
  std::string failure;                     // the last export's error, shown in the dialog until the next try
  bool export_now = false;                 // Export as... chose the path (and confirmed a replace): export at once
  std::string confirm_replace;             // the existing file the next Export would replace (asked once)
  std::string shown_path;                  // the path as drawn last frame: an edit clears the old failure
  float path_at[2] = {0, 0};               // the Path field's centre on screen (the scripted test clicks it)
  float export_at[2] = {0, 0};             // the Export (or Replace) button's centre, the same
};

struct export_context {
  std::shared_ptr<const grow_result> tree;   // the shown tree (kept alive by the export thread)
  int step = 0;                              // the timeline's step
  const preset& doc;
  renderer_gpu& renderer;                  // .png renders the current view (main thread)
  const orbit_camera& camera;
  float view_left = 0;                     // the 3D view's left edge: the dialog opens there, not over the panel
  float view_top = 0;
};

// Draws the window when open. When an export ends, sets `status` (and `error` on failure).
void draw_export_dialog(export_dialog_state& d, const export_context& c, std::string& status, bool& error);
// Cancels a running export and waits for it.
void shutdown_export_dialog(export_dialog_state& d);

}  // namespace sylva
