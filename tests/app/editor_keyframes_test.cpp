// The editor's growth-phase logic without a display: slider edits become keyframes, markers move.
#include <gtest/gtest.h>

#include "app/editor/editor_keyframes.h"

using namespace sylva;

namespace {

tree_spec so_spec() {
  tree_spec s;
  self_organizing_params p;
  p.steps = 12;
  s.params = p;
  return s;
}

}  // namespace

TEST(EditorKeyframes, AnEditFromAStepOnBecomesAKeyframeAndAnEditBackRemovesIt) {
  tree_spec s = so_spec();
  const generator_params before = params_at_step(s, 5);
  generator_params after = before;
  std::get<self_organizing_params>(after).lambda = 0.7f;
  ASSERT_EQ(key_edits(s, before, after, 5), "");
  ASSERT_EQ(s.keyframes.size(), 1u);
  EXPECT_EQ(s.keyframes[0].step, 5);
  EXPECT_EQ(s.keyframes[0].key, "lambda");
  EXPECT_EQ(s.keyframes[0].value.x, 0.7f);
  EXPECT_TRUE(keyed_at(s, "lambda", 5));
  EXPECT_EQ(std::get<self_organizing_params>(params_at_step(s, 8)).lambda, 0.7f);
  // The base value is untouched; moving the slider back to the value in effect removes the key.
  EXPECT_EQ(std::get<self_organizing_params>(s.params).lambda, 0.55f);
  const generator_params now = params_at_step(s, 5);
  generator_params back = now;
  std::get<self_organizing_params>(back).lambda = 0.55f;
  ASSERT_EQ(key_edits(s, now, back, 5), "");
  EXPECT_TRUE(s.keyframes.empty());
}

TEST(EditorKeyframes, RefusedEditsChangeNothing) {
  tree_spec s = so_spec();
  const tree_spec was = s;
  const generator_params before = params_at_step(s, 5);
  generator_params after = before;
  std::get<self_organizing_params>(after).voxel_size = 2;
  EXPECT_NE(key_edits(s, before, after, 5).find("cannot change from a step on"), std::string::npos);
  EXPECT_EQ(s, was);
  after = before;
  std::get<self_organizing_params>(after).positions.push_back(glm::vec3(1));
  EXPECT_NE(key_edits(s, before, after, 5).find("cannot be keyed"), std::string::npos);
  EXPECT_EQ(s, was);
}

TEST(EditorKeyframes, MovingAMarkerMovesItsKeyframesOrRefuses) {
  tree_spec s = so_spec();
  ASSERT_EQ(set_keyframe(s, {3, "lambda", glm::vec3(0.6f, 0, 0)}), "");
  ASSERT_EQ(set_keyframe(s, {3, "alpha", glm::vec3(3, 0, 0)}), "");
  ASSERT_EQ(set_keyframe(s, {7, "lambda", glm::vec3(0.7f, 0, 0)}), "");
  ASSERT_EQ(move_keyframes(s, 3, 5), "");
  EXPECT_EQ(keyed_steps(s), (std::vector<int>{5, 7}));
  const tree_spec was = s;
  EXPECT_NE(move_keyframes(s, 5, 7).find("already keyed"), std::string::npos);   // lambda@7 exists
  EXPECT_NE(move_keyframes(s, 5, 201).find("beyond the most steps a growth can have (200)"), std::string::npos);
  EXPECT_EQ(s, was);
  // Past the last step but within the steps' range: kept, inactive (the same rule as the loader).
  ASSERT_EQ(move_keyframes(s, 5, 13), "");
  EXPECT_EQ(keyed_steps(s), (std::vector<int>{7, 13}));
  EXPECT_FALSE(step_active(s, 13));
  EXPECT_EQ(inactive_edits(s), 2);
  ASSERT_EQ(move_keyframes(s, 13, 5), "");
  EXPECT_EQ(keyframe_text(s, s.keyframes[0]), "alpha = 3");
}

// "From this step on" keys the edits at the step where it was switched on; once the timeline
// moves it switches off, so a later edit elsewhere is not keyed without notice.
TEST(EditorKeyframes, FromThisStepOnSwitchesOffWhenTheTimelineMoves) {
  keyframe_panel_state s;
  EXPECT_FALSE(follow_step(s, 12));
  s.from_step = true;
  s.from_step_at = 12;
  EXPECT_FALSE(follow_step(s, 12));
  EXPECT_TRUE(s.from_step);
  EXPECT_TRUE(follow_step(s, 13));
  EXPECT_FALSE(s.from_step);
  EXPECT_FALSE(follow_step(s, 12));   // off stays off
  EXPECT_FALSE(s.from_step);
  // Switched on without a recorded step (a script or a test): the current step is taken.
  s.from_step = true;
  EXPECT_FALSE(follow_step(s, 30));
  EXPECT_EQ(s.from_step_at, 30);
  // Step 0 has nothing before it to keep: it cannot hold a keyframe.
  s.from_step = true, s.from_step_at = 0;
  EXPECT_TRUE(follow_step(s, 0));
}
