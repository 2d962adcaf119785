// The editor end to end: a real window under Xvfb driven by SYLVA_SCRIPT through an
// edit, undo and redo from key taps queued between frames, quit with changes (the prompt
// appears), an over-budget request (the prompt appears, the previous tree stays) and Cancel
// (Esc) during a long regrow; the autosaved recovery file comes and goes with the changes.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "app/editor/editor_files.h"
#include "editor_script_run.h"
#include "generators/tree_spec.h"
#include "render/io/mesh_bound.h"
#include "render/io/preset.h"
#include "tests/fixtures.h"

namespace {

using sylva_test::have_display;
using sylva_test::run_result;
using sylva_test::run_script;
using sylva_test::test_dir;

// The bush without its leaves (llvmpipe draws its frames fast), saved in the tests' folder as
// `file`; "" when it cannot be saved.
std::string leafless_bush(const std::string& file) {
  sylva::preset bush = sylva_test::shipped_preset("self_organizing_seed001_bush");
  bush.mesh.leaves_enabled = false;
  const std::string path = test_dir(file).string();
  return sylva::save_preset_file(bush, path).empty() ? path : "";
}

// Runs the script and expects it to pass (exit 0, no FAIL line); returns the run for more checks.
run_result run_passing(const std::string& name, const std::string& script, const std::string& preset) {
  run_result r = run_script(name, script, preset);
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(r.output.find("FAIL"), std::string::npos) << r.output;
  return r;
}

}  // namespace

TEST(EditorSession, EditUndoQuitPromptBudgetPromptAndCancel) {
  if (!have_display()) GTEST_SKIP() << "no DISPLAY";
  // The bush without its leaves: llvmpipe draws frames fast enough for a test that waits on many.
  sylva::preset bush;
  ASSERT_TRUE(sylva::load_preset_file(std::string(SYLVA_SOURCE_DIR) + "/presets/self_organizing_seed001_bush.json", bush).ok);
  bush.mesh.leaves_enabled = false;
  const std::string preset = test_dir("bush.json").string();
  ASSERT_EQ(sylva::save_preset_file(bush, preset), "");
  // The same bush with every resource sent up the main axes: a runaway growth, over the budget.
  bush.spec.params = [&] {
    auto p = std::get<sylva::self_organizing_params>(bush.spec.params);
    p.lambda = 1;
    return p;
  }();
  bush.name = "Runaway";
  const std::string runaway = test_dir("runaway.json").string();
  ASSERT_EQ(sylva::save_preset_file(bush, runaway), "");
  // Cancelling a running growth from the progress bar is not scripted here any more: the runaway
  // (λ = 1) now stops at the shadow grid's memory cap in under a second, too soon to cancel, and its
  // 600k-node tree makes llvmpipe frames take seconds. Worker tests cover cancellation.
  std::string script = R"(wait_tree
remember
set lambda=0.42
wait_tree
expect_new_tree
expect_modified 1
expect_recovery 1
key ctrl+z
wait_tree
expect_param lambda=0.46
expect_modified 0
expect_recovery 0
key ctrl+shift+z
wait_tree
expect_param lambda=0.42
set lambda=0.43
set lambda=0.44
taps 2 ctrl+z
expect_param lambda=0.42
quit
expect_prompt Unsaved changes
answer Cancel
frames 2
expect_no_prompt
remember
budget 100000
set lambda=1
expect_prompt Large tree
expect_same_tree
answer Keep the current tree
frames 2
expect_no_prompt
expect_param lambda=0.42
expect_same_tree
expect_state cancelled
budget 100000
open RUNAWAY
expect_prompt Unsaved changes
answer Discard
expect_prompt Large tree
expect_same_tree
answer Keep the current tree
frames 2
expect_param lambda=0.42
expect_modified 1
quit
expect_prompt Unsaved changes
answer Discard
not reached: Discard quits
)";
  script.replace(script.find("RUNAWAY"), 7, runaway);
  run_result r = run_script("session", script, preset);
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("ok answer Discard"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("the editor closed before line 49"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("FAIL"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(test_dir("session") / "home" / ".recovery.json"));
}

// Cancel (Esc) while a long growth runs: the previous tree and document stay, the status says
// cancelled. The fixture grows for about a minute without reaching a cap (many attraction points,
// short segments, a small kill distance), so the cancel always lands while it runs.
TEST(EditorSession, CancellingALongGrowthKeepsThePreviousTree) {
  if (!have_display()) GTEST_SKIP() << "no DISPLAY";
  sylva::preset cube;
  ASSERT_TRUE(sylva::load_preset_file(std::string(SYLVA_SOURCE_DIR) + "/presets/space_colonization_seed_cube.json", cube).ok);
  cube.mesh.leaves_enabled = false;
  const std::string start = test_dir("cube.json").string();
  ASSERT_EQ(sylva::save_preset_file(cube, start), "");
  auto p = std::get<sylva::space_colonization_params>(cube.spec.params);
  p.points = 400000;
  p.segment_length = 0.02f;
  p.influence_radius = 1.0f;
  p.kill_distance = 0.1f;
  p.max_branches = 10000000;
  p.steps = 20000;
  p.node_cap = 2000000;
  cube.spec.params = p;
  cube.mesh.mesh_budget = 32000;   // its estimated mesh fits: no question before it grows
  cube.name = "Long growth";
  const std::string long_growth = test_dir("long.json").string();
  ASSERT_EQ(sylva::save_preset_file(cube, long_growth), "");
  std::string script = R"(wait_tree
remember
budget 100000000
open LONG
wait_progress
wait_growing 2
key escape
expect_state cancelled
expect_same_tree
expect_param segment_length=0.5
expect_param points=10000
expect_modified 0
)";
  script.replace(script.find("LONG"), 4, long_growth);
  run_result r = run_passing("cancel", script, start);
  EXPECT_NE(r.output.find("ok expect_state cancelled"), std::string::npos) << r.output;
}

