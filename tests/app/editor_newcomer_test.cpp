// The editor as a newcomer meets it, end to end under Xvfb (SYLVA_SCRIPT): the library's
// thumbnails (rendered once, then read from the cache), one card per preset shipped twice, the
// library closing after a pick; the title and modified flag after Esc cancels a regrow; keyframe
// markers on the steps grown; a long status cut with its text in a tooltip; F1 and Ctrl+L from a
// text field; plain Export asking before it replaces a file, Export as writing at once.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "app/editor/editor_state.h"
#include "editor_script_run.h"
#include "render/io/preset.h"

namespace {

using sylva_test::have_display;
using sylva_test::run_result;
using sylva_test::run_script;
using sylva_test::script_passed;
using sylva_test::test_dir;
namespace fs = std::filesystem;

const std::string presets = std::string(SYLVA_SOURCE_DIR) + "/presets/";

// A preset of the source tree saved under `name` in `dir` without leaves (fast llvmpipe frames).
std::string leafless(const std::string& source, const fs::path& dir, const std::string& name) {
  sylva::preset p;
  EXPECT_TRUE(sylva::load_preset_file(presets + source, p).ok);
  p.mesh.leaves_enabled = false;
  fs::create_directories(dir);
  const std::string path = (dir / name).string();
  EXPECT_EQ(sylva::save_preset_file(p, path), "");
  return path;
}

void replace_all(std::string& s, const std::string& what, const std::string& with) {
  for (size_t at; (at = s.find(what)) != std::string::npos;) s.replace(at, what.size(), with);
}

// A status piece too wide for its room is cut between characters with "…" and fits; one that
// fits is whole. Width here: one unit per character (UTF-8 aware), the dots count one.
TEST(EditorNewcomer, ElidedTextFitsItsWidthAndKeepsCharactersWhole) {
  auto chars = [](std::string_view t) {
    float n = 0;
    for (unsigned char c : t) n += (c & 0xC0) != 0x80;
    return n;
  };
  EXPECT_EQ(sylva::ed::elide_text("Saved oak.json", 20, chars), "Saved oak.json");
  EXPECT_EQ(sylva::ed::elide_text("Saved oak.json", 14, chars), "Saved oak.json");
  EXPECT_EQ(sylva::ed::elide_text("Saved oak.json", 10, chars), "Saved oak\u2026");
  EXPECT_EQ(sylva::ed::elide_text("Saved oak.json", 7, chars), "Saved\u2026");   // no space before the dots
  EXPECT_EQ(sylva::ed::elide_text("λσκ dᵢ", 3, chars), "λσ\u2026");                 // never half a character
  EXPECT_EQ(sylva::ed::elide_text("abc", 0, chars), "\u2026");                      // nothing fits: the dots alone
}

// The name proposed for Save as and Export as: no runs of "_" and none at the ends.
TEST(EditorNewcomer, FileNamesFromPresetNamesReadCleanly) {
  EXPECT_EQ(sylva::ed::file_stem_for("Hazel fan (guiding vectors)"), "hazel_fan_guiding_vectors");
  EXPECT_EQ(sylva::ed::file_stem_for("Oak (B)"), "oak_b");
  EXPECT_EQ(sylva::ed::file_stem_for("Space colonization: seed cube"), "space_colonization_seed_cube");
  EXPECT_EQ(sylva::ed::file_stem_for("Fig. 7, radial t1"), "fig_7_radial_t1");
  EXPECT_EQ(sylva::ed::file_stem_for("  --  "), "tree");
  EXPECT_EQ(sylva::ed::file_stem_for("Érable"), "rable");   // only ASCII letters and digits are kept
}

// Two folders both shipping the bush (same name, same bytes) and one the Honda tree: two cards.
// The first start renders both thumbnails into the cache; a pick opens the preset and closes the
// library. The second start reads both from the cache and renders none.
TEST(EditorNewcomer, LibraryThumbnailsAreCachedOneCardPerPresetAndAPickClosesIt) {
  if (!have_display()) GTEST_SKIP() << "no DISPLAY";
  const fs::path fixture = test_dir("library_fixture");
  fs::remove_all(fixture);
  const std::string bush = leafless("self_organizing_seed001_bush.json", fixture / "a", "bush.json");
  fs::create_directories(fixture / "b");
  fs::copy_file(bush, fixture / "b" / "bush.json");
  leafless("lsystem_honda_a.json", fixture / "b", "honda.json");
  const std::string env = "XDG_CACHE_HOME='" + (fixture / "cache").string() + "' ";
  std::string script = R"(wait_tree
library_folders A B
key ctrl+l
expect_window library 1
wait_thumbnails
expect_cards Bush (seed 001 fig. 3b) 1
expect_cards Honda tree a 1
click card Honda tree a
frames 3
expect_window library 0
wait_tree
expect_doc_name Honda tree a
)";
  replace_all(script, "A B", (fixture / "a").string() + " " + (fixture / "b").string());
  run_result first = run_script("library1", script, bush, env);
  EXPECT_TRUE(script_passed(first));
  EXPECT_NE(first.output.find("thumbnails: 2 cards, 2 rendered, 0 from the cache, 0 without a picture"), std::string::npos)
      << first.output;
  EXPECT_NE(first.output.find("ok expect_doc_name Honda tree a"), std::string::npos) << first.output;

