#include "app/editor/editor_script.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include <sys/resource.h>

#include <GLFW/glfw3.h>
#include <imgui.h>

namespace sylva::ed {

namespace {

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

}  // namespace

void idle_mark_start(script_state& sc, uint64_t frames_drawn) {
  if (!sc.idle_pending) return;
  sc.idle_pending = false;
  sc.idle_started = true;
  sc.idle_from = std::chrono::steady_clock::now();
  sc.idle_until = sc.idle_from + std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(sc.idle_span));
  sc.idle_cpu = process_cpu_seconds();
  sc.idle_frames = frames_drawn;
}

double process_cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

bool load_script(const std::string& path, script_state& sc, std::string& error) {
  std::string text;
  if (error = read_file(path, text); !error.empty()) return false;
  size_t a = 0;
  while (a <= text.size()) {
    size_t b = text.find('\n', a);
    if (b == std::string::npos) b = text.size();
    sc.lines.push_back(text.substr(a, b - a));
    a = b + 1;
  }
  return true;
}

bool run_script(editor_state& e, script_state& sc) {
  using clock = std::chrono::steady_clock;
  auto fail = [&](const std::string& why) {
    std::fprintf(stderr, "sylva script: FAIL at line %zu (%s): %s\n", sc.next + 1, sc.lines[sc.next].c_str(), why.c_str());
    sc.failed = true;
    return false;
  };
  while (sc.next < sc.lines.size()) {
    const std::string& line = sc.lines[sc.next];
    const size_t sp = line.find(' ');
    const std::string cmd = line.substr(0, sp), arg = sp == std::string::npos ? "" : line.substr(sp + 1);
    const double waited = std::chrono::duration<double>(clock::now() - sc.started_line).count();
    const bool growing = e.cur().growth == slot_growth::growing;
    bool done = true;   // false: wait and try again next frame
    auto shown_prompt = [&](const std::string& t) {
      return std::find(e.prompts_shown.begin(), e.prompts_shown.end(), t) != e.prompts_shown.end();
    };
    if (line.empty() || line[0] == '#') {
    } else if (cmd == "wait_tree") {
      done = !growing && e.cur().shown;
      if (!done && waited > 120) return fail("no tree after 120 s");
    } else if (cmd == "set") {
      if (std::string err = set_preset_param(e.cur().doc, arg); !err.empty()) return fail(err);
      sc.frames_left = 2;   // posted on the next frame
    } else if (cmd == "set_all") {   // several assignments in one frame: one request
      preset edited = e.cur().doc;
      for (const std::string& a : words(arg))
        if (std::string err = set_preset_param(edited, a); !err.empty()) return fail(err);
      e.cur().doc = edited;
      sc.frames_left = 2;
    } else if (cmd == "expect_title") {
      if (e.window_title != arg) return fail("the title is \"" + e.window_title + "\"");
    } else if (cmd == "status") {
      set_status(e, arg);
      sc.frames_left = 2;
    } else if (cmd == "expect_status_fits") {   // the status bar's text ends inside the window; "cut": a piece was cut
      int w = 0, h = 0;
      glfwGetWindowSize(e.window, &w, &h);
      if (e.status_right > float(w)) return fail("the status runs to x " + std::to_string(e.status_right) + " of " + std::to_string(w));
      if (arg == "cut" && e.status_cut.empty()) return fail("no piece of the status was cut");
      if (arg == "cut") std::printf("sylva script: status cut, whole in its tooltip: %s\n", e.status_cut.c_str());
    } else if (cmd == "expect_marker") {   // expect_marker STEP: its marker sits at STEP / the steps grown
      const int k = std::atoi(arg.c_str());
      const int grown = e.cur().shown && e.cur().shown->skeleton ? e.cur().shown->skeleton->steps : 0;
      auto it = std::find_if(e.keys.drawn.begin(), e.keys.drawn.end(), [&](const auto& m) { return m.first == k; });
      if (it == e.keys.drawn.end() || grown <= 0) return fail("no marker at step " + arg);
      const float want = float(std::min(k, grown)) / float(grown);
      std::printf("sylva script: marker at step %d drawn at %.3f of the timeline (%d steps grown)\n", k, it->second, grown);
      if (std::abs(it->second - want) > 0.01f) return fail("the marker sits at " + std::to_string(it->second) + ", not " + std::to_string(want));
    } else if (cmd == "library_folders") {   // the library lists these folders (space separated) instead
      e.browser.folders = words(arg);
      e.browser.rescan = true;
    } else if (cmd == "wait_thumbnails") {   // until every card of the open library has its picture
      done = e.browser.open && e.browser.ready_s >= 0;
      if (!done && waited > 900) return fail("thumbnails still missing after 900 s");
      if (done)
        std::printf("sylva script: thumbnails: %zu cards, %d rendered, %d from the cache, %zu without a picture, all drawn %.1f s after the library opened\n",
                    e.browser.entries.size(), e.browser.rendered, e.browser.from_cache, e.browser.failed.size(), e.browser.ready_s);
    } else if (cmd == "expect_cards") {   // expect_cards NAME N: the library lists N cards named NAME
      const std::string name = arg.substr(0, arg.rfind(' '));
      const long n = std::count_if(e.browser.entries.begin(), e.browser.entries.end(), [&](const preset_entry& c) { return c.name == name; });
      if (n != std::atol(arg.substr(arg.rfind(' ') + 1).c_str())) return fail(std::to_string(n) + " cards named " + name);
    } else if (cmd == "menu_export_as") {   // File > Export as...: the file browser opens
      e.browse_export = true;
      sc.frames_left = 3;
    } else if (cmd == "file_path") {   // the open file browser's folder and name, as if typed
      e.files.folder = fs::path(arg).parent_path().string();
      e.files.name = fs::path(arg).filename().string();
      e.files.confirm_overwrite = false;
    } else if (cmd == "expect_export_asking") {   // the Export dialog asks before replacing its file
      std::error_code ec;
      const bool asking = fs::exists(e.exporter.path, ec) && e.exporter.confirm_replace == e.exporter.path;
      if (asking != (arg == "1")) return fail(asking ? "the dialog asks to replace" : "the dialog does not ask");
    } else if (cmd == "expect_file_size" || cmd == "wait_file_size_over") {   // PATH N; the second waits for it
      const std::string path = arg.substr(0, arg.rfind(' '));
      const auto n = std::uintmax_t(std::atoll(arg.substr(arg.rfind(' ') + 1).c_str()));
      std::error_code ec;
      const std::uintmax_t size = fs::exists(path, ec) ? fs::file_size(path, ec) : 0;
      if (cmd == "expect_file_size" && size != n) return fail(path + " holds " + std::to_string(size) + " bytes");
      done = size > n;
      if (cmd == "expect_file_size") done = true;
      else if (!done && waited > 180) return fail(path + " still holds " + std::to_string(size) + " bytes");
    } else if (cmd == "expect_ab_labels") {   // both A/B labels fit their parts; the selected one says so
      const std::string& sel = e.ab.labels_shown[e.ab.selected];
      std::printf("sylva script: A/B labels \"%s\" | \"%s\"\n", e.ab.labels_shown[0].c_str(), e.ab.labels_shown[1].c_str());
      if (!e.ab.labels_fit) return fail("an A/B label runs past its part of the view");
      if (sel.size() < 10 || sel.compare(sel.size() - 10, 10, "(selected)") != 0) return fail("the selected slot's label is \"" + sel + "\"");
    } else if (cmd == "expect_doc_name") {
      if (e.cur().doc.name != arg) return fail("the document is \"" + e.cur().doc.name + "\"");
    } else if (cmd == "expect_recovery" || cmd == "expect_recovery_b") {
      // "1": the file is there and holds the slot's current document (an autosave taken before the
      // last edit is not yet the work that a crash would leave); "0": the file is gone.
      std::error_code ec;
      const int slot = cmd == "expect_recovery" ? 0 : 1;
      const preset& now = e.ab.slots[e.ab.has_b ? slot : 0].doc;
      const bool there = fs::exists(recovery_path(e, slot), ec);
      done = arg == "1" ? there && e.autosaved_any[slot] && e.autosaved[slot] == now : !there;
      if (!done && waited > 20) return fail(arg == "1" ? "no recovery file" : "the recovery file stays");
    } else if (cmd == "wait_growing") {
      if (!growing) return fail("the growth ended before " + arg + " s");
      done = seconds_since(e.cur().posted_at) >= std::atof(arg.c_str());
    } else if (cmd == "expect_other_state") {
      static const char* names[] = {"idle", "growing", "asking", "done", "cancelled", "failed"};
      const int st = e.ab.has_b ? int(e.ab.other().growth) : 0;
      done = arg == names[std::clamp(st, 0, 5)];
      if (!done && waited > 60) return fail(std::string("the other slot's state is ") + names[std::clamp(st, 0, 5)]);
    } else if (cmd == "key" || cmd == "taps") {
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
      if (k == GLFW_KEY_UNKNOWN) return fail("unknown key");
      if (ctrl) e.input.push_key(GLFW_KEY_LEFT_CONTROL, GLFW_PRESS);
      if (shift) e.input.push_key(GLFW_KEY_LEFT_SHIFT, GLFW_PRESS);
      for (int i = 0; i < taps; ++i) {
        e.input.push_key(k, GLFW_PRESS);
        e.input.push_key(k, GLFW_RELEASE);
      }
      if (shift) e.input.push_key(GLFW_KEY_LEFT_SHIFT, GLFW_RELEASE);
      if (ctrl) e.input.push_key(GLFW_KEY_LEFT_CONTROL, GLFW_RELEASE);
      sc.frames_left = 2 * taps + 3;   // let the queued events drain before the next command
    } else if (cmd == "hold") {   // hold [ctrl+]NAME N: a press, N system repeats and a release, queued at once
      std::string name = arg.substr(0, arg.find(' '));
      const int repeats = std::atoi(arg.substr(std::min(arg.size(), arg.find(' ') + 1)).c_str());
      const bool ctrl = name.rfind("ctrl+", 0) == 0;
      if (ctrl) name = name.substr(5);
      const int k = glfw_key(name);
      if (k == GLFW_KEY_UNKNOWN) return fail("unknown key");
      if (ctrl) e.input.push_key(GLFW_KEY_LEFT_CONTROL, GLFW_PRESS);
      e.input.push_key(k, GLFW_PRESS);
      for (int i = 0; i < repeats; ++i) e.input.push_key(k, GLFW_REPEAT);
      e.input.push_key(k, GLFW_RELEASE);
      if (ctrl) e.input.push_key(GLFW_KEY_LEFT_CONTROL, GLFW_RELEASE);
      sc.frames_left = repeats + 6;
    } else if (cmd == "type") {   // type TEXT: every key press, character and release queued at once (a slow frame)
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
    } else if (cmd == "click") {   // click TARGET: a move onto it, a press and a release, queued at once
      float x = 0, y = 0;
      if (arg == "export_path") x = e.exporter.path_at[0], y = e.exporter.path_at[1];
      else if (arg == "export_button") x = e.exporter.export_at[0], y = e.exporter.export_at[1];
      else if (arg.rfind("card ", 0) == 0) {   // click card NAME: the library's card of that preset
        auto it = e.browser.card_at.find(arg.substr(5));
        if (it == e.browser.card_at.end()) return fail("no card " + arg.substr(5));
        x = it->second.first, y = it->second.second;
      } else if (std::sscanf(arg.c_str(), "%f %f", &x, &y) != 2) return fail("click export_path or click X Y");
      if (x <= 0 && y <= 0) return fail("the target is not on screen");
      e.input.push_move(x, y);
      e.input.push_button(0, true, x, y);
      e.input.push_button(0, false, x, y);
      sc.frames_left = 6;
    } else if (cmd == "search") {   // search TEXT: the parameter panel's search box
      e.panel_search = arg;
      sc.frames_left = 2;
    } else if (cmd == "click_path") {   // click_path KEY: into a path parameter's field (shown by the panel)
      const auto at = e.path_field_at.find(arg);
      if (at == e.path_field_at.end()) return fail("no field for " + arg + " on screen");
      e.input.push_move(at->second[0], at->second[1]);
      e.input.push_button(0, true, at->second[0], at->second[1]);
      e.input.push_button(0, false, at->second[0], at->second[1]);
      sc.frames_left = 6;
    } else if (cmd == "expect_texture_loads") {   // the user texture files read so far (bark, leaf, opacity)
      if (e.cur().renderer.user_texture_loads != std::atoi(arg.c_str()))
        return fail("texture files read: " + std::to_string(e.cur().renderer.user_texture_loads));
    } else if (cmd == "remember_programs") {   // the GL programs compiled so far
      sc.programs = gl_programs_compiled();
    } else if (cmd == "expect_new_programs") {   // programs compiled since remember_programs
      std::printf("sylva script: programs compiled %d (%d since remember_programs)\n", gl_programs_compiled(),
                  gl_programs_compiled() - sc.programs);
      if (gl_programs_compiled() - sc.programs != std::atoi(arg.c_str()))
        return fail(std::to_string(gl_programs_compiled() - sc.programs) + " programs compiled since");
    } else if (cmd == "show_export") {
      e.exporter.open = arg != "0";
      sc.frames_left = 3;
    } else if (cmd == "export_lods") {   // export_lods 0|1: the Export dialog's "LOD chain" box
      e.exporter.lods = arg == "1";
    } else if (cmd == "export_path") {   // sets the Export dialog's path as if typed in full
      e.exporter.path = arg;
    } else if (cmd == "export_as") {   // as File > Export as... with PATH chosen (and any replace confirmed)
      e.exporter.path = arg;
      e.exporter.open = true;
      e.exporter.export_now = true;
      e.exporter.failure.clear();
      sc.frames_left = 2;
    } else if (cmd == "expect_file") {   // waits until the file exists
      std::error_code ec;
      done = fs::exists(arg, ec) && fs::file_size(arg, ec) > 0;
      if (!done && waited > 180) return fail("no file " + arg);
    } else if (cmd == "expect_export_path") {
      if (e.exporter.path != arg) return fail("the export path is \"" + e.exporter.path + "\"");
    } else if (cmd == "expect_window") {   // expect_window shortcuts|library 0|1
      const std::string which = arg.substr(0, arg.find(' '));
      const bool want = arg.substr(arg.find(' ') + 1) == "1";
      const bool open = which == "shortcuts" ? e.show_shortcuts : which == "library" ? e.browser.open
                        : which == "export"  ? e.exporter.open : which == "messages" ? e.show_log : !want;
      if (open != want) return fail(which + (open ? " is open" : " is not open"));
    } else if (cmd == "expect_search_matches") {   // the panel's search matches N parameters in all tabs
      if (e.search_matches != std::atoi(arg.c_str())) return fail("the search matches " + std::to_string(e.search_matches));
    } else if (cmd == "generator") {   // generator NAME: the panel's Generator selector
      const int g = generator_index(arg);
      if (g < 0) return fail("no generator " + arg);
      switch_generator(e, g);
      sc.frames_left = 2;
    } else if (cmd == "remember_camera") {
      sc.camera = e.camera;
    } else if (cmd == "expect_camera") {   // expect_camera kept|moved: against remember_camera
      const orbit_camera& c = e.camera;
      const bool kept = c.target == sc.camera.target && c.distance == sc.camera.distance && c.yaw == sc.camera.yaw &&
                        c.pitch == sc.camera.pitch;
      if (kept != (arg == "kept")) return fail(kept ? "the camera did not move" : "the camera moved");
    } else if (cmd == "expect_popup") {   // expect_popup 0|1: a menu, popup or dialog is open
      const bool open = ImGui::IsPopupOpen("", ImGuiPopupFlags_AnyPopupId);
      if (open != (arg == "1")) return fail(open ? "a popup is open" : "no popup is open");
    } else if (cmd == "expect_message") {   // the status bar's text contains ARG ("" for an empty status)
      if (arg.empty() ? !e.message.empty() : e.message.find(arg) == std::string::npos) return fail("the status reads \"" + e.message + "\"");
    } else if (cmd == "step") {
      e.step = std::atoi(arg.c_str());
      sc.frames_left = 2;
    } else if (cmd == "expect_step") {
      if (e.step != std::atoi(arg.c_str())) return fail("the step is " + std::to_string(e.step));
    } else if (cmd == "answer") {
      e.script_answer = arg;
      sc.frames_left = 2;
    } else if (cmd == "expect_prompt") {
      done = shown_prompt(arg);
      if (!done && waited > 30) return fail("the dialog did not appear");
    } else if (cmd == "expect_no_prompt") {
      if (!e.prompts_shown.empty()) return fail("a dialog is open: " + e.prompts_shown.front());
    } else if (cmd == "expect_modified") {
      if (modified(e) != (arg == "1")) return fail(modified(e) ? "the document is modified" : "the document is not modified");
    } else if (cmd == "expect_state") {
      static const char* names[] = {"idle", "growing", "asking", "done", "cancelled", "failed"};
      if (arg != names[int(e.cur().growth)]) return fail(std::string("the state is ") + names[int(e.cur().growth)]);
    } else if (cmd == "expect_param") {
      preset copy = e.cur().doc;
      if (std::string err = set_preset_param(copy, arg); !err.empty()) return fail(err);
      if (!(copy == e.cur().doc)) return fail("the parameter differs");
    } else if (cmd == "wait_progress") {
      done = long_growth(e) && e.cur().worker->busy;
      if (!done && waited > 30) return fail("no progress bar");
    } else if (cmd == "remember") {
      sc.remembered_hold = e.cur().shown;
      sc.remembered = e.cur().shown ? e.cur().shown->skeleton.get() : nullptr;
    } else if (cmd == "expect_same_tree" || cmd == "expect_new_tree") {
      const bool same = e.cur().shown && e.cur().shown->skeleton.get() == sc.remembered;
      if (same != (cmd == "expect_same_tree")) return fail(same ? "the tree did not change" : "the tree changed");
    } else if (cmd == "ab_duplicate") {
      handle_ab(e, ab_action::duplicate);
      if (!e.ab.has_b) return fail("no slot B: " + e.message);
      sc.frames_left = 2;
    } else if (cmd == "ab_drop") {
      handle_ab(e, ab_action::drop);
      sc.frames_left = 2;
    } else if (cmd == "expect_has_b") {
      if (e.ab.has_b != (arg == "1")) return fail(e.ab.has_b ? "slot B is there" : "there is no slot B");
    } else if (cmd == "ab_select") {
      handle_ab(e, arg == "b" ? ab_action::select_b : ab_action::select_a);
      sc.frames_left = 2;
    } else if (cmd == "ab_mode") {
      e.ab.mode = arg == "split" ? ab_mode::split : arg == "side" ? ab_mode::side_by_side : ab_mode::off;
    } else if (cmd == "ab_divider") {
      e.ab.divider = std::clamp(float(std::atof(arg.c_str())), 0.0f, 1.0f);
    } else if (cmd == "ab_wait") {   // until slot B's tree (in whichever slot is not selected) matches its document
      const editor_slot& other = e.ab.other();
      done = e.ab.has_b && other.shown && other.shown->spec == other.doc.spec && !growing && e.cur().shown;
      if (!done && waited > 120) return fail("the other slot's tree did not arrive");
    } else if (cmd == "frame_median") {   // prints the median of N frame times (the A/B figure)
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
    } else if (cmd == "orbit") {   // orbit N: a left drag across the 3D view, one move a frame for N frames
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
    } else if (cmd == "full_quality") {   // full_quality 0|1: every frame drawn in full (a baseline to measure against)
      e.full_quality = arg == "1";
    } else if (cmd == "expect_kept_frames_over") {   // expect_kept_frames_over N: more than N frames showed the kept picture
      if (e.kept_frames <= uint64_t(std::atoll(arg.c_str()))) return fail(std::to_string(e.kept_frames) + " frames showed the kept picture");
    } else if (cmd == "expect_cheap_frames") {   // expect_cheap_frames N: frames drawn cheaper so far
      if (e.cheap_frames != uint64_t(std::atoll(arg.c_str()))) return fail(std::to_string(e.cheap_frames) + " frames drawn cheaper");
    } else if (cmd == "wait_quiet") {   // until nothing keeps the editor drawing (drawing_reason)
      done = drawing_reason(e).empty();
      if (!done && waited > 300) return fail("still drawing for " + drawing_reason(e) + " after 300 s");
    } else if (cmd == "idle") {   // idle S [MAX]: the editor left alone; its CPU use measured
      const double span = std::atof(arg.c_str());
      if (!(span > 0)) return fail("idle needs seconds > 0");
      if (!sc.idle_started && !sc.idle_pending) {   // measured from the end of this frame (idle_mark_start)
        sc.idle_pending = true;
        sc.idle_span = span;
        return true;
      }
      if (sc.idling()) return true;
      // This frame ends the wait and is not counted; the CPU it used up to here is (building the UI).
      const double cpu = process_cpu_seconds() - sc.idle_cpu, idled = seconds_since(sc.idle_from), share = 100.0 * cpu / idled;
      std::printf("sylva script: idle %.1f s: CPU %.3f s, %.1f %% of a core, %llu frames drawn%s%s\n", idled, cpu, share,
                  (unsigned long long)(e.frames_drawn - 1 - sc.idle_frames), drawing_reason(e).empty() ? "" : "; drawing for ",
                  drawing_reason(e).c_str());
      sc.idle_started = false;
      if (arg.find(' ') != std::string::npos && share > std::atof(arg.substr(arg.find(' ') + 1).c_str()))
        return fail("the idle editor used " + std::to_string(share) + " % of a core");
    } else if (cmd == "budget") {
      e.cur().worker->node_budget = std::atoll(arg.c_str());
    } else if (cmd == "shot") {
      e.script_shot = arg;
      sc.frames_left = 2;   // the UI is built before the script runs: the shot shows the next frame
    } else if (cmd == "frames") {
      if (sc.frames_left < 0) sc.frames_left = std::atoi(arg.c_str());
    } else if (cmd == "open") {
      request(e, editor_state::then::open, arg);
      sc.frames_left = 2;
    } else if (cmd == "quit") {
      request(e, editor_state::then::quit);
      sc.frames_left = 2;
    } else {
      return fail("unknown command");
    }
    if (!done) return true;
    static const auto script_start = clock::now();
    std::printf("sylva script: ok %s (%.1f s)\n", line.c_str(), std::chrono::duration<double>(clock::now() - script_start).count());
    std::fflush(stdout);
    ++sc.next;
    sc.started_line = clock::now();
    if (sc.frames_left > 0) return true;   // continue after that many frames
  }
  sc.finished = true;
  return false;
}

}  // namespace sylva::ed