// A mesh over the mesh budget is not made: the prompt keeps the tree on screen, and its answers
// keep it or apply the radial segment count that fits.
TEST(EditorSession, MeshOverItsBudgetAsksAndKeepsTheTree) {
  if (!have_display()) GTEST_SKIP() << "no DISPLAY";
  sylva::preset bush;
  ASSERT_TRUE(sylva::load_preset_file(std::string(SYLVA_SOURCE_DIR) + "/presets/self_organizing_seed001_bush.json", bush).ok);
  bush.mesh.leaves_enabled = false;
  const sylva::tree_skeleton t = sylva::grow(bush.spec, sylva::grow_options{});
  const double at_8 = sylva::with_writer(sylva::mesh_bound(t, bush.mesh), nullptr).total_bytes();
  bush.mesh.mesh_budget = int(at_8 * 1.3 / 1e6) + 1;
  sylva::mesh_params at_32 = bush.mesh;
  at_32.radial_segments = 32;
  const sylva::mesh_estimate e32 = sylva::with_writer(sylva::mesh_bound(t, at_32), nullptr);
  ASSERT_GT(e32.total_bytes(), sylva::mesh_budget_bytes(at_32));
  const int fit = sylva::mesh_fit_segments(e32, at_32);
  ASSERT_GE(fit, 8);
  const std::string preset = test_dir("bush_budget.json").string();
  ASSERT_EQ(sylva::save_preset_file(bush, preset), "");
  const std::string n = std::to_string(fit);
  const std::string script = "wait_tree\nremember\nset radial_segments=32\nexpect_prompt Large mesh\nexpect_same_tree\n"
                             "answer Keep the current tree\nframes 2\nexpect_no_prompt\nexpect_param radial_segments=8\n"
                             "expect_same_tree\nexpect_state cancelled\nset radial_segments=32\nexpect_prompt Large mesh\n"
                             "answer Use " + n + " radial segments\nframes 2\nwait_tree\nexpect_no_prompt\n"
                             "expect_param radial_segments=" + n + "\nexpect_state done\n";
  run_result r = run_passing("mesh_budget", script, preset);
  EXPECT_NE(r.output.find("ok expect_param radial_segments=" + n), std::string::npos) << r.output;
}

