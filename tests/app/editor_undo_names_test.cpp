// Undo entries say what they undo, in the panel's words.
#include <gtest/gtest.h>

#include "app/editor/editor_undo_names.h"

using namespace sylva;

TEST(EditorUndoNames, EntriesNameWhatChanged) {
  preset a = default_preset();
  EXPECT_EQ(change_name(a, a), "");
  preset b = a;
  b.render.season = leaf_season(2);
  EXPECT_EQ(change_name(a, b), "Season");
  b.render.sun_elevation += 10;
  EXPECT_EQ(change_name(a, b), "Sun elevation and 1 more");
  preset c = a;
  c.spec.seed += 1;
  EXPECT_EQ(change_name(a, c), "Seed");
  preset d = a;
  d.name = "Oak";
  EXPECT_EQ(change_name(a, d), "Open Oak");
  preset e = a;
  e.spec.cuts.push_back(prune_cut{12});
  EXPECT_EQ(change_name(a, e), "Cut at step 12");
  EXPECT_EQ(change_name(e, a), "Delete a cut");
}
