// The document: presets opened and saved, unsaved work (the quit and open prompts, recovery), undo.
#include "app/editor/editor_state.h"
#include "app/editor/editor_settings.h"
#include "app/editor/editor_undo_names.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <string>
#include <vector>
#include <cctype>

#include <GLFW/glfw3.h>
#include <imgui.h>

namespace sylva::ed {

// ---------------------------------------------------------------- presets

std::vector<fs::path> preset_dirs() {
  std::vector<fs::path> dirs;
#ifdef SYLVA_SOURCE_DIR
  dirs.emplace_back(fs::path(SYLVA_SOURCE_DIR) / "presets");
#endif
  std::error_code ec;
  fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    dirs.push_back(exe.parent_path() / "presets");
    dirs.push_back(exe.parent_path().parent_path() / "presets");
  }
  dirs.push_back(fs::current_path(ec) / "presets");
  return dirs;
}

void open_preset(editor_state& e, const std::string& path) {
  preset loaded;
  load_result r = load_preset_file(path, loaded);
  if (!r.ok) {   // the current tree stays as it is
    set_status(e, "Cannot open " + path + ": " + r.error, true);
    return;
  }
  if (!e.before_open) e.before_open = std::make_unique<editor_state::document>(
      editor_state::document{e.cur().doc, e.cur().path, e.cur().baseline, e.cur().baseline_path});
  e.cur().undo.push_back(e.cur().doc);
  e.cur().redo.clear();
  e.cur().doc = loaded;
  e.cur().undo_base = loaded;
  e.cur().path = path;
  note_saved(e, path);
  note_recent(e.recent, path);
  // The camera stays where it is once a tree is on screen, so that a preset reopened (or another
  // one) compares from the same view; F frames it. The first tree is framed.
  const bool tree_on_screen = e.cur().shown && e.cur().shown->skeleton;
  e.frame_new = !tree_on_screen;
  e.keep_view = tree_on_screen;
  std::string m = "Opened " + path + (tree_on_screen ? " (the view is kept: F frames the tree)" : "");
  if (!r.warnings.empty()) m += " (" + std::to_string(r.warnings.size()) + " warning(s): " + r.warnings.front() + ")";
  set_status(e, m, false);
}

// The selected slot's document as opened or saved (the unsaved-changes mark). The library
// rescans: a save may have changed a listed file and so its thumbnail.
void note_saved(editor_state& e, const std::string& path) {
  editor_slot& s = e.cur();
  s.baseline = s.doc;
  std::error_code ec;
  s.baseline_path = path.empty() ? "" : fs::weakly_canonical(path, ec).string();   // as the library lists it
  e.browser.rescan = true;
}

bool save_to(editor_state& e, const std::string& path) {
  std::error_code ec;
  fs::create_directories(fs::path(path).parent_path(), ec);
  std::string err = save_preset_file(e.cur().doc, path);
  if (!err.empty()) {
    set_status(e, "Save failed: " + err, true);
    return false;
  }
  e.cur().path = path;
  note_saved(e, path);
  note_recent(e.recent, path);
  set_status(e, "Saved " + path);
  return true;
}

// ---------------------------------------------------------------- unsaved work

// The user's own folder for saves, exports, screenshots and the recovery file: $SYLVA_HOME, else ~/Sylva.
std::string user_folder() {
  if (const char* h = std::getenv("SYLVA_HOME"); h && *h) return h;
  if (const char* h = std::getenv("HOME"); h && *h) return (fs::path(h) / "Sylva").string();
  return (fs::current_path() / "Sylva").string();
}

// A shipped preset is never overwritten by Save: it goes to Save as in the user's folder instead.
bool is_installed_preset(const std::string& path) {
  if (path.empty()) return false;
  std::error_code ec;
  const fs::path p = fs::weakly_canonical(path, ec);
  for (const fs::path& d : preset_dirs()) {
    const fs::path c = fs::weakly_canonical(d, ec);
    if (!ec && p.parent_path() == c) return true;
  }
  return false;
}

// "My tree" -> "~/Sylva/my_tree.json".
std::string default_save_path(const editor_state& e) {
  if (!e.cur().path.empty() && !is_installed_preset(e.cur().path)) return e.cur().path;
  return (fs::path(e.home) / (file_stem_for(e.cur().doc.name) + ".json")).string();
}

std::string file_stem_for(const std::string& name) {
  std::string stem;
  bool gap = false;   // a run of other characters since the last letter or digit
  for (char c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c))) {
      gap = !stem.empty();
      continue;
    }
    if (gap) stem += '_';
    gap = false;
    stem += char(std::tolower(static_cast<unsigned char>(c)));
  }
  return stem.empty() ? "tree" : stem;
}

