// The editor's keys and mouse gestures from one table (editor_state.h): the F1 list, the menus'
// key labels and the keys each frame reads.
#include "app/editor/editor_state.h"

#include <algorithm>
#include <array>
#include <iterator>

#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_internal.h>

#include "app/editor/view_gizmo.h"

namespace sylva::ed {

namespace {

// Esc closes what is on top: an open menu or popup (a modal dialog answers Esc itself, as Cancel),
// else the library, the F1 list, the message log or the export dialog (unless it is writing).
void close_on_escape(editor_state& e) {
  const ImGuiContext& g = *GImGui;
  if (!g.OpenPopupStack.empty()) {
    const ImGuiWindow* top = g.OpenPopupStack.back().Window;
    if (!top || !(top->Flags & ImGuiWindowFlags_Modal)) ImGui::ClosePopupsExceptModals();
  } else if (e.browser.open) {
    e.browser.open = false;
  } else if (e.show_shortcuts) {
    e.show_shortcuts = false;
  } else if (e.show_log) {
    e.show_log = false;
  } else if (e.exporter.open && !e.exporter.running) {
    e.exporter.open = false;
  }
}

// A row's keys read this frame: what they do when pressed (ctrl and shift held or not).
using key_reader = void (*)(editor_state& e, bool ctrl, bool shift);

int steps_shown(const editor_state& e) {
  return e.cur().shown && e.cur().shown->skeleton ? e.cur().shown->skeleton->steps : 0;
}

// One row per shortcut in shortcut order (the F1 list's): the keys as the list shows them, as the
// menus show them (null: as the list), what it does, and for keys, their reader, whether it works
// while a text field has the keyboard (the panel's or the library's search box: the keys type
// nothing there, and a newcomer who clicked into one still gets them), and its rank in the order
// the keys are read each frame (two keys in one frame act in that order). A gesture has no reader:
// the view and the sliders take it where they are drawn.
struct shortcut_row {
  shortcut id;
  const char* keys;
  const char* menu;
  const char* does;
  key_reader read;
  bool in_text;
  int rank;
};

constexpr shortcut_row shortcut_rows[] = {
    {shortcut::orbit, "Left-drag", nullptr, "orbit", nullptr, false, 0},
    {shortcut::pan, "Right- or middle-drag", nullptr, "pan", nullptr, false, 0},
    {shortcut::zoom, "Wheel", nullptr, "zoom", nullptr, false, 0},
    {shortcut::frame, "F", nullptr, "frame the tree",
     [](editor_state& e, bool ctrl, bool) { if (!ctrl && ImGui::IsKeyPressed(GLFW_KEY_F)) e.frame_now = true; }, false, 10},
    // Undo and redo take one step per press: a held Ctrl+Z does not run through the history
    // (neither the system's key repeats nor ImGui's own, which fires when a slow frame outlasts its
    // delay).
    {shortcut::undo, "Ctrl+Z", nullptr, "undo",
     [](editor_state& e, bool ctrl, bool shift) {
       if (ctrl && ImGui::IsKeyPressed(GLFW_KEY_Z, false) && !e.input.is_repeat(GLFW_KEY_Z)) {
         if (shift) apply_undo(e, e.cur().redo, e.cur().undo);   // Ctrl+Shift+Z: redo
         else apply_undo(e, e.cur().undo, e.cur().redo);
       }
     }, false, 7},
    {shortcut::redo, "Ctrl+Shift+Z, Ctrl+Y", "Ctrl+Shift+Z", "redo",   // (Ctrl+Shift+Z: the undo row reads it)
     [](editor_state& e, bool ctrl, bool) {
       if (ctrl && ImGui::IsKeyPressed(GLFW_KEY_Y, false) && !e.input.is_repeat(GLFW_KEY_Y)) apply_undo(e, e.cur().redo, e.cur().undo);
     }, false, 8},
    {shortcut::save, "Ctrl+S", nullptr, "save (Save as for shipped presets)",
     [](editor_state& e, bool ctrl, bool) { if (ctrl && ImGui::IsKeyPressed(GLFW_KEY_S)) save_command(e); }, false, 4},
    {shortcut::open, "Ctrl+O", nullptr, "open a preset",
     [](editor_state& e, bool ctrl, bool) { if (ctrl && ImGui::IsKeyPressed(GLFW_KEY_O)) e.ask(dialog::open_preset); }, false, 5},
    {shortcut::library, "Ctrl+L", nullptr, "preset library",
     [](editor_state& e, bool ctrl, bool) { if (ctrl && ImGui::IsKeyPressed(GLFW_KEY_L)) e.browser.open = !e.browser.open; }, true, 1},
    {shortcut::quit, "Ctrl+Q", nullptr, "quit (asks about unsaved changes)",
     [](editor_state& e, bool ctrl, bool) { if (ctrl && ImGui::IsKeyPressed(GLFW_KEY_Q)) request(e, editor_state::then::quit); }, false, 6},
    {shortcut::play, "Space", nullptr, "play / pause the growth",
     [](editor_state& e, bool ctrl, bool) { if (!ctrl && ImGui::IsKeyPressed(GLFW_KEY_SPACE)) e.playing = !e.playing; }, false, 11},
    {shortcut::first_last, "Home, End", nullptr, "first / last step",
     [](editor_state& e, bool, bool) {
       if (ImGui::IsKeyPressed(GLFW_KEY_HOME)) e.step = 0;
       if (ImGui::IsKeyPressed(GLFW_KEY_END)) e.step = steps_shown(e);
     }, false, 12},
    {shortcut::step, "Left, Right", nullptr, "one step back / forward",
     [](editor_state& e, bool, bool) {
       if (ImGui::IsKeyPressed(GLFW_KEY_LEFT)) e.step = std::max(0, e.step - 1);
       if (ImGui::IsKeyPressed(GLFW_KEY_RIGHT)) e.step = std::min(steps_shown(e), e.step + 1);
     }, false, 13},
    {shortcut::escape, "Esc", nullptr, "cancel a long regrow; else close the open menu, dialog, library or this list",
     [](editor_state& e, bool, bool) {
       if (!ImGui::IsKeyPressed(GLFW_KEY_ESCAPE)) return;
       if (long_growth(e) && !ImGui::IsPopupOpen("", ImGuiPopupFlags_AnyPopupId)) cancel_request(e);
       else close_on_escape(e);
     }, true, 0},
    {shortcut::screenshot, "F12", nullptr, "screenshot of the 3D view",
     [](editor_state& e, bool, bool) { if (ImGui::IsKeyPressed(GLFW_KEY_F12)) e.screenshot_requested = true; }, true, 3},
    {shortcut::help, "F1", nullptr, "this list",
     [](editor_state& e, bool, bool) { if (ImGui::IsKeyPressed(GLFW_KEY_F1)) e.show_shortcuts = !e.show_shortcuts; }, true, 2},
    // Front, right side and top views (Blender's numpad keys; Ctrl: the opposite side).
    {shortcut::views, "Numpad 1, 3, 7 (or 1, 3, 7)", nullptr, "front, right, top view (Ctrl: the opposite side)",
     [](editor_state& e, bool ctrl, bool) {
       const struct { int kp, row; view_axis axis, opposite; } views[] = {{GLFW_KEY_KP_1, GLFW_KEY_1, view_axis::front, view_axis::back},
                                                                          {GLFW_KEY_KP_3, GLFW_KEY_3, view_axis::right, view_axis::left},
                                                                          {GLFW_KEY_KP_7, GLFW_KEY_7, view_axis::top, view_axis::bottom}};
       for (const auto& v : views)
         if (ImGui::IsKeyPressed(v.kp) || ImGui::IsKeyPressed(v.row)) snap_view(e.camera, ctrl ? v.opposite : v.axis);
     }, false, 9},
    {shortcut::gizmo, "Click the axis gizmo", nullptr, "view along that axis", nullptr, false, 0},
    {shortcut::slider_drag, "Drag a slider", nullptr, "change it; Shift: fine steps; Ctrl+click: type a value", nullptr, false, 0},
    {shortcut::slider_reset, "Right-click a slider", nullptr, "reset it to its default", nullptr, false, 0},
};
static_assert(std::size(shortcut_rows) == size_t(shortcut::count), "one shortcut_rows row per shortcut");
constexpr bool rows_in_order() {
  for (size_t k = 0; k < std::size(shortcut_rows); ++k)
    if (size_t(shortcut_rows[k].id) != k) return false;
  return true;
}
static_assert(rows_in_order(), "shortcut_rows in shortcut order");

// The rows with keys, by rank.
std::array<const shortcut_row*, std::size(shortcut_rows)> by_rank(size_t& count) {
  std::array<const shortcut_row*, std::size(shortcut_rows)> out{};
  count = 0;
  for (const shortcut_row& r : shortcut_rows)
    if (r.read) out[count++] = &r;
  std::sort(out.begin(), out.begin() + std::ptrdiff_t(count), [](const shortcut_row* a, const shortcut_row* b) { return a->rank < b->rank; });
  return out;
}

}  // namespace

const char* shortcut_keys(shortcut s) {
  const shortcut_row& r = shortcut_rows[size_t(s)];
  return r.menu ? r.menu : r.keys;
}

void handle_keys(editor_state& e) {
  static size_t count = 0;
  static const auto ranked = by_rank(count);
  ImGuiIO& io = ImGui::GetIO();
  const bool ctrl = io.KeyCtrl, shift = io.KeyShift;
  // The keys that work in a text field rank first: the rest wait while one has the keyboard.
  for (size_t k = 0; k < count; ++k) {
    if (!ranked[k]->in_text && io.WantTextInput) return;
    ranked[k]->read(e, ctrl, shift);
  }
}

void draw_shortcuts(editor_state& e) {
  if (!e.show_shortcuts) return;
  ImGui::SetNextWindowSize(ImVec2(560 * ui_scale, 0), ImGuiCond_Appearing);
  if (ImGui::Begin("Keyboard and mouse", &e.show_shortcuts, ImGuiWindowFlags_AlwaysAutoResize)) {
    if (ImGui::BeginTable("keys", 2, ImGuiTableFlags_RowBg)) {
      for (const shortcut_row& r : shortcut_rows) {
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(r.keys);
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(r.does);
      }
      ImGui::EndTable();
    }
    ImGui::Separator();
    ImGui::TextWrapped("README.md explains more: \"The editor\" (panels, timeline, presets), \"The four "
                       "generators\" (the papers behind the parameters), \"Command line\" and \"Rendering at scale\".");
  }
  ImGui::End();
}

}  // namespace sylva::ed
