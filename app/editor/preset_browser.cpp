// Preset browser: thumbnails are grown on a helper thread, rendered on the main thread, cached on disk.
#include "app/editor/preset_browser.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>

#include <epoxy/gl.h>
#include <imgui.h>
#include <imgui_stdlib.h>

#include "app/common/gl_window.h"
#include "generators/job_pool.h"
#include "render/files.h"

namespace sylva {

namespace fs = std::filesystem;

namespace {

// Takes the next job (under the lock): a card on screen first, else the oldest.
bool take_job(preset_browser_state& b, thumbnail_job& job) {
  if (b.todo.empty()) return false;
  auto it = std::find_if(b.todo.begin(), b.todo.end(), [&](const thumbnail_job& j) { return b.wanted.count(j.key) > 0; });
  if (it == b.todo.end()) it = b.todo.begin();
  job = std::move(*it);
  b.todo.erase(it);
  return true;
}

void grow_thumbnail(preset_browser_state& b, thumbnail_job& job) {
  grow_options o;
  o.seed = job.doc.spec.seed;
  o.cancel = &b.cancel;
  grow_report report;
  auto skeleton = std::make_shared<tree_skeleton>(grow(job.doc.spec, o, &report));
  if (report.error) job.error = report.message;
  else if (!b.cancel.load()) {
    // A 128-pixel picture shows no bark ring detail: thumbnails mesh with at most 5 segments a
    // ring, straight internodes and no caps, which cuts the triangles llvmpipe shades (and the
    // shadow pass draws) to about half; the leaves, the crown and the colours stay the preset's.
    mesh_params mp = job.doc.mesh;
    mp.radial_segments = std::min(mp.radial_segments, 5);
    mp.curve_rings = 0;
    mp.caps = false;
    job.mesh = std::make_shared<tree_mesh>(mesh_tree(*skeleton, mp, job.doc.spec.seed));
    job.skeleton = std::move(skeleton);
  }
}

// Grown trees waiting to be rendered, at most: the library closed, growth pauses here rather than
// holding every preset's mesh.
constexpr size_t done_backlog = 8;

// Grows queued presets, several at once on the job pool (half its threads, so an edit's regrow
// keeps the rest), each worker taking the next job when it finishes one.
void run_thumbnail_thread(preset_browser_state& b) {
  const int threads = std::max(1, (job_pool_helpers() + 1) / 2);
  for (;;) {
    {
      std::unique_lock lock(b.mutex);
      b.wake.wait(lock, [&] { return b.quit || (!b.todo.empty() && b.done.size() < done_backlog); });
      if (b.quit) return;
    }
    parallel_jobs(size_t(threads), [&](size_t) {
      for (;;) {
        thumbnail_job job;
        {
          std::lock_guard lock(b.mutex);
          if (b.quit || b.done.size() >= done_backlog || !take_job(b, job)) return;
        }
        grow_thumbnail(b, job);
        std::lock_guard lock(b.mutex);
        b.done.push_back(std::move(job));
      }
    }, threads);
  }
}

unsigned upload_thumbnail(const std::string& png) {
  image thumb;
  if (!load_png(png, thumb).empty()) return 0;
  const int w = thumb.width, h = thumb.height;
  GLuint id = 0;
  glGenTextures(1, &id);
  glBindTexture(GL_TEXTURE_2D, id);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, thumb.pixels.data());
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glBindTexture(GL_TEXTURE_2D, 0);
  return id;
}

void scan(preset_browser_state& b) {
  b.entries = scan_preset_folders(b.folders, thumbnail_size);
  b.tags = collect_tags(b.entries);
  std::erase_if(b.selected_tags, [&](const std::string& t) { return std::find(b.tags.begin(), b.tags.end(), t) == b.tags.end(); });
  b.rescan = false;
}

}  // namespace

