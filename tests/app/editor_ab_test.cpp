// A/B comparison, the display-free part: duplicate, select, edit isolation, per-slot
// undo history and saving either slot (app/editor/editor_ab.h).
#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <unistd.h>

#include "app/editor/editor_ab.h"
#include "render/io/preset.h"

namespace sylva {
namespace {

// Slot A holds an opened, saved document with one earlier edit.
void start_doc(ab_state& s) {
  editor_slot& d = s.slots[0];
  d.doc = default_preset();
  d.doc.name = "Oak";
  d.undo_base = d.doc;
  d.path = "/somewhere/oak.json";
  d.baseline = d.doc;
  d.baseline_path = d.path;
  d.undo.push_back(preset{});   // an earlier edit of A
}

TEST(EditorAB, DuplicateCopiesTheDocumentIntoB) {
  ab_state s;
  start_doc(s);
  ASSERT_TRUE(ab_duplicate_doc(s));
  EXPECT_TRUE(s.has_b);
  EXPECT_EQ(s.selected, 0);
  const editor_slot& b = s.slots[1];
  EXPECT_EQ(b.doc.spec, s.cur().doc.spec);
  EXPECT_EQ(b.doc.mesh, s.cur().doc.mesh);
  EXPECT_EQ(b.doc.render, s.cur().doc.render);
  EXPECT_EQ(b.doc.name, "Oak (B)");
  EXPECT_TRUE(b.undo.empty());       // B starts its own history
  EXPECT_TRUE(b.path.empty());       // and has no file: Save asks where
  EXPECT_NE(b.baseline, b.doc);      // so it shows as unsaved
  EXPECT_EQ(&s.slots[0], &s.cur());
}

TEST(EditorAB, SelectChangesTheSlotAndEditsStayInTheirSlot) {
  ab_state s;
  start_doc(s);
  const tree_spec a_spec = s.cur().doc.spec;
  ASSERT_TRUE(ab_duplicate_doc(s));
  EXPECT_FALSE(ab_select_doc(s, 0));   // A is selected already
  ASSERT_TRUE(ab_select_doc(s, 1));
  EXPECT_EQ(s.selected, 1);
  EXPECT_EQ(s.cur().doc.name, "Oak (B)");
  // B takes another generator on the same seed, as the panel's combo would.
  s.cur().doc.spec.params = default_params(a_spec.params.index() == 0 ? 1 : 0);
  ASSERT_NE(s.cur().doc.spec.params.index(), a_spec.params.index());
  s.cur().undo.push_back(s.cur().undo_base);
  s.cur().undo_base = s.cur().doc;
  EXPECT_EQ(s.slots[0].doc.spec, a_spec);   // A untouched
  ASSERT_TRUE(ab_select_doc(s, 0));
  EXPECT_EQ(s.cur().doc.spec, a_spec);
  EXPECT_EQ(s.cur().undo.size(), 1u);                      // A's history, not B's
  EXPECT_EQ(s.cur().path, "/somewhere/oak.json");
  const editor_slot& b = s.slots[1];
  EXPECT_NE(b.doc.spec.params.index(), a_spec.params.index());
  EXPECT_EQ(b.doc.spec.seed, a_spec.seed);
  EXPECT_EQ(b.undo.size(), 1u);
  // Undoing in B (the editor's apply_undo on the selected slot) restores B's duplicate, not A.
  ASSERT_TRUE(ab_select_doc(s, 1));
  s.cur().redo.push_back(s.cur().doc);
  s.cur().doc = s.cur().undo.back();
  s.cur().undo.pop_back();
  EXPECT_EQ(s.cur().doc.spec, a_spec);       // B's first state was the copy of A
  EXPECT_EQ(s.cur().doc.name, "Oak (B)");
  EXPECT_EQ(s.slots[0].undo.size(), 1u);
}

TEST(EditorAB, SavingSlotBWritesBsSpec) {
  ab_state s;
  start_doc(s);
  ASSERT_TRUE(ab_duplicate_doc(s));
  ASSERT_TRUE(ab_select_doc(s, 1));
  s.cur().doc.spec.seed = 4242;   // as the panel's Seed field does
  ASSERT_TRUE(ab_select_doc(s, 0));   // A is selected; B is saved from its slot
  const std::string path =
      (std::filesystem::temp_directory_path() / ("sylva_ab_b_" + std::to_string(getpid()) + ".json")).string();
  ASSERT_EQ(ab_save_slot(s, 1, path), "");
  preset loaded;
  ASSERT_TRUE(load_preset_file(path, loaded).ok);
  EXPECT_EQ(loaded.spec.seed, 4242u);
  EXPECT_EQ(loaded.spec, s.slots[1].doc.spec);
  EXPECT_NE(loaded.spec, s.cur().doc.spec);
  EXPECT_EQ(s.slots[1].path, path);
  EXPECT_EQ(s.slots[1].baseline, s.slots[1].doc);   // B is saved now
  EXPECT_EQ(s.cur().path, "/somewhere/oak.json");                                // A's file unchanged
  EXPECT_NE(ab_save_slot(s, 1, path + "/under_a_file.json"), "");   // a clear error, no crash
  EXPECT_EQ(s.slots[1].path, path);                            // and B's file stays
  std::filesystem::remove(path);
}

TEST(EditorAB, DuplicateOnlyFromAAndDropReturnsToA) {
  ab_state s;
  start_doc(s);
  ASSERT_TRUE(ab_duplicate_doc(s));
  ASSERT_TRUE(ab_select_doc(s, 1));
  EXPECT_FALSE(ab_duplicate_doc(s));
  ab_drop_doc(s);
  EXPECT_FALSE(s.has_b);
  EXPECT_EQ(s.selected, 0);
  EXPECT_EQ(s.cur().doc.name, "Oak");
  EXPECT_FALSE(ab_select_doc(s, 1));   // no B to select
}

TEST(EditorAB, CompareTextNamesBothSlots) {
  ab_counts a, b;
  a.present = true, a.nodes = 1234, a.leaves = 56789, a.triangles = 2500000, a.grow_ms = 12.4, a.mesh_ms = 3;
  const std::string t = ab_compare_text(a, b);
  EXPECT_EQ(t, "A 1234 nodes 56.8k leaves 2.50M tris grow 12 ms mesh 3 ms | B growing");
  EXPECT_EQ(ab_counts_of(nullptr).present, false);
}

// Quitting asks about both slots: B's unsaved change is found while A is selected and clean.
TEST(EditorAB, QuitSeesSlotBsChangesWhileAIsSelectedAndClean) {
  ab_state s;
  start_doc(s);
  EXPECT_TRUE(ab_unsaved_slots(s).empty());   // no B: A is clean
  ASSERT_TRUE(ab_duplicate_doc(s));
  ASSERT_TRUE(ab_select_doc(s, 1));
  s.cur().doc.spec.seed = 77;   // an edit of B
  ASSERT_TRUE(ab_select_doc(s, 0));
  // B was never saved, and is edited; A is selected and as saved.
  EXPECT_EQ(s.cur().doc, s.cur().baseline);
  EXPECT_EQ(ab_unsaved_slots(s), std::vector<int>{1});
  EXPECT_EQ(ab_unsaved_line(s, 1), "Slot B \"Oak (B)\" (no file yet)");
  EXPECT_EQ(ab_unsaved_line(s, 0), "Slot A \"Oak\" (/somewhere/oak.json)");
  // Saved, B is clean: nothing to ask.
  const std::string path =
      (std::filesystem::temp_directory_path() / ("sylva_ab_quit_" + std::to_string(getpid()) + ".json")).string();
  ASSERT_EQ(ab_save_slot(s, 1, path), "");
  EXPECT_TRUE(ab_unsaved_slots(s).empty());
  // Both edited: both listed, the selected slot first.
  s.cur().doc.spec.seed = 5;
  EXPECT_EQ(ab_unsaved_slots(s), std::vector<int>{0});
  ASSERT_TRUE(ab_select_doc(s, 1));
  s.cur().doc.spec.seed = 6;
  EXPECT_EQ(ab_unsaved_slots(s), (std::vector<int>{1, 0}));
  EXPECT_EQ(ab_unsaved_line(s, 1), "Slot B \"Oak (B)\" (" + path + ")");
  std::filesystem::remove(path);
  // Without B the line names the document only.
  ab_state alone;
  alone.slots[0].doc.name = "Oak (B)";
  EXPECT_EQ(ab_unsaved_line(alone, 0), "\"Oak (B)\" (no file yet)");
}

// The unselected slot's failed or over-budget regrow keeps its tree, and says so.
TEST(EditorAB, SlotBsFailedRegrowIsShownAndItsTreeMarkedStale) {
  slot_view v;
  v.posted_generation = 4;
  v.posted_once = true;
  v.growth = slot_growth::growing;
  grow_result ok;
  ok.generation = 3;   // an older request's tree: shown, the state stays growing
  ok.skeleton = std::make_shared<tree_skeleton>();
  EXPECT_EQ(ab_take_other_result(v, ok), ab_result_use::show);
  EXPECT_EQ(v.growth, slot_growth::growing);
  EXPECT_EQ(ab_slot_problem(v.growth, v.growth_text), "");
  grow_result failed = ok;   // the newest request failed (the worker re-publishes the last tree)
  failed.generation = 4;
  failed.report.error = true;
  failed.report.message = "out of memory while growing: lower the node cap or the step count";
  EXPECT_EQ(ab_take_other_result(v, failed), ab_result_use::keep);
  EXPECT_EQ(v.growth, slot_growth::failed);
  EXPECT_FALSE(v.posted_once);   // selecting B posts its document again
  const std::string problem = ab_slot_problem(v.growth, v.growth_text);
  EXPECT_EQ(problem, "growth stopped: out of memory while growing: lower the node cap or the step count");
  ab_counts a, b;
  a.present = b.present = true;
  a.nodes = 10, b.nodes = 20;
  b.problem = problem;
  const std::string line = ab_compare_text(a, b);
  EXPECT_NE(line.find("| B growth stopped: out of memory"), std::string::npos) << line;
  EXPECT_NE(line.find("(last tree: 20 nodes"), std::string::npos) << line;
  // Over the budget: kept, and the slot waits for the user's answer.
  slot_view w;
  w.posted_generation = 2;
  grow_result big = ok;
  big.generation = 2;
  big.over_budget = true;
  big.estimated_nodes = 1.5e6;
  EXPECT_EQ(ab_take_other_result(w, big), ab_result_use::keep);
  EXPECT_EQ(w.growth, slot_growth::asking);
  EXPECT_NE(ab_slot_problem(w.growth, w.growth_text).find("over the node budget (about 1500000 nodes)"), std::string::npos);
  // A cancelled request's late answer is dropped; a good newest answer clears the problem.
  w.stale_before = 6;
  big.generation = 5;
  EXPECT_EQ(ab_take_other_result(w, big), ab_result_use::ignore);
  w.posted_generation = 6;
  ok.generation = 6;
  ok.report.stop_reason = "finished";
  EXPECT_EQ(ab_take_other_result(w, ok), ab_result_use::show);
  EXPECT_EQ(w.growth, slot_growth::done);
  EXPECT_EQ(ab_slot_problem(w.growth, w.growth_text), "");
}

}  // namespace
}  // namespace sylva
