// The editor driven from a script, for its end-to-end tests (not used by people).
#pragma once

#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "app/editor/editor_state.h"

namespace sylva::ed {

// SYLVA_SCRIPT=FILE drives the real window from a script, one command per line, for the editor's
// end-to-end test (tests/app/editor_test.cpp). Commands that wait give up after a timeout and fail.
//   wait_tree                  until no growth is in progress and a tree is shown
//   set KEY=VALUE              an edit, as the panel would make it (set_preset_param)
//   key [ctrl+][shift+]NAME    a press and release queued between two frames (NAME: a-z, escape, f12, ...)
//   taps N [ctrl+]NAME         N presses and releases queued at once
//   expect_recovery 0|1        whether the autosaved recovery file exists and holds the current document (waits)
//   answer LABEL               press a button of the open dialog
//   expect_prompt TITLE / expect_no_prompt
//   expect_modified 0|1 / expect_state growing|done|cancelled|failed / expect_param KEY=VALUE
//   wait_progress              until the progress bar with Cancel shows
//   remember / expect_same_tree / expect_new_tree
//   budget N / shot PATH / frames N / open PATH (as the library does) / quit (as Ctrl+Q)
//   ab_duplicate / ab_select a|b / ab_mode off|side|split / ab_divider F / ab_wait (the other slot's tree)
//   expect_other_state STATE   until the unselected A/B slot's growth state is STATE (as expect_state)
//   expect_recovery_b 0|1      the same for slot B's recovery file
//   wait_growing S             until the growth in progress has run S seconds (fails if it ends first)
//   frame_median N             prints the median (and the longest) time of the next N frames
//   hold [ctrl+]NAME N         a press, N system repeats (a held key) and a release, queued at once
//   type TEXT                  each character's press, character and release, all queued at once
//   click export_path | X Y    a move, a press and a release queued at once (a quick click on a slow frame)
//   show_export 0|1 / export_path P / expect_export_path P   the Export dialog
//   export_lods 0|1                                    its "LOD chain" box (as the CLI's --lods)
//   export_as P / expect_file P   Export as... with P chosen, which writes it; waits for the file
//   expect_window shortcuts|library|export|messages 0|1 / expect_message TEXT (contained; empty: no message)
//   expect_popup 0|1           whether a menu, popup or dialog is open
//   step N / expect_step N     the timeline's step
//   ab_drop / expect_has_b 0|1 Drop B (asks when B has edits) / whether slot B exists
//   search TEXT / click_path KEY   the panel's search box / a click into a path parameter's field
//   generator NAME             the Generator selector (a name of `sylva params`: lsystem, ...)
//   remember_camera / expect_camera kept|moved   the view against the one remembered
//   expect_search_matches N    the search matches N parameters and #define constants over all tabs
//   expect_texture_loads N     the user texture files the renderer has read so far
//   remember_programs / expect_new_programs N   GL programs compiled since (printed with the total)
//   orbit N                    a left drag across the 3D view, one move a frame for N frames; prints
//                              the frames' median and how many were drawn cheaper (view_quality.h)
//   expect_cheap_frames N      the frames drawn cheaper so far
//   expect_kept_frames_over N  more than N frames showed the last picture again (nothing in it changed)
//   full_quality 0|1           every frame drawn in full: the baseline for orbit and frame_median
//   wait_quiet                 until nothing keeps the editor drawing (no growth, LOD build, wind ...)
//   idle S [MAX]               touches nothing for S seconds, so the editor may idle; prints the CPU
//                              time the process used (every thread) as a share of one core and the
//                              frames drawn meanwhile; with MAX, fails above MAX % of a core
// At the end of the script the editor closes (exit 0); a failed expectation exits with 3.
struct script_state {
  std::vector<std::string> lines;
  size_t next = 0;
  std::chrono::steady_clock::time_point started_line = std::chrono::steady_clock::now();
  int frames_left = -1;
  int programs = 0;   // remember_programs
  orbit_camera camera;   // remember_camera
  int orbit_step = 0;    // orbit: the moves made so far
  uint64_t orbit_cheap = 0;
  const tree_skeleton* remembered = nullptr;
  std::shared_ptr<const grow_result> remembered_hold;   // keeps the remembered tree alive
  bool failed = false, finished = false;
  std::vector<std::chrono::steady_clock::time_point> frame_times;   // frame_median: one per frame
  // idle: asked for (it starts once the frame that asked is drawn), started; its span, its start and
  // end, and the CPU seconds and frames drawn at its start.
  bool idle_pending = false, idle_started = false;
  double idle_span = 0;
  std::chrono::steady_clock::time_point idle_from, idle_until;
  double idle_cpu = 0;
  uint64_t idle_frames = 0;
  // The script touches nothing now: the frame loop may wait for events (editor.cpp).
  bool idling() const { return idle_pending || (idle_started && std::chrono::steady_clock::now() < idle_until); }
};

// Starts an idle the script asked for in this frame, once the frame is drawn (editor.cpp): the
// frame's own drawing is no part of the quiet it measures.
void idle_mark_start(script_state& sc, uint64_t frames_drawn);

// CPU seconds the process has used so far, every thread (getrusage).
double process_cpu_seconds();

// Reads the script at `path` into `sc`; false with `error` set when it cannot be read.
bool load_script(const std::string& path, script_state& sc, std::string& error);
// Runs the script's current command; returns false once the script is over.
bool run_script(editor_state& e, script_state& sc);

// One script line's call to its command's handler (app/editor/editor_script_commands.cpp).
struct script_call {
  editor_state& e;
  script_state& sc;
  const std::string &cmd, &arg;   // the line's first word, and the rest after one space
  double waited;                  // seconds this line has been running
  bool growing;                   // the selected slot's growth is in progress
  bool done = true;               // false: the command waits, and runs again next frame
  // Whether a dialog titled `title` was shown this frame.
  bool shown_prompt(const std::string& title) const;
};
// A command's handler: "" when it ran or waits (call.done false), else why it failed.
using script_handler = std::string (*)(script_call& call);
// The handler of the command `name`, or null when there is none.
script_handler find_script_command(const std::string& name);

}  // namespace sylva::ed
