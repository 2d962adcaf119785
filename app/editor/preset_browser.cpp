// Preset browser: thumbnails are grown on a helper thread, rendered on the main thread, cached on disk.
#include "app/editor/preset_browser.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>

#include <epoxy/gl.h>
#include <imgui.h>
#include <imgui_stdlib.h>

#include "app/gl_window.h"
#include "render/files.h"

namespace sylva {

namespace fs = std::filesystem;

namespace {

constexpr int loads_per_frame = 4;   // cached PNGs are small; more per frame would stall the UI

void run_thumbnail_thread(preset_browser_state& b) {
  for (;;) {
    thumbnail_job job;
    {
      std::unique_lock lock(b.mutex);
      b.wake.wait(lock, [&] { return b.quit || !b.todo.empty(); });
      if (b.quit) return;
      job = std::move(b.todo.front());
      b.todo.pop_front();
    }
    grow_options o;
    o.seed = job.doc.spec.seed;
    o.cancel = &b.cancel;
    grow_report report;
    auto skeleton = std::make_shared<tree_skeleton>(grow(job.doc.spec, o, &report));
    if (report.error) job.error = report.message;
    else if (!b.cancel.load()) {
      job.mesh = std::make_shared<tree_mesh>(mesh_tree(*skeleton, job.doc.mesh, job.doc.spec.seed));
      job.skeleton = std::move(skeleton);
    }
    std::lock_guard lock(b.mutex);
    b.done.push_back(std::move(job));
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
  b.entries.clear();
  std::set<std::string> seen, same_file;
  for (const std::string& f : b.folders) {
    for (preset_entry& e : scan_preset_folder(f, thumbnail_size)) {
      std::error_code ec;
      const std::string canonical = fs::weakly_canonical(e.path, ec).string();
      if (!seen.insert(canonical).second) continue;   // the same folder reached twice
      // The same preset shipped twice (the binary's tree and the working folder both hold
      // presets/): one card, from the first folder.
      std::string bytes;
      if (read_file(canonical, bytes).empty() && !same_file.insert(fs::path(canonical).filename().string() + '\n' + bytes).second)
        continue;
      e.path = canonical;
      b.entries.push_back(std::move(e));
    }
  }
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

void update_thumbnails(preset_browser_state& b) {
  if (!b.open) return;
  if (b.rescan) scan(b);
  int loads = 0;
  std::vector<thumbnail_job> queue;
  for (const preset_entry& e : b.entries) {
    if (!e.error.empty() || b.textures.count(e.thumbnail_key) || b.pending.count(e.thumbnail_key) ||
        b.failed.count(e.thumbnail_key))
      continue;
    const std::string png = (fs::path(b.cache_dir) / (e.thumbnail_key + ".png")).string();
    std::error_code ec;
    if (fs::exists(png, ec)) {
      if (loads++ >= loads_per_frame) continue;
      if (unsigned id = upload_thumbnail(png)) b.textures[e.thumbnail_key] = id;
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
  thumbnail_job finished;
  bool have = false;
  {
    std::lock_guard lock(b.mutex);
    for (thumbnail_job& j : queue) b.todo.push_back(std::move(j));
    if (!b.done.empty()) {
      finished = std::move(b.done.front());
      b.done.pop_front();
      have = true;
    }
  }
  if (!queue.empty()) b.wake.notify_one();
  if (!have) return;
  // Render one finished tree per frame so the editor stays responsive.
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
  // Written under a temporary name and renamed: a half-written PNG is never taken for a cached one.
  const std::string tmp = finished.png_path + ".tmp.png";
  std::string err = save_view_png(r, rp, cam, thumbnail_size, thumbnail_size, tmp);
  std::error_code ec;
  if (err.empty()) fs::rename(tmp, finished.png_path, ec);
  unsigned id = err.empty() && !ec ? upload_thumbnail(finished.png_path) : 0;
  if (id) b.textures[finished.key] = id;
  else b.failed.insert(finished.key);
  upload_tree(r, tree_mesh{});   // the thumbnail's buffers are not needed until the next one
}

std::string draw_preset_browser(preset_browser_state& b, const std::string& current_path, bool modified) {
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