void init_preset_browser(preset_browser_state& b, const std::vector<std::string>& folders) {
  b.folders = folders;
  b.cache_dir = thumbnail_cache_dir();
  std::error_code ec;
  fs::create_directories(b.cache_dir, ec);
  b.thread = std::thread(run_thumbnail_thread, std::ref(b));
}

void shutdown_preset_browser(preset_browser_state& b) {
  {
    std::lock_guard lock(b.mutex);
    b.quit = true;
  }
  b.cancel = 1;
  b.wake.notify_all();
  if (b.thread.joinable()) b.thread.join();
  for (auto& [key, id] : b.textures)
    if (id) glDeleteTextures(1, &id);
  b.textures.clear();
  if (b.renderer) destroy_renderer(*b.renderer);
  b.renderer.reset();
}

namespace {

// Renders a grown preset into its cached PNG and uploads it (main thread).
void render_thumbnail(preset_browser_state& b, const thumbnail_job& finished) {
  b.pending.erase(finished.key);
  if (!finished.mesh || b.renderer_failed) {
    b.failed.insert(finished.key);
    return;
  }
  if (!b.renderer) {
    b.renderer = std::make_unique<renderer_gpu>();
    if (!init_renderer(*b.renderer, b.share)) {
      b.renderer_failed = true;
      b.failed.insert(finished.key);
      return;
    }
  }
  renderer_gpu& r = *b.renderer;
  upload_tree(r, *finished.mesh);
  set_tree_step(r, *finished.skeleton, finished.doc.mesh.min_radius, finished.skeleton->steps);
  // Framed as the editor and PNG export frame it (frame_camera), for a square picture.
  orbit_camera cam;
  frame_camera(cam, r.bounds_min, r.bounds_max, 1.0f);   // square thumbnails
  render_params rp = finished.doc.render;
  rp.shafts = light_shafts::off;   // at thumbnail size they only wash the tree out
  // A 512 map shades a 128-pixel tree as finely as 2048 does the window; it is the pass that
  // cost most of a thumbnail on a software renderer.
  rp.shadow_resolution = std::min(rp.shadow_resolution, 4 * thumbnail_size);
  // Written under a temporary name and renamed: a half-written PNG is never taken for a cached one.
  const std::string tmp = finished.png_path + ".tmp.png";
  std::string err = save_view_png(r, rp, cam, thumbnail_size, thumbnail_size, tmp);
  std::error_code ec;
  if (err.empty()) fs::rename(tmp, finished.png_path, ec);
  unsigned id = err.empty() && !ec ? upload_thumbnail(finished.png_path) : 0;
  if (id) b.textures[finished.key] = id, ++b.rendered;
  else b.failed.insert(finished.key);
}

}  // namespace

bool thumbnails_ready(const preset_browser_state& b) {
  return std::all_of(b.entries.begin(), b.entries.end(), [&](const preset_entry& e) {
    return !e.error.empty() || b.textures.count(e.thumbnail_key) || b.failed.count(e.thumbnail_key);
  });
}