TEST(EditorSession, RecoveryFileIsOfferedOnTheNextStart) {
  if (!have_display()) GTEST_SKIP() << "no DISPLAY";
  const std::string preset = std::string(SYLVA_SOURCE_DIR) + "/presets/lsystem_honda_a.json";
  namespace fs = std::filesystem;
  const fs::path home = test_dir("recovery") / "home";
  // First session: edit, wait for the autosave, then "crash" (the script ends without asking).
  run_result first = run_script("recovery", "wait_tree\nset derivations=8\nwait_tree\nexpect_recovery 1\n", preset);
  ASSERT_EQ(first.code, 0) << first.output;
  ASSERT_TRUE(fs::exists(home / ".recovery.json"));
  const std::string script = "expect_prompt Restore unsaved work?\nanswer Restore\nframes 2\nwait_tree\n"
                             "expect_param derivations=8\nexpect_modified 1\n";
  // run_script clears its folder: keep the recovery file across the second start.
  const fs::path keep = test_dir("recovery_keep.json");
  fs::copy_file(home / ".recovery.json", keep, fs::copy_options::overwrite_existing);
  const std::string cmd_home = home.string();
  fs::remove_all(home.parent_path());
  fs::create_directories(home);
  fs::copy_file(keep, home / ".recovery.json");
  std::ofstream(home.parent_path() / "script.txt") << script;
  const std::string cmd = "SYLVA_HOME='" + cmd_home + "' SYLVA_SCRIPT='" + (home.parent_path() / "script.txt").string() +
                          "' SYLVA_WINDOW=800x500 '" + std::string(SYLVA_BINARY) + "' '" + preset + "' 2>&1";
  EXPECT_EQ(std::system(cmd.c_str()), 0);
}

// An autosave that cannot be offered back (here a half-written file) is never dropped: the editor
// says why and where it is kept, and moves it where the next autosave cannot overwrite it.
TEST(EditorSession, AnUnusableRecoveryFileIsReportedAndKept) {
  if (!have_display()) GTEST_SKIP() << "no DISPLAY";
  namespace fs = std::filesystem;
  const std::string preset = std::string(SYLVA_SOURCE_DIR) + "/presets/lsystem_honda_a.json";
  const fs::path dir = test_dir("unrestored"), home = dir / "home";
  fs::remove_all(dir);
  fs::create_directories(home);
  const std::string broken = R"({"sylva_preset": 1, "generator": "lsystem", "params": {"derivations": )";
  std::ofstream(home / ".recovery.json") << broken;
  std::ofstream(dir / "script.txt") << "expect_prompt Unsaved work not restored\nexpect_message is kept as\n"
                                       "answer OK\nframes 2\nwait_tree\nset derivations=7\nwait_tree\n"
                                       "expect_recovery 1\n";
  const std::string cmd = "SYLVA_HOME='" + home.string() + "' SYLVA_SCRIPT='" + (dir / "script.txt").string() +
                          "' SYLVA_WINDOW=800x500 '" + std::string(SYLVA_BINARY) + "' '" + preset + "' > '" +
                          (dir / "log.txt").string() + "' 2>&1";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << std::ifstream(dir / "log.txt").rdbuf();
  std::vector<fs::path> kept;
  for (const auto& f : fs::directory_iterator(home))
    if (f.path().filename().string().rfind("unrestored-", 0) == 0 && f.path().extension() == ".json") kept.push_back(f.path());
  ASSERT_EQ(kept.size(), 1u);
  std::stringstream text;
  text << std::ifstream(kept[0]).rdbuf();
  EXPECT_EQ(text.str(), broken);   // the user's bytes, untouched
  // The new session's own autosave went to .recovery.json again, beside the kept file.
  EXPECT_TRUE(fs::exists(home / ".recovery.json"));
  fs::remove_all(dir);
}

