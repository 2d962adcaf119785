// The editor's in-app file browser (editor_files.h).
#include "app/editor/editor_files.h"

#include <algorithm>
#include <filesystem>

#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_stdlib.h>

namespace sylva {

namespace fs = std::filesystem;

std::string list_folder(const std::string& folder, const std::vector<std::string>& extensions, bool all,
                        std::vector<file_entry>& out) {
  out.clear();
  std::error_code ec;
  fs::directory_iterator it(folder, ec);
  if (ec) return "cannot read " + folder + ": " + ec.message();
  for (const auto& entry : it) {
    const std::string name = entry.path().filename().string();
    if (name.empty() || name[0] == '.') continue;
    std::error_code e2;
    const bool dir = entry.is_directory(e2);
    if (!dir && !all) {
      std::string ext = entry.path().extension().string();
      std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
      if (std::find(extensions.begin(), extensions.end(), ext) == extensions.end()) continue;
    }
    out.push_back({name, dir});
  }
  std::sort(out.begin(), out.end(), [](const file_entry& a, const file_entry& b) {
    return a.folder != b.folder ? a.folder : a.name < b.name;
  });
  return "";
}

void note_recent(std::vector<std::string>& recent, const std::string& path) {
  recent.erase(std::remove(recent.begin(), recent.end(), path), recent.end());
  recent.insert(recent.begin(), path);
  if (recent.size() > 10) recent.resize(10);
}

std::vector<std::string> recent_presets(const std::vector<std::string>& recent) {
  std::vector<std::string> out;
  for (const std::string& p : recent) {
    std::error_code ec;
    if (fs::path(p).extension() == ".json" && fs::is_regular_file(p, ec)) out.push_back(p);
  }
  return out;
}

namespace {

void refresh(file_browser& b) { b.error = list_folder(b.folder, b.extensions, b.all_files, b.entries); }

bool in_forbidden(const file_browser& b, const fs::path& path) {
  std::error_code ec;
  const fs::path parent = fs::weakly_canonical(path, ec).parent_path();
  for (const std::string& f : b.forbidden_folders)
    if (parent == fs::weakly_canonical(f, ec)) return true;
  return false;
}

bool pressed(const char* label, std::string& answer, bool enabled = true) {
  if (!enabled) ImGui::BeginDisabled();
  bool clicked = ImGui::Button(label);
  if (!enabled) ImGui::EndDisabled();
  if (enabled && !answer.empty() && answer == label) {
    answer.clear();
    clicked = true;
  }
  return clicked;
}

}  // namespace

void open_file_browser(file_browser& b, const std::string& title, bool saving, const std::string& folder,
                       const std::string& name, const std::vector<std::string>& extensions) {
  b.title = title;
  b.saving = saving;
  b.extensions = extensions;
  b.all_files = false;
  std::error_code ec;
  if (saving) fs::create_directories(folder, ec);
  b.folder = folder;
  b.name = name;
  b.confirm_overwrite = false;
  b.request_open = true;
  refresh(b);
}

std::string draw_file_browser(file_browser& b, const std::vector<std::string>& recent, std::string& answer) {
  if (b.title.empty()) return "";
  if (b.request_open) {
    ImGui::OpenPopup(b.title.c_str());
    b.request_open = false;
  }
  ImGui::SetNextWindowSize(ImVec2(760, 480), ImGuiCond_Appearing);
  if (!ImGui::BeginPopupModal(b.title.c_str())) return "";
  std::string chosen;
  // Places and the current folder.
  for (const auto& [label, path] : b.places) {
    if (ImGui::SmallButton(label.c_str())) {
      b.folder = path;
      refresh(b);
    }
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", path.c_str());
    ImGui::SameLine();
  }
  if (ImGui::SmallButton("Up")) {
    b.folder = fs::path(b.folder).parent_path().string();
    refresh(b);
  }
  ImGui::SameLine();
  ImGui::SetNextItemWidth(-1);
  if (ImGui::InputText("##folder", &b.folder, ImGuiInputTextFlags_EnterReturnsTrue)) refresh(b);
  // Recent files on the left, the folder on the right.
  const float footer = ImGui::GetFrameHeightWithSpacing() * 2 + ImGui::GetTextLineHeightWithSpacing();
  ImGui::BeginChild("recent", ImVec2(220, -footer), true);
  ImGui::TextDisabled("Recent");
  for (const std::string& r : recent) {
    std::string ext = fs::path(r).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    if (!b.all_files && std::find(b.extensions.begin(), b.extensions.end(), ext) == b.extensions.end()) continue;
    if (ImGui::Selectable(fs::path(r).filename().string().c_str())) {
      b.folder = fs::path(r).parent_path().string();
      b.name = fs::path(r).filename().string();
      b.confirm_overwrite = false;
      refresh(b);
    }
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", r.c_str());
  }
  ImGui::EndChild();
  ImGui::SameLine();
  ImGui::BeginChild("files", ImVec2(0, -footer), true);
  if (!b.error.empty()) ImGui::TextColored(ImVec4(1, 0.45f, 0.4f, 1), "%s", b.error.c_str());
  std::string enter;
  for (const file_entry& f : b.entries) {
    const std::string label = f.folder ? f.name + "/" : f.name;
    if (ImGui::Selectable(label.c_str(), !f.folder && f.name == b.name, ImGuiSelectableFlags_AllowDoubleClick)) {
      if (f.folder) {
        enter = f.name;
      } else {
        b.name = f.name;
        b.confirm_overwrite = false;
        if (ImGui::IsMouseDoubleClicked(0) && !b.saving) chosen = (fs::path(b.folder) / f.name).string();
      }
    }
  }
  if (b.entries.empty() && b.error.empty()) ImGui::TextDisabled("(no matching files)");
  ImGui::EndChild();
  if (!enter.empty()) {
    b.folder = (fs::path(b.folder) / enter).string();
    refresh(b);
  }
  // Name, filter, the overwrite question and the buttons.
  ImGui::SetNextItemWidth(-230);
  if (ImGui::InputText("##name", &b.name)) b.confirm_overwrite = false;
  ImGui::SameLine();
  std::string filter;
  for (const std::string& e : b.extensions) filter += (filter.empty() ? "*" : " *") + e;
  ImGui::SetNextItemWidth(-1);
  const char* filters[] = {filter.c_str(), "All files"};
  int fi = b.all_files ? 1 : 0;
  if (ImGui::Combo("##filter", &fi, filters, 2)) {
    b.all_files = fi == 1;
    refresh(b);
  }
  fs::path target = fs::path(b.folder) / b.name;
  if (b.saving && !b.name.empty() && !target.has_extension() && !b.extensions.empty()) target += b.extensions.front();
  std::error_code ec;
  const bool exists = !b.name.empty() && fs::exists(target, ec);
  const bool forbidden = b.saving && in_forbidden(b, target);
  if (forbidden) ImGui::TextColored(ImVec4(1, 0.8f, 0.4f, 1), "%s", b.forbidden_folder_note.c_str());
  else if (b.confirm_overwrite) ImGui::TextColored(ImVec4(1, 0.8f, 0.4f, 1), "%s exists. Replace it?", target.filename().c_str());
  else if (!b.saving && !b.name.empty() && !exists) ImGui::TextDisabled("%s does not exist", target.string().c_str());
  else ImGui::TextDisabled("%s", target.string().c_str());
  const bool can = !b.name.empty() && !forbidden && (b.saving || exists);
  const char* ok = b.saving ? (b.confirm_overwrite ? "Replace" : "Save") : "Open";
  if (pressed(ok, answer, can) || (can && ImGui::IsKeyPressed(GLFW_KEY_ENTER) && !b.confirm_overwrite)) {
    if (b.saving && exists && !b.confirm_overwrite) b.confirm_overwrite = true;
    else chosen = target.string();
  }
  ImGui::SameLine();
  if (pressed("Cancel", answer) || ImGui::IsKeyPressed(GLFW_KEY_ESCAPE)) {
    b.title.clear();
    ImGui::CloseCurrentPopup();
  }
  if (!chosen.empty()) {
    b.title.clear();
    ImGui::CloseCurrentPopup();
  }
  ImGui::EndPopup();
  return chosen;
}

}  // namespace sylva