bool modified(const editor_state& e) { return !(e.cur().doc == e.cur().baseline); }

std::string window_title_text(const editor_state& e) {
  return std::string("Sylva - ") + (e.ab.has_b ? (e.ab.selected == 0 ? "[A] " : "[B] ") : "") + e.cur().doc.name + (modified(e) ? " *" : "");
}

// The slots with unsaved changes (A/B: both slots; the selected one first).
std::vector<int> unsaved_slots(const editor_state& e) { return ab_unsaved_slots(e.ab); }

// Slot A's recovery file, or slot B's (hidden from the file browser).
std::string recovery_path(const editor_state& e, int slot) {
  return (fs::path(e.home) / (slot == 0 ? ".recovery.json" : ".recovery_b.json")).string();
}

void remove_recovery(editor_state& e, int slot) {
  if (e.autosave_off[slot]) return;   // an unusable autosave that could not be moved aside stays
  std::error_code ec;
  fs::remove(recovery_path(e, slot), ec);
  fs::remove(recovery_path(e, slot) + ".source", ec);
  e.autosaved_any[slot] = false;
}
void remove_recovery(editor_state& e) {
  remove_recovery(e, 0);
  remove_recovery(e, 1);
}

namespace {

// An autosave that cannot be offered back is the user's work all the same: it is moved aside to
// ~/Sylva/unrestored-YYYYMMDD-HHMMSS[-b].json (a name the next autosave never writes), and the
// editor says why and where. If it cannot be moved, that slot's autosave stays off this session.
void keep_unrestored(editor_state& e, int slot, const std::string& file, const std::string& why) {
  char stamp[32];
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  localtime_r(&now, &tm);
  std::strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S", &tm);
  std::error_code ec;
  std::string kept;
  for (int n = 0; n < 100 && kept.empty(); ++n) {
    const std::string name = std::string("unrestored-") + stamp + (slot ? "-b" : "") + (n ? "-" + std::to_string(n) : "") + ".json";
    const fs::path to = fs::path(e.home) / name;
    if (fs::exists(fs::symlink_status(to, ec))) continue;
    fs::rename(file, to, ec);
    if (ec) break;
    kept = to.string();
    fs::rename(file + ".source", kept + ".source", ec);   // best effort: it only names the document's path
  }
  std::string m = "The autosaved work in " + file + " cannot be offered back: " + why + ". ";
  if (!kept.empty()) {
    m += "It is kept as " + kept + "; fix it in a text editor and open it.";
  } else {
    e.autosave_off[slot] = true;
    m += "It could not be moved aside, so it stays where it is and this session does not autosave over it.";
  }
  e.unrestored.push_back(m);
  e.ask(dialog::not_restored);
  set_status(e, m, true);   // also on stderr
}

}  // namespace

// Work left unsaved by a crash or a killed session (each slot's autosave), offered back at start.
// One that cannot be used is kept under another name and said (keep_unrestored).
void find_recovery(editor_state& e) {
  for (int slot = 0; slot < 2; ++slot) {
    std::error_code ec;
    const std::string file = recovery_path(e, slot);
    if (!fs::exists(fs::symlink_status(file, ec))) continue;
    std::string json, source, why = read_file(file, json, max_preset_bytes);
    if (why.empty() && fs::exists(fs::symlink_status(file + ".source", ec)))
      why = read_file(file + ".source", source, settings_path_max + 1);
    preset& doc = slot == 0 ? e.recovered : e.recovered_b_doc;
    if (why.empty()) why = parse_recovery(json, source, doc, slot == 0 ? e.recovered_path : e.recovered_b_path);
    if (!why.empty()) {
      keep_unrestored(e, slot, file, why);
      continue;
    }
    (slot == 0 ? e.recovered_a : e.recovered_b) = true;
    e.ask(dialog::restore);
  }
}

// Every few seconds while modified: each slot's document to ~/Sylva/.recovery[_b].json, its own
// path beside it. Slots are A and B, not selected and other, so a recovery names the right slot.
void autosave(editor_state& e, double dt) {
  if (e.quit_confirmed) return;
  const std::vector<int> unsaved = unsaved_slots(e);
  for (int slot = 0; slot < 2; ++slot)
    if (e.autosaved_any[slot] && std::find(unsaved.begin(), unsaved.end(), slot) == unsaved.end()) remove_recovery(e, slot);
  if (unsaved.empty()) {
    e.autosave_wait = 0;
    return;
  }
  e.autosave_wait += dt;
  if (e.autosave_wait < 3.0) return;
  e.autosave_wait = 0;
  std::error_code ec;
  fs::create_directories(e.home, ec);
  for (int slot : unsaved) {
    if (e.autosave_off[slot]) continue;
    const editor_slot& s = e.ab.slots[slot];
    const preset& doc = s.doc;
    if (e.autosaved_any[slot] && doc == e.autosaved[slot]) continue;
    if (!save_preset_file(doc, recovery_path(e, slot)).empty()) continue;   // best effort; never interrupts
    (void)write_file_atomic(recovery_path(e, slot) + ".source", s.path);
    e.autosaved[slot] = doc;
    e.autosaved_any[slot] = true;
  }
}


