// The editor's picking ray matches the renderer's projection: the ray through the pixel where a
// point is drawn passes through that point, and a click there picks the branch drawn there.
#include <gtest/gtest.h>

#include "app/editor/editor_prune.h"
#include "generators/keyframes.h"
#include "generators/space_colonization.h"
#include "render/mesh/pick.h"

using namespace sylva;

TEST(EditorPrune, RayThroughAProjectedPointPassesThroughIt) {
  orbit_camera cam;
  cam.target = {0.3f, 2, -0.2f}, cam.distance = 7, cam.yaw = 50, cam.pitch = 12;
  const view_rect v{420, 22, 780, 600};
  // The renderer's projection (render/gl/renderer.cpp draw_frame): render/camera.h's, over the view's aspect.
  const glm::mat4 vp = camera_projection(cam, v.w / v.h, 0.07f, 100.0f) * camera_view(cam);
  for (const glm::vec3 p : {glm::vec3(0), glm::vec3(1, 3, 0.5f), glm::vec3(-2, 1, 1), glm::vec3(0.5f, 4, -1)}) {
    glm::vec4 c = vp * glm::vec4(p, 1);
    c /= c.w;
    glm::vec3 o, d;
    view_ray(cam, v, v.x + (c.x + 1) * 0.5f * v.w, v.y + (1 - c.y) * 0.5f * v.h, o, d);
    const glm::vec3 w = p - o;
    EXPECT_LT(glm::length(w - glm::dot(w, d) * d), 1e-4f * glm::length(w));
  }
  // A click on the drawn middle of an internode picks it.
  tree_skeleton t;
  t.add_node({0, 0, 0}, -1, 0.05f, 0, 0);
  t.add_node({0, 2, 0}, 0, 0.05f, 1, 0);
  t.steps = 1;
  glm::vec4 c = vp * glm::vec4(0, 1, 0, 1);
  c /= c.w;
  prune_panel_state s;
  pick_in_view(s, t, 1, cam, v, v.x + (c.x + 1) * 0.5f * v.w, v.y + (1 - c.y) * 0.5f * v.h);
  EXPECT_EQ(s.selected, 1);
}

// A cut acts from the step after the one shown: at the last step the tree grew it would change
// nothing, even when the Growth steps setting allows many more steps (the oak stops at 56 of 400).
TEST(EditorPrune, CutAtTheLastGrownStepIsRefusedWithTheStepsItGrew) {
  tree_spec spec;   // space colonization, as the oak: its Growth steps are far more than 56
  spec.params = space_colonization_params{};
  ASSERT_GT(last_keyframe_step(spec), 57);
  EXPECT_EQ(cut_refusal(spec, 56, 45, "A cut"), "");
  EXPECT_EQ(cut_refusal(spec, 56, 55, "A cut"), "");
  const std::string why = cut_refusal(spec, 56, 56, "A cut");
  EXPECT_NE(why.find("step 56 of 56"), std::string::npos) << why;
  EXPECT_NE(cut_refusal(spec, 56, 57, "The brush").find("The brush"), std::string::npos);
  // Without a shown tree the spec's own last step is the limit.
  EXPECT_EQ(cut_refusal(spec, -1, 56, "A cut"), "");
  EXPECT_NE(cut_refusal(spec, -1, last_keyframe_step(spec), "A cut"), "");
}
