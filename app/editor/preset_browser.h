// The editor's preset browser: a searchable, tag-filtered grid of cached offscreen thumbnails.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <unordered_map>
#include <vector>

#include "app/editor/preset_library.h"
#include "render/io/preset.h"
#include "render/gl/renderer.h"

namespace sylva {

inline constexpr int thumbnail_size = 128;

// A preset grown and meshed off the main thread, waiting for the main thread to render it.
struct thumbnail_job {
  std::string key, png_path;
  preset doc;
  std::shared_ptr<const tree_skeleton> skeleton;
  std::shared_ptr<const tree_mesh> mesh;
  std::string error;
};

struct preset_browser_state {
  bool open = false;
  std::vector<std::string> folders;          // scanned in order; the user can add more
  std::vector<preset_entry> entries;
  std::vector<std::string> tags, selected_tags;
  std::string query, folder_input, cache_dir;
  bool rescan = true;
  // Thumbnails: GL textures by key (main thread only); keys queued or given up on.
  std::unordered_map<std::string, unsigned> textures;
  std::set<std::string> pending, failed;
  std::vector<std::string> on_screen;      // keys of the cards drawn in the grid's visible part this frame
  std::map<std::string, std::pair<float, float>> card_at;   // each card's centre by preset name (scripted test)
  std::unique_ptr<renderer_gpu> renderer;  // a second renderer so the edited tree stays uploaded
  std::shared_ptr<gl_shared> share;        // the editor's programs and textures (one GL context): not compiled again
  bool renderer_failed = false;
  // Since the library was last opened: thumbnails read from the cache and rendered, and the
  // seconds until every card had its picture or gave up (-1: not yet).
  int from_cache = 0, rendered = 0;
  double ready_s = -1;
  bool was_open = false;
  std::chrono::steady_clock::time_point opened_at, last_update;
  // The growth thread for thumbnails missing from the cache (CPU only; GL stays on the main
  // thread). It grows several presets at once on the job pool, cards on screen first (`wanted`).
  std::thread thread;
  std::mutex mutex;
  std::condition_variable wake;
  std::deque<thumbnail_job> todo, done;
  std::set<std::string> wanted;
  bool quit = false;
  std::atomic<uint32_t> cancel{0};
};

// `folders`: where presets live; missing ones are skipped. Starts the thumbnail thread.
void init_preset_browser(preset_browser_state& b, const std::vector<std::string>& folders);
// Stops the thread and frees the textures (needs the GL context).
void shutdown_preset_browser(preset_browser_state& b);
// Loads cached thumbnails and renders the grown ones (main thread, between frames), within about a
// quarter of the frame time (at least 30 ms and one thumbnail per frame).
void update_thumbnails(preset_browser_state& b);
// Every entry has its thumbnail, or will not get one (an error, no preview).
bool thumbnails_ready(const preset_browser_state& b);
// Draws the browser window when open; returns the path of a preset the user clicked, or "".
// `current_path` (canonical) is the edited document's file, marked in the grid, and `modified`
// whether it has unsaved changes.
std::string draw_preset_browser(preset_browser_state& b, const std::string& current_path, bool modified);

}  // namespace sylva
