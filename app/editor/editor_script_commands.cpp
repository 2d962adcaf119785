// The scripted session's commands (app/editor/editor_script.h, which says what each does): a
// table, one row per command name, each with its handler.
#include "app/editor/editor_script.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include <GLFW/glfw3.h>
#include <imgui.h>

namespace sylva::ed {

namespace {

using clock = std::chrono::steady_clock;

int glfw_key(const std::string& name) {
  if (name.size() == 1 && std::isalpha(static_cast<unsigned char>(name[0]))) return GLFW_KEY_A + (std::tolower(name[0]) - 'a');
  if (name.size() == 1 && std::isdigit(static_cast<unsigned char>(name[0]))) return GLFW_KEY_0 + (name[0] - '0');
  if (name == "escape") return GLFW_KEY_ESCAPE;
  if (name == "enter") return GLFW_KEY_ENTER;
  if (name == "backspace") return GLFW_KEY_BACKSPACE;
  if (name == "space") return GLFW_KEY_SPACE;
  if (name == "f12") return GLFW_KEY_F12;
  if (name == "f1") return GLFW_KEY_F1;
  if (name == "end") return GLFW_KEY_END;
  if (name == "home") return GLFW_KEY_HOME;
  if (name == "kp1") return GLFW_KEY_KP_1;
  if (name == "kp3") return GLFW_KEY_KP_3;
  if (name == "kp7") return GLFW_KEY_KP_7;
  return GLFW_KEY_UNKNOWN;
}

std::vector<std::string> words(const std::string& s) {
  std::vector<std::string> out;
  std::istringstream in(s);
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

// Handlers two commands share: each reads which it runs from call.cmd.

// expect_file_size, wait_file_size_over: PATH N; the second waits for it
std::string file_size(script_call& call) {
  const std::string& arg = call.arg; const std::string& cmd = call.cmd; const double waited = call.waited; bool& done = call.done;
  const std::string path = arg.substr(0, arg.rfind(' '));
  const auto n = std::uintmax_t(std::atoll(arg.substr(arg.rfind(' ') + 1).c_str()));
  std::error_code ec;
  const std::uintmax_t size = fs::exists(path, ec) ? fs::file_size(path, ec) : 0;
  if (cmd == "expect_file_size" && size != n) return path + " holds " + std::to_string(size) + " bytes";
  done = size > n;
  if (cmd == "expect_file_size") done = true;
  else if (!done && waited > 180) return path + " still holds " + std::to_string(size) + " bytes";
  return "";
}

// expect_recovery, expect_recovery_b
std::string recovery_file(script_call& call) {
  editor_state& e = call.e; const std::string& arg = call.arg; const std::string& cmd = call.cmd; const double waited = call.waited; bool& done = call.done;
  // "1": the file is there and holds the slot's current document (an autosave taken before the
  // last edit is not yet the work that a crash would leave); "0": the file is gone.
  std::error_code ec;
  const int slot = cmd == "expect_recovery" ? 0 : 1;
  const preset& now = e.ab.slots[e.ab.has_b ? slot : 0].doc;
  const bool there = fs::exists(recovery_path(e, slot), ec);
  done = arg == "1" ? there && e.autosaved_any[slot] && e.autosaved[slot] == now : !there;
  if (!done && waited > 20) return arg == "1" ? "no recovery file" : "the recovery file stays";
  return "";
}

// key, taps
std::string key_taps(script_call& call) {
  editor_state& e = call.e; script_state& sc = call.sc; const std::string& arg = call.arg; const std::string& cmd = call.cmd;
  std::string name = arg;
  int taps = 1;
  if (cmd == "taps") {   // taps N KEY: N press/release pairs queued at once between two frames
    taps = std::atoi(arg.c_str());
    name = arg.substr(std::min(arg.size(), arg.find(' ') + 1));
  }
  bool ctrl = false, shift = false;
  for (;;) {
    if (name.rfind("ctrl+", 0) == 0) ctrl = true, name = name.substr(5);
    else if (name.rfind("shift+", 0) == 0) shift = true, name = name.substr(6);
    else break;
  }
  const int k = glfw_key(name);
  if (k == GLFW_KEY_UNKNOWN) return "unknown key";
  if (ctrl) e.input.push_key(GLFW_KEY_LEFT_CONTROL, GLFW_PRESS);
  if (shift) e.input.push_key(GLFW_KEY_LEFT_SHIFT, GLFW_PRESS);
  for (int i = 0; i < taps; ++i) {
    e.input.push_key(k, GLFW_PRESS);
    e.input.push_key(k, GLFW_RELEASE);
  }
  if (shift) e.input.push_key(GLFW_KEY_LEFT_SHIFT, GLFW_RELEASE);
  if (ctrl) e.input.push_key(GLFW_KEY_LEFT_CONTROL, GLFW_RELEASE);
  sc.frames_left = 2 * taps + 3;   // let the queued events drain before the next command
  return "";
}

// expect_same_tree, expect_new_tree
std::string same_or_new_tree(script_call& call) {
  editor_state& e = call.e; script_state& sc = call.sc; const std::string& cmd = call.cmd;
  const bool same = e.cur().shown && e.cur().shown->skeleton.get() == sc.remembered;
  if (same != (cmd == "expect_same_tree")) return same ? "the tree did not change" : "the tree changed";
  return "";
}

struct script_command {
  const char* name;
  script_handler run;
};

const script_command script_commands[] = {
    {"wait_tree", [](script_call& call) -> std::string {
      editor_state& e = call.e; const double waited = call.waited; const bool growing = call.growing; bool& done = call.done;
      done = !growing && e.cur().shown;
      if (!done && waited > 120) return "no tree after 120 s";
      return "";
    }},
    {"set", [](script_call& call) -> std::string {
      editor_state& e = call.e; script_state& sc = call.sc; const std::string& arg = call.arg;
      if (std::string err = set_preset_param(e.cur().doc, arg); !err.empty()) return err;
      sc.frames_left = 2;   // posted on the next frame
      return "";
    }},
    {"set_all", [](script_call& call) -> std::string {   // several assignments in one frame: one request
      editor_state& e = call.e; script_state& sc = call.sc; const std::string& arg = call.arg;
      preset edited = e.cur().doc;
      for (const std::string& a : words(arg))
        if (std::string err = set_preset_param(edited, a); !err.empty()) return err;
      e.cur().doc = edited;
      sc.frames_left = 2;
      return "";
    }},
    {"expect_title", [](script_call& call) -> std::string {
      editor_state& e = call.e; const std::string& arg = call.arg;
      if (e.window_title != arg) return "the title is \"" + e.window_title + "\"";
      return "";
    }},
    {"status", [](script_call& call) -> std::string {
      editor_state& e = call.e; script_state& sc = call.sc; const std::string& arg = call.arg;
      set_status(e, arg);
      sc.frames_left = 2;
      return "";
    }},
    {"expect_status_fits", [](script_call& call) -> std::string {   // the status bar's text ends inside the window; "cut": a piece was cut
      editor_state& e = call.e; const std::string& arg = call.arg;
      int w = 0, h = 0;
      glfwGetWindowSize(e.window, &w, &h);
      if (e.status_right > float(w)) return "the status runs to x " + std::to_string(e.status_right) + " of " + std::to_string(w);
      if (arg == "cut" && e.status_cut.empty()) return "no piece of the status was cut";
      if (arg == "cut") std::printf("sylva script: status cut, whole in its tooltip: %s\n", e.status_cut.c_str());
      return "";
    }},
    {"expect_marker", [](script_call& call) -> std::string {   // expect_marker STEP: its marker sits at STEP / the steps grown
      editor_state& e = call.e; const std::string& arg = call.arg;
      const int k = std::atoi(arg.c_str());
      const int grown = e.cur().shown && e.cur().shown->skeleton ? e.cur().shown->skeleton->steps : 0;
      auto it = std::find_if(e.keys.drawn.begin(), e.keys.drawn.end(), [&](const auto& m) { return m.first == k; });
      if (it == e.keys.drawn.end() || grown <= 0) return "no marker at step " + arg;
      const float want = float(std::min(k, grown)) / float(grown);
      std::printf("sylva script: marker at step %d drawn at %.3f of the timeline (%d steps grown)\n", k, it->second, grown);
      if (std::abs(it->second - want) > 0.01f) return "the marker sits at " + std::to_string(it->second) + ", not " + std::to_string(want);
      return "";
    }},
    {"library_folders", [](script_call& call) -> std::string {   // the library lists these folders (space separated) instead
      editor_state& e = call.e; const std::string& arg = call.arg;
      e.browser.folders = words(arg);
      e.browser.rescan = true;
      return "";
    }},
    {"wait_thumbnails", [](script_call& call) -> std::string {   // until every card of the open library has its picture
      editor_state& e = call.e; const double waited = call.waited; bool& done = call.done;
      done = e.browser.open && e.browser.ready_s >= 0;
      if (!done && waited > 900) return "thumbnails still missing after 900 s";
      if (done)
        std::printf("sylva script: thumbnails: %zu cards, %d rendered, %d from the cache, %zu without a picture, all drawn %.1f s after the library opened\n",
                    e.browser.entries.size(), e.browser.rendered, e.browser.from_cache, e.browser.failed.size(), e.browser.ready_s);
      return "";
    }},
    {"expect_cards", [](script_call& call) -> std::string {   // expect_cards NAME N: the library lists N cards named NAME
      editor_state& e = call.e; const std::string& arg = call.arg;
      const std::string name = arg.substr(0, arg.rfind(' '));
      const long n = std::count_if(e.browser.entries.begin(), e.browser.entries.end(), [&](const preset_entry& c) { return c.name == name; });
      if (n != std::atol(arg.substr(arg.rfind(' ') + 1).c_str())) return std::to_string(n) + " cards named " + name;
      return "";
    }},
    {"menu_export_as", [](script_call& call) -> std::string {   // File > Export as...: the file browser opens
      editor_state& e = call.e; script_state& sc = call.sc;
      e.ask(dialog::export_as);
      sc.frames_left = 3;
      return "";
    }},
    {"file_path", [](script_call& call) -> std::string {   // the open file browser's folder and name, as if typed
      editor_state& e = call.e; const std::string& arg = call.arg;
      e.files.folder = fs::path(arg).parent_path().string();
      e.files.name = fs::path(arg).filename().string();
      e.files.confirm_overwrite = false;
      return "";
    }},
    {"expect_export_asking", [](script_call& call) -> std::string {   // the Export dialog asks before replacing its file
      editor_state& e = call.e; const std::string& arg = call.arg;
      std::error_code ec;
      const bool asking = fs::exists(e.exporter.path, ec) && e.exporter.confirm_replace == e.exporter.path;
      if (asking != (arg == "1")) return asking ? "the dialog asks to replace" : "the dialog does not ask";
      return "";
    }},
    {"expect_file_size", file_size},
    {"wait_file_size_over", file_size},
    {"expect_ab_labels", [](script_call& call) -> std::string {   // both A/B labels fit their parts; the selected one says so
      editor_state& e = call.e;
      const std::string& sel = e.ab.labels_shown[e.ab.selected];
      std::printf("sylva script: A/B labels \"%s\" | \"%s\"\n", e.ab.labels_shown[0].c_str(), e.ab.labels_shown[1].c_str());
      if (!e.ab.labels_fit) return "an A/B label runs past its part of the view";
      if (sel.size() < 10 || sel.compare(sel.size() - 10, 10, "(selected)") != 0) return "the selected slot's label is \"" + sel + "\"";
      return "";
    }},
    {"expect_doc_name", [](script_call& call) -> std::string {
      editor_state& e = call.e; const std::string& arg = call.arg;
      if (e.cur().doc.name != arg) return "the document is \"" + e.cur().doc.name + "\"";
      return "";
    }},
    {"expect_recovery", recovery_file},
    {"expect_recovery_b", recovery_file},
    {"wait_growing", [](script_call& call) -> std::string {
      editor_state& e = call.e; const std::string& arg = call.arg; const bool growing = call.growing; bool& done = call.done;
      if (!growing) return "the growth ended before " + arg + " s";
      done = seconds_since(e.cur().posted_at) >= std::atof(arg.c_str());
      return "";
    }},
    {"expect_other_state", [](script_call& call) -> std::string {
      editor_state& e = call.e; const std::string& arg = call.arg; const double waited = call.waited; bool& done = call.done;
      static const char* names[] = {"idle", "growing", "asking", "done", "cancelled", "failed"};
      const int st = e.ab.has_b ? int(e.ab.other().growth) : 0;
      done = arg == names[std::clamp(st, 0, 5)];
      if (!done && waited > 60) return std::string("the other slot's state is ") + names[std::clamp(st, 0, 5)];
      return "";
    }},
    {"key", key_taps},
    {"taps", key_taps},
    {"hold", [](script_call& call) -> std::string {   // hold [ctrl+]NAME N: a press, N system repeats and a release, queued at once
      editor_state& e = call.e; script_state& sc = call.sc; const std::string& arg = call.arg;
      std::string name = arg.substr(0, arg.find(' '));
      const int repeats = std::atoi(arg.substr(std::min(arg.size(), arg.find(' ') + 1)).c_str());
      const bool ctrl = name.rfind("ctrl+", 0) == 0;
      if (ctrl) name = name.substr(5);
      const int k = glfw_key(name);
      if (k == GLFW_KEY_UNKNOWN) return "unknown key";
      if (ctrl) e.input.push_key(GLFW_KEY_LEFT_CONTROL, GLFW_PRESS);
      e.input.push_key(k, GLFW_PRESS);
      for (int i = 0; i < repeats; ++i) e.input.push_key(k, GLFW_REPEAT);
      e.input.push_key(k, GLFW_RELEASE);
      if (ctrl) e.input.push_key(GLFW_KEY_LEFT_CONTROL, GLFW_RELEASE);
      sc.frames_left = repeats + 6;
      return "";
    }},
    {"type", [](script_call& call) -> std::string {   // type TEXT: every key press, character and release queued at once (a slow frame)
      editor_state& e = call.e; script_state& sc = call.sc; const std::string& arg = call.arg;
      for (char c : arg) {
        const int k = std::isalpha(static_cast<unsigned char>(c)) ? GLFW_KEY_A + (std::tolower(c) - 'a')
                      : c == '/'                                  ? GLFW_KEY_SLASH
                      : c == '.'                                  ? GLFW_KEY_PERIOD
                      : std::isdigit(static_cast<unsigned char>(c)) ? GLFW_KEY_0 + (c - '0')
                                                                  : GLFW_KEY_SPACE;
        e.input.push_key(k, GLFW_PRESS);
        e.input.push_char(static_cast<unsigned char>(c));
        e.input.push_key(k, GLFW_RELEASE);
      }
      sc.frames_left = 2 * int(arg.size()) + 4;
      return "";
    }},
    {"click", [](script_call& call) -> std::string {   // click TARGET: a move onto it, a press and a release, queued at once
      editor_state& e = call.e; script_state& sc = call.sc; const std::string& arg = call.arg;
      float x = 0, y = 0;
      if (arg == "export_path") x = e.exporter.path_at[0], y = e.exporter.path_at[1];
      else if (arg == "export_button") x = e.exporter.export_at[0], y = e.exporter.export_at[1];
      else if (arg.rfind("card ", 0) == 0) {   // click card NAME: the library's card of that preset
        auto it = e.browser.card_at.find(arg.substr(5));
        if (it == e.browser.card_at.end()) return "no card " + arg.substr(5);
        x = it->second.first, y = it->second.second;
      } else if (std::sscanf(arg.c_str(), "%f %f", &x, &y) != 2) return "click export_path or click X Y";
      if (x <= 0 && y <= 0) return "the target is not on screen";
      e.input.push_move(x, y);
      e.input.push_button(0, true, x, y);
      e.input.push_button(0, false, x, y);
      sc.frames_left = 6;
      return "";
    }},
    {"search", [](script_call& call) -> std::string {   // search TEXT: the parameter panel's search box
      editor_state& e = call.e; script_state& sc = call.sc; const std::string& arg = call.arg;
      e.panel_search = arg;
      sc.frames_left = 2;
      return "";
    }},
    {"click_path", [](script_call& call) -> std::string {   // click_path KEY: into a path parameter's field (shown by the panel)
      editor_state& e = call.e; script_state& sc = call.sc; const std::string& arg = call.arg;
      const auto at = e.path_field_at.find(arg);
      if (at == e.path_field_at.end()) return "no field for " + arg + " on screen";
      e.input.push_move(at->second[0], at->second[1]);
      e.input.push_button(0, true, at->second[0], at->second[1]);
      e.input.push_button(0, false, at->second[0], at->second[1]);
      sc.frames_left = 6;
      return "";
    }},
    {"expect_texture_loads", [](script_call& call) -> std::string {   // the user texture files read so far (bark, leaf, opacity)
      editor_state& e = call.e; const std::string& arg = call.arg;
      if (e.cur().renderer.user_texture_loads != std::atoi(arg.c_str()))
        return "texture files read: " + std::to_string(e.cur().renderer.user_texture_loads);
      return "";
    }},
    {"remember_programs", [](script_call& call) -> std::string {   // the GL programs compiled so far
      script_state& sc = call.sc;
      sc.programs = gl_programs_compiled();
      return "";
    }},
    {"expect_new_programs", [](script_call& call) -> std::string {   // programs compiled since remember_programs
      script_state& sc = call.sc; const std::string& arg = call.arg;
      std::printf("sylva script: programs compiled %d (%d since remember_programs)\n", gl_programs_compiled(),
                  gl_programs_compiled() - sc.programs);
      if (gl_programs_compiled() - sc.programs != std::atoi(arg.c_str()))
        return std::to_string(gl_programs_compiled() - sc.programs) + " programs compiled since";
      return "";
    }},
    {"show_export", [](script_call& call) -> std::string {
      editor_state& e = call.e; script_state& sc = call.sc; const std::string& arg = call.arg;
      e.exporter.open = arg != "0";
      sc.frames_left = 3;
      return "";
    }},
    {"export_lods", [](script_call& call) -> std::string {   // export_lods 0|1: the Export dialog's "LOD chain" box
      call.e.exporter.lods = call.arg == "1";
      return "";
    }},
    {"export_path", [](script_call& call) -> std::string {   // sets the Export dialog's path as if typed in full
      editor_state& e = call.e; const std::string& arg = call.arg;
      e.exporter.path = arg;
      return "";
    }},
    {"export_as", [](script_call& call) -> std::string {   // as File > Export as... with PATH chosen (and any replace confirmed)
      editor_state& e = call.e; script_state& sc = call.sc; const std::string& arg = call.arg;
      e.exporter.path = arg;
      e.exporter.open = true;
      e.exporter.export_now = true;
      e.exporter.failure.clear();
      sc.frames_left = 2;
      return "";
    }},
    {"expect_file", [](script_call& call) -> std::string {   // waits until the file exists
      const std::string& arg = call.arg; const double waited = call.waited; bool& done = call.done;
      std::error_code ec;
      done = fs::exists(arg, ec) && fs::file_size(arg, ec) > 0;
      if (!done && waited > 180) return "no file " + arg;
      return "";
    }},
    {"expect_export_path", [](script_call& call) -> std::string {
      editor_state& e = call.e; const std::string& arg = call.arg;
      if (e.exporter.path != arg) return "the export path is \"" + e.exporter.path + "\"";
      return "";
    }},
    {"expect_window", [](script_call& call) -> std::string {   // expect_window shortcuts|library 0|1
      editor_state& e = call.e; const std::string& arg = call.arg;
      const std::string which = arg.substr(0, arg.find(' '));
      const bool want = arg.substr(arg.find(' ') + 1) == "1";
      const bool open = which == "shortcuts" ? e.show_shortcuts : which == "library" ? e.browser.open
                        : which == "export"  ? e.exporter.open : which == "messages" ? e.show_log : !want;
      if (open != want) return which + (open ? " is open" : " is not open");
      return "";
    }},
    {"expect_search_matches", [](script_call& call) -> std::string {   // the panel's search matches N parameters in all tabs
      editor_state& e = call.e; const std::string& arg = call.arg;
      if (e.search_matches != std::atoi(arg.c_str())) return "the search matches " + std::to_string(e.search_matches);
      return "";
    }},
    {"generator", [](script_call& call) -> std::string {   // generator NAME: the panel's Generator selector
      editor_state& e = call.e; script_state& sc = call.sc; const std::string& arg = call.arg;
      const int g = generator_index(arg);
      if (g < 0) return "no generator " + arg;
      switch_generator(e, g);
      sc.frames_left = 2;
      return "";
    }},
    {"remember_camera", [](script_call& call) -> std::string {
      editor_state& e = call.e; script_state& sc = call.sc;
      sc.camera = e.camera;
      return "";
    }},
    {"expect_camera", [](script_call& call) -> std::string {   // expect_camera kept|moved: against remember_camera
      editor_state& e = call.e; script_state& sc = call.sc; const std::string& arg = call.arg;
      const orbit_camera& c = e.camera;
      const bool kept = c.target == sc.camera.target && c.distance == sc.camera.distance && c.yaw == sc.camera.yaw &&
                        c.pitch == sc.camera.pitch;
      if (kept != (arg == "kept")) return kept ? "the camera did not move" : "the camera moved";
      return "";
    }},
    {"expect_popup", [](script_call& call) -> std::string {   // expect_popup 0|1: a menu, popup or dialog is open
      const std::string& arg = call.arg;
      const bool open = ImGui::IsPopupOpen("", ImGuiPopupFlags_AnyPopupId);
      if (open != (arg == "1")) return open ? "a popup is open" : "no popup is open";
      return "";
    }},
    {"expect_message", [](script_call& call) -> std::string {   // the status bar's text contains ARG ("" for an empty status)
      editor_state& e = call.e; const std::string& arg = call.arg;
      if (arg.empty() ? !e.message.empty() : e.message.find(arg) == std::string::npos) return "the status reads \"" + e.message + "\"";
      return "";
    }},
    {"step", [](script_call& call) -> std::string {
      editor_state& e = call.e; script_state& sc = call.sc; const std::string& arg = call.arg;
      e.step = std::atoi(arg.c_str());
      sc.frames_left = 2;
      return "";
    }},
    {"expect_step", [](script_call& call) -> std::string {
      editor_state& e = call.e; const std::string& arg = call.arg;
      if (e.step != std::atoi(arg.c_str())) return "the step is " + std::to_string(e.step);
      return "";
    }},
    {"answer", [](script_call& call) -> std::string {
      editor_state& e = call.e; script_state& sc = call.sc; const std::string& arg = call.arg;
      e.script_answer = arg;
      sc.frames_left = 2;
      return "";
    }},
    {"expect_prompt", [](script_call& call) -> std::string {
      const std::string& arg = call.arg; const double waited = call.waited; bool& done = call.done;
      done = call.shown_prompt(arg);
      if (!done && waited > 30) return "the dialog did not appear";
      return "";
    }},
    {"expect_no_prompt", [](script_call& call) -> std::string {
      editor_state& e = call.e;
      if (!e.prompts_shown.empty()) return "a dialog is open: " + e.prompts_shown.front();
      return "";
    }},
    {"expect_modified", [](script_call& call) -> std::string {
      editor_state& e = call.e; const std::string& arg = call.arg;
      if (modified(e) != (arg == "1")) return modified(e) ? "the document is modified" : "the document is not modified";
      return "";
    }},
    {"expect_state", [](script_call& call) -> std::string {
      editor_state& e = call.e; const std::string& arg = call.arg;
      static const char* names[] = {"idle", "growing", "asking", "done", "cancelled", "failed"};
      if (arg != names[int(e.cur().growth)]) return std::string("the state is ") + names[int(e.cur().growth)];
      return "";
    }},
    {"expect_param", [](script_call& call) -> std::string {
      editor_state& e = call.e; const std::string& arg = call.arg;
      preset copy = e.cur().doc;
      if (std::string err = set_preset_param(copy, arg); !err.empty()) return err;
      if (!(copy == e.cur().doc)) return "the parameter differs";
      return "";
    }},
    {"wait_progress", [](script_call& call) -> std::string {
      editor_state& e = call.e; const double waited = call.waited; bool& done = call.done;
      done = long_growth(e) && e.cur().worker->busy;
      if (!done && waited > 30) return "no progress bar";
      return "";
    }},
    {"remember", [](script_call& call) -> std::string {
      editor_state& e = call.e; script_state& sc = call.sc;
      sc.remembered_hold = e.cur().shown;
      sc.remembered = e.cur().shown ? e.cur().shown->skeleton.get() : nullptr;
      return "";
    }},
    {"expect_same_tree", same_or_new_tree},
    {"expect_new_tree", same_or_new_tree},
    {"ab_duplicate", [](script_call& call) -> std::string {
      editor_state& e = call.e; script_state& sc = call.sc;
      handle_ab(e, ab_action::duplicate);
      if (!e.ab.has_b) return "no slot B: " + e.message;
      sc.frames_left = 2;
      return "";
    }},
    {"ab_drop", [](script_call& call) -> std::string {
      editor_state& e = call.e; script_state& sc = call.sc;
      handle_ab(e, ab_action::drop);
      sc.frames_left = 2;
      return "";
    }},
    {"expect_has_b", [](script_call& call) -> std::string {
      editor_state& e = call.e; const std::string& arg = call.arg;
      if (e.ab.has_b != (arg == "1")) return e.ab.has_b ? "slot B is there" : "there is no slot B";
      return "";
    }},
    {"ab_select", [](script_call& call) -> std::string {
      editor_state& e = call.e; script_state& sc = call.sc; const std::string& arg = call.arg;
      handle_ab(e, arg == "b" ? ab_action::select_b : ab_action::select_a);
      sc.frames_left = 2;
      return "";
    }},
    {"ab_mode", [](script_call& call) -> std::string {
      editor_state& e = call.e; const std::string& arg = call.arg;
      e.ab.mode = arg == "split" ? ab_mode::split : arg == "side" ? ab_mode::side_by_side : ab_mode::off;
      return "";
    }},
    {"ab_divider", [](script_call& call) -> std::string {
      editor_state& e = call.e; const std::string& arg = call.arg;
      e.ab.divider = std::clamp(float(std::atof(arg.c_str())), 0.0f, 1.0f);
      return "";
    }},
    {"ab_wait", [](script_call& call) -> std::string {   // until slot B's tree (in whichever slot is not selected) matches its document
      editor_state& e = call.e; const double waited = call.waited; const bool growing = call.growing; bool& done = call.done;
      const editor_slot& other = e.ab.other();
      done = e.ab.has_b && other.shown && other.shown->spec == other.doc.spec && !growing && e.cur().shown;
      if (!done && waited > 120) return "the other slot's tree did not arrive";
      return "";
    }},
    {"frame_median", [](script_call& call) -> std::string {   // prints the median of N frame times (the A/B figure)
      editor_state& e = call.e; script_state& sc = call.sc; const std::string& arg = call.arg; bool& done = call.done;
      sc.frame_times.push_back(clock::now());
      const size_t n = size_t(std::max(1, std::atoi(arg.c_str())));
      done = sc.frame_times.size() > n;
      if (done) {
        std::vector<double> ms;
        for (size_t i = 1; i < sc.frame_times.size(); ++i)
          ms.push_back(std::chrono::duration<double, std::milli>(sc.frame_times[i] - sc.frame_times[i - 1]).count());
        const double worst = *std::max_element(ms.begin(), ms.end());   // the impostor atlas's hitch
        std::nth_element(ms.begin(), ms.begin() + ms.size() / 2, ms.end());
        std::printf("sylva script: frame median %.2f ms over %zu frames (A/B %s)\n", ms[ms.size() / 2], ms.size(),
                    ab_showing(e.ab) ? ab_mode_label(e.ab.mode) : "off");
        std::printf("sylva script: frame max %.2f ms\n", worst);
        std::fflush(stdout);
        sc.frame_times.clear();
      }
      return "";
    }},
    {"orbit", [](script_call& call) -> std::string {   // orbit N: a left drag across the 3D view, one move a frame for N frames
      editor_state& e = call.e; script_state& sc = call.sc; const std::string& arg = call.arg; bool& done = call.done;
      const int n = std::max(1, std::atoi(arg.c_str()));
      int w = 0, h = 0;
      glfwGetWindowSize(e.window, &w, &h);
      const float x0 = panel_width() + 0.3f * (float(w) - panel_width()), y0 = 0.5f * float(h);
      const clock::time_point now = clock::now();
      if (sc.orbit_step == 0) {
        e.input.push_move(x0, y0);
        e.input.push_button(0, true, x0, y0);
        sc.frame_times.clear();
        sc.orbit_cheap = e.cheap_frames;
      } else if (sc.orbit_step <= n + 1) {
        if (sc.orbit_step > 1) sc.frame_times.push_back(now);   // from the first frame that drags
        e.input.push_move(x0 + 6.0f * float(sc.orbit_step), y0);
      }
      done = sc.orbit_step > n + 1;
      ++sc.orbit_step;
      if (done) {
        e.input.push_button(0, false, x0 + 6.0f * float(n + 1), y0);
        std::vector<double> ms;
        for (size_t i = 1; i < sc.frame_times.size(); ++i)
          ms.push_back(std::chrono::duration<double, std::milli>(sc.frame_times[i] - sc.frame_times[i - 1]).count());
        std::nth_element(ms.begin(), ms.begin() + ms.size() / 2, ms.end());
        std::printf("sylva script: orbit: frame median %.1f ms over %zu frames, %llu drawn cheaper\n", ms.empty() ? 0.0 : ms[ms.size() / 2],
                    ms.size(), (unsigned long long)(e.cheap_frames - sc.orbit_cheap));
        sc.orbit_step = 0;
        sc.frame_times.clear();
        sc.frames_left = 6;
      }
      return "";
    }},
    {"full_quality", [](script_call& call) -> std::string {   // full_quality 0|1: every frame drawn in full (a baseline to measure against)
      editor_state& e = call.e; const std::string& arg = call.arg;
      e.full_quality = arg == "1";
      return "";
    }},
    {"expect_kept_frames_over", [](script_call& call) -> std::string {   // expect_kept_frames_over N: more than N frames showed the kept picture
      editor_state& e = call.e; const std::string& arg = call.arg;
      if (e.kept_frames <= uint64_t(std::atoll(arg.c_str()))) return std::to_string(e.kept_frames) + " frames showed the kept picture";
      return "";
    }},
    {"expect_cheap_frames", [](script_call& call) -> std::string {   // expect_cheap_frames N: frames drawn cheaper so far
      editor_state& e = call.e; const std::string& arg = call.arg;
      if (e.cheap_frames != uint64_t(std::atoll(arg.c_str()))) return std::to_string(e.cheap_frames) + " frames drawn cheaper";
      return "";
    }},
    {"wait_quiet", [](script_call& call) -> std::string {   // until nothing keeps the editor drawing (drawing_reason)
      editor_state& e = call.e; const double waited = call.waited; bool& done = call.done;
      done = drawing_reason(e).empty();
      if (!done && waited > 300) return "still drawing for " + drawing_reason(e) + " after 300 s";
      return "";
    }},
    {"idle", [](script_call& call) -> std::string {   // idle S [MAX]: the editor left alone; its CPU use measured
      editor_state& e = call.e; script_state& sc = call.sc; const std::string& arg = call.arg; bool& done = call.done;
      const double span = std::atof(arg.c_str());
      if (!(span > 0)) return "idle needs seconds > 0";
      if (!sc.idle_started && !sc.idle_pending) {   // (idle_mark_start)
        sc.idle_pending = true;
        sc.idle_span = span;
        done = false;   // measured from the end of this frame
        return "";
      }
      if (sc.idling()) return done = false, "";
      // This frame ends the wait and is not counted; the CPU it used up to here is (building the UI).
      const double cpu = process_cpu_seconds() - sc.idle_cpu, idled = seconds_since(sc.idle_from), share = 100.0 * cpu / idled;
      std::printf("sylva script: idle %.1f s: CPU %.3f s, %.1f %% of a core, %llu frames drawn%s%s\n", idled, cpu, share,
                  (unsigned long long)(e.frames_drawn - 1 - sc.idle_frames), drawing_reason(e).empty() ? "" : "; drawing for ",
                  drawing_reason(e).c_str());
      sc.idle_started = false;
      if (arg.find(' ') != std::string::npos && share > std::atof(arg.substr(arg.find(' ') + 1).c_str()))
        return "the idle editor used " + std::to_string(share) + " % of a core";
      return "";
    }},
    {"budget", [](script_call& call) -> std::string {
      editor_state& e = call.e; const std::string& arg = call.arg;
      e.cur().worker->node_budget = std::atoll(arg.c_str());
      return "";
    }},
    {"shot", [](script_call& call) -> std::string {
      editor_state& e = call.e; script_state& sc = call.sc; const std::string& arg = call.arg;
      e.script_shot = arg;
      sc.frames_left = 2;   // the UI is built before the script runs: the shot shows the next frame
      return "";
    }},
    {"frames", [](script_call& call) -> std::string {
      script_state& sc = call.sc; const std::string& arg = call.arg;
      if (sc.frames_left < 0) sc.frames_left = std::atoi(arg.c_str());
      return "";
    }},
    {"open", [](script_call& call) -> std::string {
      editor_state& e = call.e; script_state& sc = call.sc; const std::string& arg = call.arg;
      request(e, editor_state::then::open, arg);
      sc.frames_left = 2;
      return "";
    }},
    {"quit", [](script_call& call) -> std::string {
      editor_state& e = call.e; script_state& sc = call.sc;
      request(e, editor_state::then::quit);
      sc.frames_left = 2;
      return "";
    }},
};

}  // namespace

bool script_call::shown_prompt(const std::string& title) const {
  return std::find(e.prompts_shown.begin(), e.prompts_shown.end(), title) != e.prompts_shown.end();
}

script_handler find_script_command(const std::string& name) {
  for (const script_command& c : script_commands)
    if (name == c.name) return c.run;
  return nullptr;
}

}  // namespace sylva::ed
