// A/B comparison (issue 18), the display-free part: duplicate, select, edit isolation, per-slot
// undo history and saving either slot (app/editor_ab.h).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include <unistd.h>

#include "app/editor_ab.h"
#include "render/preset.h"

namespace sylva {
namespace {

ab_doc start_doc() {
  ab_doc d;
  d.doc = default_preset();
  d.doc.name = "Oak";
  d.undo_base = d.doc;
  d.path = "/somewhere/oak.json";
  d.baseline = d.doc;
  d.baseline_path = d.path;
  d.undo.push_back(preset{});   // an earlier edit of A
  return d;
}

TEST(EditorAB, DuplicateCopiesTheDocumentIntoB) {
  ab_state s;
  ab_doc cur = start_doc();
  ASSERT_TRUE(ab_duplicate_doc(s, cur));
  EXPECT_TRUE(s.has_b);
  EXPECT_EQ(s.selected, 0);
  const ab_doc& b = ab_slot_doc(s, 1, cur);
  EXPECT_EQ(b.doc.spec, cur.doc.spec);
  EXPECT_EQ(b.doc.mesh, cur.doc.mesh);
  EXPECT_EQ(b.doc.render, cur.doc.render);
  EXPECT_EQ(b.doc.name, "Oak (B)");
  EXPECT_TRUE(b.undo.empty());       // B starts its own history
  EXPECT_TRUE(b.path.empty());       // and has no file: Save asks where
  EXPECT_NE(b.baseline, b.doc);      // so it shows as unsaved
  EXPECT_EQ(&ab_slot_doc(s, 0, cur), &cur);
}

TEST(EditorAB, SelectSwapsAndEditsStayInTheirSlot) {
  ab_state s;
  ab_doc cur = start_doc();
  const tree_spec a_spec = cur.doc.spec;
  ASSERT_TRUE(ab_duplicate_doc(s, cur));
  EXPECT_FALSE(ab_select_doc(s, 0, cur));   // A is selected already
  ASSERT_TRUE(ab_select_doc(s, 1, cur));
  EXPECT_EQ(s.selected, 1);
  EXPECT_EQ(cur.doc.name, "Oak (B)");
  // B takes another generator on the same seed, as the panel's combo would.
  cur.doc.spec.params = default_params(a_spec.params.index() == 0 ? 1 : 0);
  ASSERT_NE(cur.doc.spec.params.index(), a_spec.params.index());
  cur.undo.push_back(cur.undo_base);
  cur.undo_base = cur.doc;
  EXPECT_EQ(ab_slot_doc(s, 0, cur).doc.spec, a_spec);   // A untouched
  ASSERT_TRUE(ab_select_doc(s, 0, cur));
  EXPECT_EQ(cur.doc.spec, a_spec);
  EXPECT_EQ(cur.undo.size(), 1u);                      // A's history, not B's
  EXPECT_EQ(cur.path, "/somewhere/oak.json");
  const ab_doc& b = ab_slot_doc(s, 1, cur);
  EXPECT_NE(b.doc.spec.params.index(), a_spec.params.index());
  EXPECT_EQ(b.doc.spec.seed, a_spec.seed);
  EXPECT_EQ(b.undo.size(), 1u);
  // Undoing in B (the editor's apply_undo on the selected slot) restores B's duplicate, not A.
  ASSERT_TRUE(ab_select_doc(s, 1, cur));
  cur.redo.push_back(cur.doc);
  cur.doc = cur.undo.back();
  cur.undo.pop_back();
  EXPECT_EQ(cur.doc.spec, a_spec);       // B's first state was the copy of A
  EXPECT_EQ(cur.doc.name, "Oak (B)");
  EXPECT_EQ(ab_slot_doc(s, 0, cur).undo.size(), 1u);
}

TEST(EditorAB, SavingSlotBWritesBsSpec) {
  ab_state s;
  ab_doc cur = start_doc();
  ASSERT_TRUE(ab_duplicate_doc(s, cur));
  ASSERT_TRUE(ab_select_doc(s, 1, cur));
  cur.doc.spec.seed = 4242;   // as the panel's Seed field does
  ASSERT_TRUE(ab_select_doc(s, 0, cur));   // A is selected; B is saved from its slot
  const std::string path =
      (std::filesystem::temp_directory_path() / ("sylva_ab_b_" + std::to_string(getpid()) + ".json")).string();
  ASSERT_EQ(ab_save_slot(s, 1, cur, path), "");
  preset loaded;
  ASSERT_TRUE(load_preset_file(path, loaded).ok);
  EXPECT_EQ(loaded.spec.seed, 4242u);
  EXPECT_EQ(loaded.spec, ab_slot_doc(s, 1, cur).doc.spec);
  EXPECT_NE(loaded.spec, cur.doc.spec);
  EXPECT_EQ(ab_slot_doc(s, 1, cur).path, path);
  EXPECT_EQ(ab_slot_doc(s, 1, cur).baseline, ab_slot_doc(s, 1, cur).doc);   // B is saved now
  EXPECT_EQ(cur.path, "/somewhere/oak.json");                                // A's file unchanged
  EXPECT_NE(ab_save_slot(s, 1, cur, path + "/under_a_file.json"), "");   // a clear error, no crash
  EXPECT_EQ(ab_slot_doc(s, 1, cur).path, path);                            // and B's file stays
  std::filesystem::remove(path);
}

TEST(EditorAB, DuplicateOnlyFromAAndDropReturnsToA) {
  ab_state s;
  ab_doc cur = start_doc();
  ASSERT_TRUE(ab_duplicate_doc(s, cur));
  ASSERT_TRUE(ab_select_doc(s, 1, cur));
  EXPECT_FALSE(ab_duplicate_doc(s, cur));
  ab_drop_doc(s, cur);
  EXPECT_FALSE(s.has_b);
  EXPECT_EQ(s.selected, 0);
  EXPECT_EQ(cur.doc.name, "Oak");
  EXPECT_FALSE(ab_select_doc(s, 1, cur));   // no B to select
}

TEST(EditorAB, CompareTextNamesBothSlots) {
  ab_counts a, b;
  a.present = true, a.nodes = 1234, a.leaves = 56789, a.triangles = 2500000, a.grow_ms = 12.4, a.mesh_ms = 3;
  const std::string t = ab_compare_text(a, b);
  EXPECT_EQ(t, "A 1234 nodes 56.8k leaves 2.50M tris grow 12 ms mesh 3 ms | B growing");
  EXPECT_EQ(ab_counts_of(nullptr).present, false);
}

}  // namespace
}  // namespace sylva