TEST(EditorSession, SaveAsAndScreenshotsGoToTheUsersFolder) {
  if (!have_display()) GTEST_SKIP() << "no DISPLAY";
  namespace fs = std::filesystem;
  const std::string preset = std::string(SYLVA_SOURCE_DIR) + "/presets/lsystem_honda_a.json";
  // Ctrl+S on a shipped preset is Save as in the user's folder; F12 saves the 3D view there and
  // says where; Open browses with the recent files.
  const std::string script = "wait_tree\nkey ctrl+s\nexpect_prompt Save preset as\nanswer Save\nframes 2\n"
                             "expect_modified 0\nkey f12\nframes 3\nkey ctrl+o\nexpect_prompt Open preset\n"
                             "answer Cancel\nframes 2\nexpect_no_prompt\n";
  run_result r = run_script("files", script, preset);
  ASSERT_EQ(r.code, 0) << r.output;
  const fs::path home = test_dir("files") / "home";
  int presets = 0, shots = 0;
  for (const auto& f : fs::directory_iterator(home)) presets += f.path().extension() == ".json";
  for (const auto& f : fs::directory_iterator(home / "screenshots")) shots += f.path().extension() == ".png";
  EXPECT_EQ(presets, 1);
  EXPECT_EQ(shots, 1);
  EXPECT_FALSE(fs::exists("sylva_screenshot.png"));
}

TEST(EditorFiles, ListsFoldersFirstAndFiltersByExtension) {
  namespace fs = std::filesystem;
  const fs::path d = test_dir("list_folder");
  fs::remove_all(d);
  fs::create_directories(d / "sub");
  std::ofstream(d / "b.json") << "{}";
  std::ofstream(d / "a.JSON") << "{}";
  std::ofstream(d / "c.png") << "";
  std::ofstream(d / ".hidden.json") << "";
  std::vector<sylva::file_entry> out;
  EXPECT_EQ(sylva::list_folder(d.string(), {".json"}, false, out), "");
  ASSERT_EQ(out.size(), 3u);
  EXPECT_TRUE(out[0].folder);
  EXPECT_EQ(out[1].name, "a.JSON");
  EXPECT_EQ(out[2].name, "b.json");
  EXPECT_EQ(sylva::list_folder(d.string(), {".json"}, true, out), "");
  EXPECT_EQ(out.size(), 4u);
  EXPECT_NE(sylva::list_folder((d / "missing").string(), {".json"}, false, out), "");
  std::vector<std::string> recent = {"x", "y"};
  sylva::note_recent(recent, "y");
  EXPECT_EQ(recent, (std::vector<std::string>{"y", "x"}));
}

TEST(EditorBench, EditLatencyIsReportedPerPreset) {
  if (!have_display()) GTEST_SKIP() << "no DISPLAY";
  const std::string cmd = "'" + std::string(SYLVA_BINARY) + "' bench --edit --json --repeat 2 --width 64 --height 48 '" +
                          std::string(SYLVA_SOURCE_DIR) + "/presets/lsystem_honda_a.json' 2>&1";
  FILE* f = popen(cmd.c_str(), "r");
  ASSERT_NE(f, nullptr);
  std::string out;
  char buf[512];
  while (fgets(buf, sizeof buf, f)) out += buf;
  EXPECT_EQ(pclose(f), 0) << out;
  EXPECT_NE(out.find("\"preset\":\"lsystem_honda_a\""), std::string::npos) << out;
  EXPECT_NE(out.find("\"nodes\":1024"), std::string::npos) << out;
  EXPECT_NE(out.find("\"edit_ms\":"), std::string::npos) << out;
}