void update_thumbnails(preset_browser_state& b) {
  using clock = std::chrono::steady_clock;
  const clock::time_point start = clock::now();
  // A quarter of the time since the last call (the frame), at least 30 ms: on a slow frame more
  // thumbnails per frame, on a fast one no visible stall.
  const double frame_s = b.last_update == clock::time_point{} ? 0 : std::chrono::duration<double>(start - b.last_update).count();
  const double budget_s = std::clamp(0.25 * frame_s, 0.03, 1.0);
  b.last_update = start;
  auto spent = [&] { return std::chrono::duration<double>(clock::now() - start).count(); };
  if (b.open && !b.was_open) b.opened_at = start, b.ready_s = -1, b.from_cache = b.rendered = 0;
  b.was_open = b.open;
  if (!b.open) return;
  if (b.rescan) scan(b);
  std::vector<thumbnail_job> queue;
  bool over_budget = false;
  for (const preset_entry& e : b.entries) {
    if (!e.error.empty() || b.textures.count(e.thumbnail_key) || b.pending.count(e.thumbnail_key) ||
        b.failed.count(e.thumbnail_key))
      continue;
    const std::string png = (fs::path(b.cache_dir) / (e.thumbnail_key + ".png")).string();
    std::error_code ec;
    if (fs::exists(png, ec)) {   // a cached PNG is small: read as many as the budget allows
      if (over_budget || (over_budget = spent() > budget_s)) continue;
      if (unsigned id = upload_thumbnail(png)) b.textures[e.thumbnail_key] = id, ++b.from_cache;
      else b.failed.insert(e.thumbnail_key);
      continue;
    }
    thumbnail_job job;
    job.key = e.thumbnail_key;
    job.png_path = png;
    if (!load_preset_file(e.path, job.doc).ok) {
      b.failed.insert(e.thumbnail_key);
      continue;
    }
    b.pending.insert(e.thumbnail_key);
    queue.push_back(std::move(job));
  }
  {
    std::lock_guard lock(b.mutex);
    for (thumbnail_job& j : queue) b.todo.push_back(std::move(j));
    b.wanted = std::set<std::string>(b.on_screen.begin(), b.on_screen.end());
  }
  if (!queue.empty()) b.wake.notify_all();
  // Grown trees are rendered here until the budget is spent, at least one per frame.
  bool drew = false;
  for (bool first = true; first || spent() < budget_s; first = false) {
    thumbnail_job finished;
    {
      std::lock_guard lock(b.mutex);
      if (b.done.empty()) break;
      finished = std::move(b.done.front());
      b.done.pop_front();
    }
    render_thumbnail(b, finished);
    drew = true;
  }
  if (drew) b.wake.notify_all();   // room in the backlog again
  if (drew && b.renderer) upload_tree(*b.renderer, tree_mesh{});   // the thumbnail's buffers are not needed until the next one
  if (b.ready_s < 0 && thumbnails_ready(b)) b.ready_s = std::chrono::duration<double>(clock::now() - b.opened_at).count();
}

