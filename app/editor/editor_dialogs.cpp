// The menu bar and the dialogs: file browsers, unsaved changes, large tree, recovery, shortcuts, messages.
#include "app/editor/editor_state.h"
#include "app/editor/editor_undo_names.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>
#include <ctime>

#include <GLFW/glfw3.h>
#include <imgui.h>

namespace sylva::ed {

namespace {

std::vector<std::string> export_extensions() {
  std::vector<std::string> out;
  for (const export_format& f : export_format_table) out.push_back(f.ext);
  return out;
}

// A dialog button that the scripted test can press too (`answer LABEL`).
bool scripted_button(editor_state& e, const char* label) {
  const bool clicked = ImGui::Button(label);
  if (!e.script_answer.empty() && e.script_answer == label) {
    e.script_answer.clear();
    return true;
  }
  return clicked;
}


}  // namespace

// "sylva-20261201-114502.png"
std::string screenshot_name() {
  char b[64];
  const std::time_t t = std::time(nullptr);
  std::strftime(b, sizeof b, "sylva-%Y%m%d-%H%M%S.png", std::localtime(&t));
  return b;
}

// ---------------------------------------------------------------- UI

void draw_menu(editor_state& e) {
  if (!ImGui::BeginMainMenuBar()) return;
  if (ImGui::BeginMenu("File")) {
    if (ImGui::MenuItem("Open preset...", shortcut_keys(shortcut::open))) e.ask(dialog::open_preset);
    const std::vector<std::string> recent = recent_presets(e.recent);
    if (ImGui::BeginMenu("Open recent", !recent.empty())) {
      for (const std::string& p : recent)
        if (ImGui::MenuItem(fs::path(p).filename().string().c_str())) request(e, editor_state::then::open, p);
        else if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", p.c_str());
      ImGui::EndMenu();
    }
    ImGui::MenuItem("Preset library", shortcut_keys(shortcut::library), &e.browser.open);
    if (ImGui::MenuItem("Save", shortcut_keys(shortcut::save))) save_command(e);
    if (ImGui::MenuItem("Save as...")) e.ask(dialog::save_as);
    if (ImGui::MenuItem("Export...", nullptr, e.exporter.open)) {
      if (e.exporter.open) e.exporter.open = false;
      else open_export_dialog(e);
    }
    if (ImGui::MenuItem("Export as...")) e.ask(dialog::export_as);
    if (ImGui::MenuItem("Screenshot", shortcut_keys(shortcut::screenshot))) e.screenshot_requested = true;
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("The 3D view, without menus, to %s/screenshots/", e.home.c_str());
    if (ImGui::MenuItem("Screenshot as...")) e.ask(dialog::screenshot_as);
    ImGui::Separator();
    if (ImGui::MenuItem("Quit", shortcut_keys(shortcut::quit))) request(e, editor_state::then::quit);
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("Edit")) {
    // Each entry says what it undoes ("Undo Influence radius").
    const std::string undo_label = "Undo " + (e.cur().undo.empty() ? std::string() : change_name(e.cur().undo.back(), e.cur().doc)) + "##undo";
    const std::string redo_label = "Redo " + (e.cur().redo.empty() ? std::string() : change_name(e.cur().doc, e.cur().redo.back())) + "##redo";
    if (ImGui::MenuItem(undo_label.c_str(), shortcut_keys(shortcut::undo), false, !e.cur().undo.empty())) apply_undo(e, e.cur().undo, e.cur().redo);
    if (ImGui::MenuItem(redo_label.c_str(), shortcut_keys(shortcut::redo), false, !e.cur().redo.empty())) apply_undo(e, e.cur().redo, e.cur().undo);
    if (!e.cur().undo.empty() && ImGui::BeginMenu("Undo history")) {   // newest first; a click goes back to it
      int go_back = -1;
      for (size_t k = e.cur().undo.size(); k-- > 0 && e.cur().undo.size() - k <= 20;) {
        const preset& after = k + 1 < e.cur().undo.size() ? e.cur().undo[k + 1] : e.cur().doc;
        ImGui::PushID(int(k));
        if (ImGui::MenuItem(change_name(e.cur().undo[k], after).c_str())) go_back = int(e.cur().undo.size() - k);
        ImGui::PopID();
      }
      ImGui::EndMenu();
      for (int i = 0; i < go_back; ++i) apply_undo(e, e.cur().undo, e.cur().redo);
    }
    ImGui::Separator();
    draw_node_budget(e);
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("View")) {
    ImGui::MenuItem("Growth overlays", nullptr, &e.show_overlays);
    draw_overlay_menu(e.overlays, e.cur().renderer.overlay);
    ImGui::MenuItem("Parameter panel", nullptr, &e.show_panel);
    ImGui::MenuItem("Timeline", nullptr, &e.show_timeline);
    ImGui::MenuItem("Advanced parameters", nullptr, &e.show_advanced);
    if (ImGui::MenuItem("Frame tree", shortcut_keys(shortcut::frame))) e.frame_now = true;
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("Help")) {
    ImGui::MenuItem("Keyboard and mouse", shortcut_keys(shortcut::help), &e.show_shortcuts);
    ImGui::MenuItem("Messages", nullptr, &e.show_log);
    if (ImGui::MenuItem("About Sylva")) e.ask(dialog::about);
    ImGui::EndMenu();
  }
  ImGui::EndMainMenuBar();
}

void open_export_dialog(editor_state& e) {
  e.exporter.open = true;
  // Exports land in the user's folder, named after the tree, unless a place was chosen already.
  std::error_code ec;
  fs::create_directories(e.home, ec);
  if (fs::path(e.exporter.path).is_relative())
    e.exporter.path = (fs::path(e.home) / (fs::path(default_save_path(e)).stem().string() + fs::path(e.exporter.path).extension().string())).string();
}

void draw_node_budget(editor_state& e) {
  // Typed and applied on Enter (a half-typed number is not clamped under the cursor), or picked.
  static int64_t typed = 0;
  static bool editing = false;
  constexpr int64_t lo = 1000, hi = 50000000;
  if (!editing) typed = e.cur().worker->node_budget.load();
  ImGui::SetNextItemWidth(130 * ui_scale);
  if (ImGui::InputScalar("Node budget", ImGuiDataType_S64, &typed, nullptr, nullptr, "%lld",
                         ImGuiInputTextFlags_EnterReturnsTrue | ImGuiInputTextFlags_CharsDecimal))
    e.cur().worker->node_budget = std::clamp(typed, lo, hi);
  editing = ImGui::IsItemActive();
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("A request estimated to grow more nodes than this asks before growing (%s to %s; Enter applies)",
                      count_text(double(lo)).c_str(), count_text(double(hi)).c_str());
  for (const int64_t v : {int64_t(100000), int64_t(1000000), int64_t(10000000)}) {
    ImGui::SameLine();
    ImGui::PushID(int(v / 1000));
    if (ImGui::SmallButton(v >= 1000000 ? (std::to_string(v / 1000000) + "M").c_str() : (std::to_string(v / 1000) + "k").c_str()))
      e.cur().worker->node_budget = v;
    ImGui::PopID();
  }
}

void draw_output_extras(editor_state& e) {
  ImGui::Separator();
  ImGui::TextUnformatted("Growth");
  draw_node_budget(e);
  ImGui::Separator();
  ImGui::TextUnformatted("Files");
  if (ImGui::Button("Export...")) open_export_dialog(e);
  ImGui::SameLine();
  if (ImGui::Button("Export as...")) e.ask(dialog::export_as);
  ImGui::SameLine();
  if (ImGui::Button("Screenshot (F12)")) e.screenshot_requested = true;
}

void draw_message_log(editor_state& e) {
  if (!e.show_log) return;
  ImGui::SetNextWindowSize(ImVec2(640 * ui_scale, 300 * ui_scale), ImGuiCond_FirstUseEver);
  if (ImGui::Begin("Messages", &e.show_log)) {
    if (ImGui::SmallButton("Clear")) e.log.clear();
    ImGui::SameLine();
    if (ImGui::SmallButton("Copy all")) {
      std::string all;
      for (const auto& l : e.log) all += l.time + "  " + l.text + "\n";
      ImGui::SetClipboardText(all.c_str());
    }
    ImGui::Separator();
    ImGui::BeginChild("lines");
    for (const auto& l : e.log) {
      ImGui::TextDisabled("%s", l.time.c_str());
      ImGui::SameLine();
      ImGui::PushTextWrapPos(0);
      if (l.error) ImGui::TextColored(ImVec4(1, 0.5f, 0.45f, 1), "%s", l.text.c_str());
      else ImGui::TextUnformatted(l.text.c_str());
      ImGui::PopTextWrapPos();
    }
    if (ImGui::GetScrollY() >= ImGui::GetScrollMaxY()) ImGui::SetScrollHereY(1.0f);
    ImGui::EndChild();
  }
  ImGui::End();
}

namespace {

// Whether dialog d was asked for; the request is then taken.
bool take(editor_state& e, dialog d) {
  const bool asked = e.asked[size_t(d)];
  e.asked[size_t(d)] = false;
  return asked;
}

// The file browser's places: the user's folder, the shipped presets (read-only for Save) and home.
void set_places(editor_state& e, file_browser& b) {
  b.places.clear();
  b.places.push_back({"My trees", e.home});
  for (const fs::path& d : preset_dirs())
    if (std::error_code ec; fs::is_directory(d, ec)) {
      b.places.push_back({"Shipped presets", fs::weakly_canonical(d, ec).string()});
      break;
    }
  if (const char* h = std::getenv("HOME")) b.places.push_back({"Home", h});
  b.forbidden_folders.clear();
  for (const fs::path& d : preset_dirs()) b.forbidden_folders.push_back(d.string());
  b.forbidden_folder_note = "The shipped presets are read-only: save your own copy in " + e.home;
}

// Opens the file browser for one of its uses (Open, Save as, Screenshot as, Export as).
void open_browser(editor_state& e, dialog use) {
  switch (use) {
    case dialog::open_preset: {
      std::string folder = !e.cur().path.empty() && !is_installed_preset(e.cur().path) ? fs::path(e.cur().path).parent_path().string() : e.home;
      std::error_code ec;
      if (!fs::is_directory(folder, ec)) {   // nothing of the user's yet: the shipped presets
        folder.clear();
        for (const fs::path& d : preset_dirs())
          if (fs::is_directory(d, ec)) { folder = d.string(); break; }
        if (folder.empty()) folder = e.home;
      }
      set_places(e, e.files);
      open_file_browser(e.files, "Open preset", false, folder, "", {".json"});
      break;
    }
    case dialog::save_as: {
      const fs::path p = default_save_path(e);
      set_places(e, e.files);
      open_file_browser(e.files, "Save preset as", true, p.parent_path().string(), p.filename().string(), {".json"});
      break;
    }
    case dialog::screenshot_as:
      set_places(e, e.files);
      open_file_browser(e.files, "Save screenshot as", true, (fs::path(e.home) / "screenshots").string(),
                        screenshot_name(), {".png"});
      break;
    case dialog::export_as: {   // the export dialog then opens on the chosen path
      set_places(e, e.files);
      const fs::path current = fs::path(e.exporter.path).is_relative() ? fs::path(e.home) / e.exporter.path : fs::path(e.exporter.path);
      const std::string stem = fs::path(default_save_path(e)).stem().string();
      open_file_browser(e.files, "Export as", true, current.parent_path().string(),
                        stem + (current.has_extension() ? current.extension().string() : ".glb"),
                        export_extensions());
      break;
    }
    default:
      return;
  }
  e.browse = use;
}

// The file browser drawn, and its answer (a path chosen, or cancelled) acted on.
void draw_browser(editor_state& e) {
  if (!e.files.title.empty()) e.prompts_shown.push_back(e.files.title);
  const bool was_open = !e.files.title.empty();
  if (const std::string chosen = draw_file_browser(e.files, e.recent, e.script_answer); !chosen.empty()) {
    if (e.browse == dialog::open_preset) {
      request(e, editor_state::then::open, chosen);
    } else if (e.browse == dialog::save_as) {
      const bool saved = save_to(e, chosen);
      if (saved && e.continue_after_save) perform_pending(e);
      e.continue_after_save = false;
    } else if (e.browse == dialog::export_as) {
      e.exporter.path = chosen;
      e.exporter.open = true;
      e.exporter.export_now = true;   // the browser asked about replacing already: write it now
      e.exporter.failure.clear();
    } else {
      e.screenshot_to = chosen;
    }
  } else if (was_open && e.files.title.empty()) {   // cancelled
    if (e.browse == dialog::save_as) {
      e.continue_after_save = false;
      e.save_all = false;
      e.pending = editor_state::then::nothing;
    }
  }
}

void unsaved_changes_body(editor_state& e) {
  const bool quitting = e.pending == editor_state::then::quit;
  // Quitting with A/B asks about both slots: the list names each slot with changes.
  const std::vector<int> unsaved = quitting ? unsaved_slots(e) : std::vector<int>{e.ab.selected};
  if (unsaved.size() == 1) {
    ImGui::Text("%s has changes that are not saved.", ab_unsaved_line(e.ab, unsaved[0]).c_str());
  } else {
    ImGui::TextUnformatted("These have changes that are not saved:");
    for (int slot : unsaved) ImGui::BulletText("%s", ab_unsaved_line(e.ab, slot).c_str());
  }
  ImGui::TextUnformatted(quitting ? (unsaved.size() > 1 ? "Save them all before quitting? (A slot without a file asks where.)"
                                                        : "Save them before quitting?")
                                  : "Save them before opening another preset?");
  ImGui::Spacing();
  if (scripted_button(e, unsaved.size() > 1 ? "Save all" : "Save")) {
    ImGui::CloseCurrentPopup();
    if (quitting) {   // every slot with changes, in turn (perform_pending)
      e.save_all = true;
      perform_pending(e);
    } else if (e.cur().path.empty() || is_installed_preset(e.cur().path)) {
      e.continue_after_save = true;
      e.ask(dialog::save_as);
    } else if (save_to(e, e.cur().path)) {
      perform_pending(e);
    }
  }
  ImGui::SameLine();
  if (scripted_button(e, "Discard")) {
    ImGui::CloseCurrentPopup();
    perform_pending(e);
  }
  ImGui::SameLine();
  if (scripted_button(e, "Cancel") || ImGui::IsKeyPressed(GLFW_KEY_ESCAPE)) {
    e.pending = editor_state::then::nothing;
    ImGui::CloseCurrentPopup();
  }
}

void large_tree_body(editor_state& e) {
  const grow_result* b = e.budget_answer.get();
  // The question belongs to the slot that asked: switching A/B drops it (the slot asks again
  // when it is selected again).
  if (!b) ImGui::CloseCurrentPopup();
  if (b) {
    ImGui::Text("This will grow about %s nodes, ~%s, ~%.1f GB.", count_text(b->estimated_nodes).c_str(),
                seconds_text(b->estimated_seconds).c_str(), b->estimated_bytes / 1e9);
    if (!b->estimate_note.empty()) ImGui::TextDisabled("Keyframes and cuts after the trial's reach are %s.", b->estimate_note.c_str());
    ImGui::Text("The node budget is %s (the Edit menu or the Output tab).", count_text(double(e.cur().worker->node_budget.load())).c_str());
    if (!b->mesh_over_budget.empty()) {   // the trial's estimate of the mesh (render/io/mesh_bound.h)
      ImGui::PushTextWrapPos(ImGui::GetFontSize() * 36);
      ImGui::TextWrapped("Its mesh is estimated over the mesh budget: %s. Grown anyway, it is meshed only if its own "
                         "bound fits.", b->mesh_over_budget.c_str());
      ImGui::PopTextWrapPos();
    }
    ImGui::TextDisabled("The tree on screen stays until you choose.");
  }
  if (scripted_button(e, "Grow anyway") && b) {
    e.approve_next = true;
    e.cur().posted_once = false;   // post again, approved
    e.budget_answer.reset();
    ImGui::CloseCurrentPopup();
  }
  ImGui::SameLine();
  if (scripted_button(e, "Keep the current tree") || ImGui::IsKeyPressed(GLFW_KEY_ESCAPE)) {
    keep_shown_tree(e, "over budget: the previous tree stays");
    e.budget_answer.reset();
    ImGui::CloseCurrentPopup();
  }
}

// A tree over the mesh budget (render/io/mesh_bound.h) was not meshed: the tree on screen stays, and the
// prompt offers the radial segment count that fits or the budget the mesh needs (as edits: undoable).
void large_mesh_body(editor_state& e) {
  const grow_result* b = e.mesh_answer.get();
  if (!b) ImGui::CloseCurrentPopup();
  auto done = [&] {
    e.mesh_answer.reset();
    ImGui::CloseCurrentPopup();
  };
  if (b) {
    ImGui::Text("The mesh would take ~%.2f GB, over the mesh budget of %d MB (Mesh settings).", b->mesh_bound_bytes / 1e9,
                e.cur().doc.mesh.mesh_budget);
    ImGui::PushTextWrapPos(ImGui::GetFontSize() * 36);
    ImGui::TextDisabled("%s", b->report.message.c_str());
    ImGui::PopTextWrapPos();
    ImGui::TextDisabled("The tree on screen stays until you choose.");
    const int fit = b->mesh_fit_segments;
    if (fit > 0 && scripted_button(e, ("Use " + std::to_string(fit) + " radial segments").c_str())) {
      e.cur().doc.mesh.radial_segments = fit;
      done();
    }
    const double need_mb = std::ceil(b->mesh_bound_bytes / 1e6);
    if (b && need_mb <= 32000) {
      if (fit > 0) ImGui::SameLine();
      if (scripted_button(e, ("Raise the mesh budget to " + std::to_string(int(need_mb)) + " MB").c_str())) {
        e.cur().doc.mesh.mesh_budget = int(need_mb);
        done();
      }
    }
  }
  if (scripted_button(e, "Keep the current tree") || ImGui::IsKeyPressed(GLFW_KEY_ESCAPE)) {
    keep_shown_tree(e, "over the mesh budget: the previous tree stays");
    done();
  }
}

void drop_b_body(editor_state& e) {
  ImGui::TextUnformatted("Slot B has edits of its own. Dropping it throws them away (Save B first to keep them).");
  if (scripted_button(e, "Drop B")) {
    e.ab.drop_confirmed = true;
    handle_ab(e, ab_action::drop);
    ImGui::CloseCurrentPopup();
  }
  ImGui::SameLine();
  if (scripted_button(e, "Keep B") || ImGui::IsKeyPressed(GLFW_KEY_ESCAPE)) ImGui::CloseCurrentPopup();
}

void not_restored_body(editor_state& e) {
  for (const std::string& m : e.unrestored) {
    ImGui::PushTextWrapPos(ImGui::GetFontSize() * 36);
    ImGui::TextUnformatted(m.c_str());
    ImGui::PopTextWrapPos();
  }
  if (scripted_button(e, "OK") || ImGui::IsKeyPressed(GLFW_KEY_ESCAPE)) ImGui::CloseCurrentPopup();
}

void restore_body(editor_state& e) {
  if (e.recovered_a)
    ImGui::Text("Sylva closed with unsaved changes to \"%s\"%s%s.", e.recovered.name.c_str(),
                e.recovered_path.empty() ? "" : " from ", e.recovered_path.c_str());
  if (e.recovered_b)
    ImGui::Text("%s unsaved changes to slot B \"%s\"%s%s (restored as slot B).", e.recovered_a ? "And" : "Sylva closed with",
                e.recovered_b_doc.name.c_str(), e.recovered_b_path.empty() ? "" : " from ", e.recovered_b_path.c_str());
  ImGui::TextDisabled("Autosaved in %s", recovery_path(e, e.recovered_a ? 0 : 1).c_str());
  if (scripted_button(e, "Restore")) {
    if (e.recovered_a) {
      e.cur().undo.push_back(e.cur().doc);
      e.cur().doc = e.recovered;
      e.cur().undo_base = e.cur().doc;
      e.cur().path = e.recovered_path;
      e.frame_new = true;
    }
    e.restore_b_pending = e.recovered_b;   // once slot A's tree is shown (restore_slot_b)
    set_status(e, "Restored unsaved work; save it to keep it");
    ImGui::CloseCurrentPopup();
  }
  ImGui::SameLine();
  if (scripted_button(e, "Discard")) {
    remove_recovery(e);
    ImGui::CloseCurrentPopup();
  }
}

void about_body(editor_state&) {
  ImGui::TextUnformatted("Sylva: a tree designer.");
  ImGui::TextUnformatted("Left-drag orbits, right/middle-drag pans, the wheel zooms, F frames the tree.");
  ImGui::TextUnformatted("Ctrl+Z undo, Ctrl+Shift+Z / Ctrl+Y redo, Ctrl+S save, Ctrl+O open, F12 screenshot.");
  ImGui::TextUnformatted("Right-click a slider to reset it. Symbols: λ σ τ κ φ α s₀ w₀ r₁ r₂");
  if (ImGui::Button("Close")) ImGui::CloseCurrentPopup();
}

// The modal prompts, one row each in dialog order: the popup's title, its contents, whether the
// scripted test sees it (prompts_shown), and a popup that must close before it opens.
struct modal_prompt {
  dialog d;
  const char* title;
  void (*body)(editor_state& e);
  bool listed;
  const char* after;
};
constexpr modal_prompt modal_prompts[] = {
    {dialog::unsaved_changes, "Unsaved changes", unsaved_changes_body, true, nullptr},
    {dialog::large_tree, "Large tree", large_tree_body, true, nullptr},
    {dialog::large_mesh, "Large mesh", large_mesh_body, true, nullptr},
    {dialog::drop_b, "Drop slot B?", drop_b_body, true, nullptr},
    {dialog::not_restored, "Unsaved work not restored", not_restored_body, true, "Restore unsaved work?"},
    {dialog::restore, "Restore unsaved work?", restore_body, true, nullptr},
    {dialog::about, "About Sylva", about_body, false, nullptr},
};
static_assert(std::size(modal_prompts) == size_t(dialog::count) - size_t(dialog::unsaved_changes),
              "one modal_prompts row per modal dialog");
constexpr bool rows_in_order() {
  for (size_t k = 0; k < std::size(modal_prompts); ++k)
    if (size_t(modal_prompts[k].d) != size_t(dialog::unsaved_changes) + k) return false;
  return true;
}
static_assert(rows_in_order(), "modal_prompts rows in dialog order");

}  // namespace

void draw_dialogs(editor_state& e) {
  for (dialog use : {dialog::open_preset, dialog::save_as, dialog::screenshot_as, dialog::export_as})
    if (take(e, use)) open_browser(e, use);
  draw_browser(e);
  for (const modal_prompt& m : modal_prompts) {
    if ((!m.after || !ImGui::IsPopupOpen(m.after)) && take(e, m.d)) ImGui::OpenPopup(m.title);
    if (!ImGui::BeginPopupModal(m.title, nullptr, ImGuiWindowFlags_AlwaysAutoResize)) continue;
    if (m.listed) e.prompts_shown.push_back(m.title);
    m.body(e);
    ImGui::EndPopup();
  }
}

}  // namespace sylva::ed