// A newcomer on slow frames: a quick click into the Export path and typing straight after it,
// all queued before the next frame, gives the whole text; Export as... writes the file; a held Ctrl+Z (system repeats) undoes
// one step, not the history; F1 and Ctrl+L open their windows on the first press.
TEST(EditorSession, SlowFramesLoseNoTypingAndHeldUndoTakesOneStep) {
  if (!have_display()) GTEST_SKIP() << "no DISPLAY";
  const std::string preset = leafless_bush("newcomer_bush.json");
  ASSERT_FALSE(preset.empty());
  const std::string script = R"(wait_tree
show_export 1
export_path 
click export_path
type /proc/x.glb
frames 4
expect_export_path /proc/x.glb
show_export 0
frames 3
export_as EXPORTED
expect_file EXPORTED
show_export 0
set lambda=0.42
wait_tree
set lambda=0.43
wait_tree
set lambda=0.44
wait_tree
hold ctrl+z 8
wait_tree
expect_param lambda=0.43
key f1
expect_window shortcuts 1
key ctrl+l
expect_window library 1
)";
  std::string with_paths = script;
  const std::string exported = (test_dir("newcomer") / "home" / "exported.json").string();
  for (size_t at; (at = with_paths.find("EXPORTED")) != std::string::npos;) with_paths.replace(at, 8, exported);
  run_result r = run_passing("newcomer", with_paths, preset);
  EXPECT_NE(r.output.find("ok expect_export_path /proc/x.glb"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("ok expect_window library 1"), std::string::npos) << r.output;
}

// Drop B throws B away at once while B holds nothing of its own, and asks once B has edits.
TEST(EditorSession, DropBAsksOnlyWhenBHasEdits) {
  if (!have_display()) GTEST_SKIP() << "no DISPLAY";
  const std::string preset = leafless_bush("dropb_bush.json");
  ASSERT_FALSE(preset.empty());
  const std::string script = R"(wait_tree
ab_duplicate
ab_drop
expect_no_prompt
expect_has_b 0
ab_duplicate
set lambda=0.5
frames 2
ab_drop
expect_prompt Drop slot B?
answer Keep B
frames 2
expect_has_b 1
ab_drop
expect_prompt Drop slot B?
answer Drop B
frames 2
expect_has_b 0
)";
  run_result r = run_passing("dropb", script, preset);
  EXPECT_NE(r.output.find("ok answer Keep B"), std::string::npos) << r.output;
}

// A path parameter loads its file on Enter, not on every keystroke: typing a texture path in
// several bursts (frames apart) reads no file until Enter, then one.
TEST(EditorSession, ATexturePathLoadsOnEnterNotWhileTyped) {
  if (!have_display()) GTEST_SKIP() << "no DISPLAY";
  const std::string preset = leafless_bush("path_bush.json");
  ASSERT_FALSE(preset.empty());
  const std::string script = R"(wait_tree
expect_texture_loads 0
search leaf texture
frames 3
click_path leaf_texture
type /no
frames 3
type /such
frames 3
type /leaf.png
frames 3
expect_texture_loads 0
expect_param leaf_texture=
key enter
frames 4
expect_texture_loads 1
expect_param leaf_texture=/no/such/leaf.png
)";
  run_passing("texture_path", script, preset);
}

// Slot B draws with slot A's programs (one GL context, one set): duplicating compiles none.
TEST(EditorSession, SlotBCompilesNoProgramsOfItsOwn) {
  if (!have_display()) GTEST_SKIP() << "no DISPLAY";
  const std::string preset = leafless_bush("programs_bush.json");
  ASSERT_FALSE(preset.empty());
  const std::string script = R"(wait_tree
remember_programs
ab_duplicate
frames 4
expect_has_b 1
expect_new_programs 0
)";
  run_passing("programs", script, preset);
}