  run_result second = run_script("library2", script, bush, env);
  EXPECT_TRUE(script_passed(second));
  EXPECT_NE(second.output.find("thumbnails: 2 cards, 0 rendered, 2 from the cache, 0 without a picture"), std::string::npos)
      << second.output;
}

// Esc cancels a long regrow: the document goes back to the tree on screen, and the title's "*"
// says what the modified flag says, after an edit (kept) and from the saved state (none).
TEST(EditorNewcomer, EscDuringARegrowLeavesTheTitleAndModifiedFlagAgreeing) {
  if (!have_display()) GTEST_SKIP() << "no DISPLAY";
  const std::string cube = leafless("space_colonization_seed_cube.json", test_dir("title_fixture"), "cube.json");
  // One frame's edits that grow for about a minute (as in CancellingALongGrowthKeepsThePreviousTree).
  const std::string long_edit =
      "set_all points=400000 segment_length=0.02 influence_radius=1 kill_distance=0.1 max_branches=10000000 steps=20000 "
      "node_cap=2000000 mesh_budget=32000\n";
  std::string script = R"(wait_tree
frames 2
expect_title Sylva - Space colonization: seed cube
set segment_length=0.45
wait_tree
frames 2
expect_modified 1
expect_title Sylva - Space colonization: seed cube *
budget 100000000
LONG_EDITwait_progress
wait_growing 2
key escape
expect_state cancelled
expect_param segment_length=0.45
expect_modified 1
frames 2
expect_title Sylva - Space colonization: seed cube *
key ctrl+z
wait_tree
expect_param segment_length=0.5
expect_modified 0
frames 2
expect_title Sylva - Space colonization: seed cube
LONG_EDITwait_progress
wait_growing 2
key escape
expect_state cancelled
expect_modified 0
frames 2
expect_title Sylva - Space colonization: seed cube
)";
  replace_all(script, "LONG_EDIT", long_edit);
  run_result r = run_script("title", script, cube);
  EXPECT_TRUE(script_passed(r));
  EXPECT_NE(r.output.find("ok expect_title Sylva - Space colonization: seed cube * ("), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("ok expect_title Sylva - Space colonization: seed cube ("), std::string::npos) << r.output;
}