namespace {

// Quit with "Save": saves the next slot with unsaved changes (the selected one first). A slot
// without its own file selects it and asks where (Save as), then goes on. Returns false when a
// slot is waiting for its Save as, or a save failed (the quit stops there).
bool save_next_slot(editor_state& e) {
  const std::vector<int> unsaved = unsaved_slots(e);
  if (unsaved.empty()) return true;
  if (e.ab.has_b && unsaved.front() != e.ab.selected) select_slot(e, unsaved.front());
  if (e.cur().path.empty() || is_installed_preset(e.cur().path)) {
    e.continue_after_save = true;
    e.ask(dialog::save_as);
    return false;
  }
  if (!save_to(e, e.cur().path)) {
    e.save_all = false;
    e.pending = editor_state::then::nothing;
    return false;
  }
  return true;
}

}  // namespace

// Carries out what waited for the unsaved-changes question.
void perform_pending(editor_state& e) {
  // Quitting with "Save" and two slots: every slot with changes is saved before the quit.
  if (e.pending == editor_state::then::quit && e.save_all) {
    while (!unsaved_slots(e).empty())
      if (!save_next_slot(e)) return;
    e.save_all = false;
  }
  const editor_state::then what = e.pending;
  e.pending = editor_state::then::nothing;
  e.continue_after_save = false;
  if (what == editor_state::then::quit) {
    e.quit_confirmed = true;
    remove_recovery(e);
    glfwSetWindowShouldClose(e.window, GLFW_TRUE);
  } else if (what == editor_state::then::open) {
    open_preset(e, e.pending_path);
  }
}

// Quit, window close, Open and the library go through here: asks first when the document is
// modified. Open replaces the selected slot only; quitting asks about both A/B slots.
void request(editor_state& e, editor_state::then what, const std::string& path) {
  e.pending = what;
  e.pending_path = path;
  e.save_all = false;
  if (what == editor_state::then::quit ? unsaved_slots(e).empty() : !modified(e)) return perform_pending(e);
  e.ask(dialog::unsaved_changes);
}

// Save: to the document's own file, or Save as when it has none or it is a shipped preset.
void save_command(editor_state& e) {
  if (e.cur().path.empty() || is_installed_preset(e.cur().path)) e.ask(dialog::save_as);
  else save_to(e, e.cur().path);
}

// ---------------------------------------------------------------- undo

void apply_undo(editor_state& e, std::vector<preset>& from, std::vector<preset>& to) {
  if (from.empty()) return;
  const bool undoing = &from == &e.cur().undo;
  const std::string what = undoing ? change_name(from.back(), e.cur().doc) : change_name(e.cur().doc, from.back());
  to.push_back(e.cur().doc);
  e.cur().doc = from.back();
  from.pop_back();
  e.cur().undo_base = e.cur().doc;
  if (!what.empty()) set_status(e, (undoing ? "Undone: " : "Redone: ") + what);
}

// One undo step per completed edit: nothing is recorded while a widget is held.
// A completed edit that would leave a document the loader refuses (keyframes or cuts on a text
// L-system) is taken back with the reason, so every document the editor holds saves and reopens.
void record_undo(editor_state& e) {
  // A number that is not finite (a field typed "1e999") is put back at once, while its field is
  // still active too: the document is posted to the worker in this frame.
  if (std::string why = non_finite_refusal(e.cur().doc); !why.empty() && non_finite_refusal(e.cur().undo_base).empty()) {
    e.cur().doc = e.cur().undo_base;
    return set_status(e, "Not applied: " + why, true);
  }
  if (ImGui::IsAnyItemActive() || e.cur().doc == e.cur().undo_base) return;
  if (std::string why = document_refusal(e.cur().doc); !why.empty() && document_refusal(e.cur().undo_base).empty()) {
    e.cur().doc = e.cur().undo_base;
    set_status(e, "Not applied: " + why + ". Delete those keyframes or cuts first.", true);
    return;
  }
  e.cur().undo.push_back(e.cur().undo_base);
  if (e.cur().undo.size() > 200) e.cur().undo.erase(e.cur().undo.begin());
  e.cur().redo.clear();
  e.cur().undo_base = e.cur().doc;
}

}  // namespace sylva::ed