std::string draw_preset_browser(preset_browser_state& b, const std::string& current_path, bool modified) {
  b.on_screen.clear();
  b.card_at.clear();
  if (!b.open) return "";
  std::string clicked;
  ImGui::SetNextWindowSize(ImVec2(760, 640), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowPos(ImVec2(440, 60), ImGuiCond_FirstUseEver);
  if (!ImGui::Begin("Preset library", &b.open)) {
    ImGui::End();
    return "";
  }
  ImGui::SetNextItemWidth(260);
  ImGui::InputTextWithHint("##search", "search name, description, tags", &b.query);
  ImGui::SameLine();
  if (ImGui::Button("Rescan")) b.rescan = true;
  ImGui::SameLine();
  ImGui::SetNextItemWidth(220);
  ImGui::InputTextWithHint("##folder", "another folder of presets", &b.folder_input);
  ImGui::SameLine();
  if (ImGui::Button("Add folder") && !b.folder_input.empty()) {
    b.folders.push_back(b.folder_input);
    b.folder_input.clear();
    b.rescan = true;
  }
  // Tag filter: a toggle per tag, most used first; every selected tag must be present.
  for (size_t i = 0; i < b.tags.size(); ++i) {
    const std::string& t = b.tags[i];
    auto it = std::find(b.selected_tags.begin(), b.selected_tags.end(), t);
    const bool on = it != b.selected_tags.end();
    if (on) ImGui::PushStyleColor(ImGuiCol_Button, ImGui::GetStyleColorVec4(ImGuiCol_ButtonActive));
    ImGui::PushID(int(i));
    if (ImGui::SmallButton(t.c_str())) {
      if (on) b.selected_tags.erase(it);
      else b.selected_tags.push_back(t);
    }
    ImGui::PopID();
    if (on) ImGui::PopStyleColor();
    if (i + 1 == b.tags.size()) break;
    // Wrap like text: stay on this line only when the next button fits.
    const float next_end = ImGui::GetItemRectMax().x + ImGui::GetStyle().ItemSpacing.x +
                           ImGui::CalcTextSize(b.tags[i + 1].c_str()).x + 2 * ImGui::GetStyle().FramePadding.x;
    if (next_end < ImGui::GetWindowPos().x + ImGui::GetWindowContentRegionMax().x) ImGui::SameLine();
  }
  ImGui::Separator();
  ImGui::BeginChild("grid");
  const float cell = float(thumbnail_size) + 16;
  const int columns = std::max(1, int(ImGui::GetContentRegionAvail().x / cell));
  int shown = 0;
  for (size_t i = 0; i < b.entries.size(); ++i) {
    const preset_entry& e = b.entries[i];
    if (!preset_matches(e, b.query, b.selected_tags)) continue;
    if (shown++ % columns) ImGui::SameLine();
    ImGui::PushID(int(i));
    ImGui::BeginGroup();
    const bool current = !current_path.empty() && e.path == current_path;
    const ImVec2 size{float(thumbnail_size), float(thumbnail_size)};
    auto tex = b.textures.find(e.thumbnail_key);
    bool pressed = false;
    if (current) ImGui::PushStyleColor(ImGuiCol_Button, modified ? ImVec4(0.85f, 0.55f, 0.1f, 1) : ImVec4(0.3f, 0.6f, 0.9f, 1));
    if (tex != b.textures.end() && tex->second) {
      pressed = ImGui::ImageButton(reinterpret_cast<ImTextureID>(static_cast<intptr_t>(tex->second)), size, ImVec2(0, 0), ImVec2(1, 1), 4);
    } else {
      const char* what = !e.error.empty() ? "cannot load" : b.failed.count(e.thumbnail_key) ? "no preview" : "rendering...";
      pressed = ImGui::Button(what, ImVec2(size.x + 8, size.y + 8));
    }
    if (current) ImGui::PopStyleColor();
    if (ImGui::IsItemVisible()) b.on_screen.push_back(e.thumbnail_key);
    const ImVec2 lo = ImGui::GetItemRectMin(), hi = ImGui::GetItemRectMax();
    b.card_at[e.name] = {0.5f * (lo.x + hi.x), 0.5f * (lo.y + hi.y)};
    if (ImGui::IsItemHovered()) {
      ImGui::BeginTooltip();
      ImGui::PushTextWrapPos(420);
      ImGui::TextUnformatted(e.name.c_str());
      if (!e.error.empty()) ImGui::TextColored(ImVec4(1, 0.45f, 0.4f, 1), "%s", e.error.c_str());
      ImGui::TextDisabled("%s", e.generator.c_str());
      ImGui::TextUnformatted(e.description.c_str());
      std::string tags;
      for (const std::string& t : e.tags) tags += (tags.empty() ? "" : ", ") + t;
      ImGui::TextDisabled("tags: %s", tags.c_str());
      ImGui::TextDisabled("%s", e.path.c_str());
      if (current && modified) ImGui::TextColored(ImVec4(1, 0.7f, 0.2f, 1), "open in the editor, with unsaved changes");
      ImGui::PopTextWrapPos();
      ImGui::EndTooltip();
    }
    if (pressed && e.error.empty()) clicked = e.path, b.open = false;   // the library gets out of the way
    // The name under the thumbnail, wrapped to the cell's width; a * marks the open preset's unsaved changes.
    const std::string label = (current && modified ? "* " : "") + e.name;
    ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + size.x + 8);
    if (current) ImGui::TextColored(modified ? ImVec4(1, 0.7f, 0.2f, 1) : ImVec4(0.5f, 0.75f, 1, 1), "%s", label.c_str());
    else ImGui::TextUnformatted(label.c_str());
    ImGui::PopTextWrapPos();
    ImGui::EndGroup();
    ImGui::PopID();
  }
  if (!shown) ImGui::TextDisabled(b.entries.empty() ? "No presets found in the folders." : "No preset matches.");
  ImGui::EndChild();
  ImGui::End();
  return clicked;
}

}  // namespace sylva