// A keyframe's marker sits at its step over the steps the tree grew (the cube stops long before
// its Growth steps setting); a long status message is cut at the window's edge, whole in a tooltip.
TEST(EditorNewcomer, MarkersFollowTheStepsGrownAndALongStatusFits) {
  if (!have_display()) GTEST_SKIP() << "no DISPLAY";
  const std::string cube = leafless("space_colonization_seed_cube.json", test_dir("marker_fixture"), "cube.json");
  sylva::preset p;
  ASSERT_TRUE(sylva::load_preset_file(cube, p).ok);
  const int setting = std::get<sylva::space_colonization_params>(p.spec.params).steps;
  const std::string long_text(300, 'x');
  const std::string script = "wait_tree\nset segment_length@10=0.45\nwait_tree\nframes 2\nexpect_marker 10\nstatus Saved " +
                             long_text + " end\nexpect_status_fits cut\n";
  run_result r = run_script("markers", script, cube);
  EXPECT_TRUE(script_passed(r));
  const size_t at = r.output.find("steps grown)");
  ASSERT_NE(at, std::string::npos) << r.output;
  const int grown = std::atoi(r.output.c_str() + r.output.rfind('(', at) + 1);
  EXPECT_GT(grown, 10);
  EXPECT_LT(grown, setting) << "the cube must stop before its setting for the marker to tell the two apart";
  const size_t tooltip = r.output.find("whole in its tooltip: ");
  ASSERT_NE(tooltip, std::string::npos) << r.output;
  EXPECT_NE(r.output.find("   Saved " + long_text + " end", tooltip), std::string::npos) << r.output;
}

// With the keyboard in a text field (the Export path), F1 and Ctrl+L still open and close their
// windows, each press queued inside one frame as on a slow frame, and type nothing into the field.
TEST(EditorNewcomer, F1AndCtrlLWorkFromATextFieldOnSlowFrames) {
  if (!have_display()) GTEST_SKIP() << "no DISPLAY";
  const std::string bush = leafless("self_organizing_seed001_bush.json", test_dir("keys_fixture"), "bush.json");
  const std::string script = R"(wait_tree
show_export 1
export_path tree.glb
click export_path
key f1
expect_window shortcuts 1
key ctrl+l
expect_window library 1
key f1
expect_window shortcuts 0
key ctrl+l
expect_window library 0
expect_export_path tree.glb
)";
  run_result r = run_script("keys", script, bush);
  EXPECT_TRUE(script_passed(r));
  EXPECT_NE(r.output.find("ok expect_window library 0"), std::string::npos) << r.output;
}

// The search box keeps the tabs and the generator selector; it says when nothing matches, and it
// finds a text L-system's #define constants by their comment ("angle of the limbs from the trunk").
TEST(EditorNewcomer, SearchSaysWhenNothingMatchesAndFindsDefineConstants) {
  if (!have_display()) GTEST_SKIP() << "no DISPLAY";
  const std::string pine = leafless("species_pine.json", test_dir("search_fixture"), "pine.json");
  const std::string script = R"(wait_tree
search lambda
expect_search_matches 0
search limbs from the trunk
expect_search_matches 1
search
expect_search_matches -1
)";
  run_result r = run_script("search", script, pine);
  EXPECT_TRUE(script_passed(r));
  EXPECT_NE(r.output.find("ok expect_search_matches -1"), std::string::npos) << r.output;
}

// Opening a preset again keeps the view (F frames it), so before and after compare from one place;
// a new generator is a new tree: the pine's needles, plated bark and name do not carry over.
TEST(EditorNewcomer, ReopeningKeepsTheViewAndANewGeneratorDropsTheSpeciesLook) {
  if (!have_display()) GTEST_SKIP() << "no DISPLAY";
  const std::string pine = leafless("species_pine.json", test_dir("reopen_fixture"), "pine.json");
  const std::string script = "wait_tree\nkey 1\nset radial_segments=5\nwait_tree\nremember_camera\nopen " + pine + R"(
expect_prompt Unsaved changes
answer Discard
wait_tree
frames 3
expect_camera kept
key f
expect_camera moved
expect_param leaf_archetype=needles
expect_param bark_archetype=plated
generator lsystem
wait_tree
expect_doc_name New L-system
expect_param leaf_archetype=ovate
expect_param bark_archetype=furrowed
)";
  run_result r = run_script("reopen", script, pine);
  EXPECT_TRUE(script_passed(r));
  EXPECT_NE(r.output.find("ok expect_param bark_archetype=furrowed"), std::string::npos) << r.output;
}

// Esc closes what is on top, as the F1 list says: an open menu, then the library, then the list.
TEST(EditorNewcomer, EscClosesAMenuTheLibraryAndTheHelp) {
  if (!have_display()) GTEST_SKIP() << "no DISPLAY";
  const std::string bush = leafless("self_organizing_seed001_bush.json", test_dir("esc_fixture"), "bush.json");
  const std::string script = R"(wait_tree
click 20 10
expect_popup 1
key escape
expect_popup 0
key ctrl+l
key f1
expect_window library 1
expect_window shortcuts 1
key escape
expect_window library 0
expect_window shortcuts 1
key escape
expect_window shortcuts 0
)";
  run_result r = run_script("esc", script, bush);
  EXPECT_TRUE(script_passed(r));
  EXPECT_NE(r.output.find("ok expect_window shortcuts 0"), std::string::npos) << r.output;
}

// Side by side in a small window, a long preset name is cut with "…" so that each label fits its
// half and the selected slot's still ends "(selected)" (it was clipped off).
TEST(EditorNewcomer, ABLabelsFitTheirHalvesAndKeepSelected) {
  if (!have_display()) GTEST_SKIP() << "no DISPLAY";
  sylva::preset bush;
  ASSERT_TRUE(sylva::load_preset_file(presets + "self_organizing_seed001_bush.json", bush).ok);
  bush.mesh.leaves_enabled = false;
  bush.name = "Bush with a name far too long for half of a small window";
  const fs::path dir = test_dir("ab_labels_fixture");
  fs::create_directories(dir);
  ASSERT_EQ(sylva::save_preset_file(bush, (dir / "bush.json").string()), "");
  const std::string script = "wait_tree\nab_duplicate\nab_mode side\nab_wait\nframes 3\nexpect_ab_labels\nab_select a\nframes 3\nexpect_ab_labels\n";
  run_result r = run_script("ab_labels", script, (dir / "bush.json").string());
  EXPECT_TRUE(script_passed(r));
  EXPECT_NE(r.output.find("\u2026  (selected)\""), std::string::npos) << r.output;   // cut, and still marked
}

// Plain Export onto an existing file asks first and writes only after Replace; Export as... (its
// file browser asked already) writes over an existing file at once. Each export's outcome stays in
// the status bar (it was cleared as stale in the frame it arrived).
TEST(EditorNewcomer, ExportAsksBeforeReplacingAndExportAsWritesAtOnce) {
  if (!have_display()) GTEST_SKIP() << "no DISPLAY";
  const fs::path dir = test_dir("export_fixture");
  const std::string bush = leafless("self_organizing_seed001_bush.json", dir, "bush.json");
  const std::string plain = (dir / "plain.json").string(), as = (dir / "as.json").string();
  std::ofstream(plain) << "old";
  std::ofstream(as) << "old";
  std::string script = R"(wait_tree
show_export 1
export_path PLAIN
frames 3
click export_button
frames 3
expect_export_asking 1
expect_file_size PLAIN 3
click export_button
wait_file_size_over PLAIN 3
frames 3
expect_message Exported PLAIN
show_export 0
menu_export_as
expect_prompt Export as
file_path AS
answer Save
expect_prompt Export as
answer Replace
wait_file_size_over AS 3
frames 3
expect_message Exported AS
expect_export_asking 0
)";
  replace_all(script, "PLAIN", plain);
  replace_all(script, "AS\n", as + "\n");
  replace_all(script, "AS 3", as + " 3");
  replace_all(script, "Exported AS", "Exported " + as);
  run_result r = run_script("export", script, bush);
  EXPECT_TRUE(script_passed(r));
  EXPECT_GT(fs::file_size(plain), 3u);
  EXPECT_GT(fs::file_size(as), 3u);
}

}  // namespace
