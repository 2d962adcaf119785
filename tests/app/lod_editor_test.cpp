// The editor's level choice with the impostor (app/editor/editor_lod.h): far away the renderer
// holds one camera-facing card showing the nearest atlas view, "Show LOD" 4 asks for it anywhere,
// and near the tree LOD0 comes back.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

#include "app/editor/editor_lod.h"
#include "generators/tree_spec.h"
#include "tests/gl/gl_test_context.h"
#include "render/io/preset.h"

using namespace sylva;

namespace {
class LodEditor : public sylva_test::renderer_test {};

// The shown tree as the editor holds it (the chain's build off the UI thread keeps it alive).
std::shared_ptr<const grow_result> as_result(const preset& p, const tree_skeleton& t, const tree_mesh& m) {
  auto g = std::make_shared<grow_result>();
  g->skeleton = std::make_shared<tree_skeleton>(t);
  g->mesh = m;
  g->mesh_settings = p.mesh;
  return g;
}
}  // namespace

TEST_F(LodEditor, FarAwayTheImpostorCardStandsInAndTurnsWithTheCamera) {
  auto [p, t, m] = show_preset("species_cedar");
  const auto g = as_result(p, t, m);
  render_params rp = p.render;
  rp.lod.impostor_size = 128;
  editor_lod s;   // no editor_lod_new_tree: the chain is built on the first update
  orbit_camera cam;
  cam.target = 0.5f * (m.bounds_min + m.bounds_max);
  cam.distance = 1000;   // far below LOD3's coverage
  cam.yaw = 10;
  // The chain is built off the UI thread: the first update asks for it and LOD0 shows until it
  // arrives; the update after it takes the chain.
  editor_lod_update(s, r, g, rp, cam, t.steps);
  EXPECT_EQ(s.chain, nullptr);
  EXPECT_EQ(s.uploaded, 0);
  EXPECT_NE(editor_lod_status(s).find("building the LOD chain"), std::string::npos) << editor_lod_status(s);
  ASSERT_TRUE(editor_lod_wait(s, 120000));
  // The atlas is built over frames (begin, a view each, the read-back, the layers); LOD3 shows meanwhile.
  int frames = 0;
  for (; frames < 20 && !s.impostor; ++frames) {
    editor_lod_update(s, r, g, rp, cam, t.steps);
    ASSERT_NE(s.chain, nullptr);
    ASSERT_EQ(s.impostor_error, "");
    if (!s.impostor) {
      EXPECT_EQ(s.uploaded, lod_levels - 1) << "frame " << frames;
      EXPECT_EQ(s.impostor, nullptr);
    }
  }
  EXPECT_EQ(frames, 8 + 3);
  EXPECT_EQ(s.atlas_frames, 8 + 3);
  EXPECT_EQ(s.wanted, lod_levels);
  ASSERT_EQ(s.uploaded, lod_levels);
  ASSERT_NE(s.impostor, nullptr);
  EXPECT_EQ(s.impostor->sets.size(), size_t(8));
  EXPECT_EQ(r.cards, s.impostor);
  EXPECT_EQ(r.leaf_end.back(), 2u);                    // the camera's card and the sun's
  EXPECT_EQ(r.index_end.back(), 0u);                   // no bark
  draw_frame(r, rp, cam, 64, 64);                      // leaf layers are updated by the next frame
  EXPECT_EQ(r.leaf_layers, leaf_archetype_count + 8);   // the views after the archetypes
  EXPECT_NE(editor_lod_status(s).find("Impostor"), std::string::npos) << editor_lod_status(s);
  // The LOD view's counts are the file's (issue 54): the chain built for an export of this tree
  // holds the same triangles, and the status shows them as `sylva export --lods` prints them.
  const lod_chain exported = build_lods(t, m, p.mesh, rp.lod);
  EXPECT_EQ(s.chain->triangles, exported.triangles);
  EXPECT_EQ(exported.triangles[0], final_triangles(m));
  EXPECT_NE(editor_lod_status(s).find(lod_summary(exported)), std::string::npos) << editor_lod_status(s);
  // Turning the camera by half a view re-uploads the card with the next view.
  const uint64_t uploads = r.uploads_total;
  editor_lod_update(s, r, g, rp, cam, t.steps);
  EXPECT_EQ(r.uploads_total, uploads);                 // unchanged camera: nothing uploaded
  cam.yaw = 10 + 45;
  editor_lod_update(s, r, g, rp, cam, t.steps);
  EXPECT_GT(r.uploads_total, uploads);
  // The sun turning by a degree re-uploads the cards (the shadow card faces the sun).
  const uint64_t still = r.uploads_total;
  rp.sun_azimuth += 2;
  editor_lod_update(s, r, g, rp, cam, t.steps);
  EXPECT_GT(r.uploads_total, still);
  // A new leaf colour renders the atlas again, over frames: LOD3 until it is complete.
  const auto before = s.impostor;
  rp.leaf_color = glm::vec3(0.8f, 0.2f, 0.1f);
  editor_lod_update(s, r, g, rp, cam, t.steps);
  EXPECT_EQ(s.impostor, nullptr);
  EXPECT_EQ(s.uploaded, lod_levels - 1);
  for (int k = 0; k < 20 && !s.impostor; ++k) editor_lod_update(s, r, g, rp, cam, t.steps);
  EXPECT_NE(s.impostor, nullptr);
  EXPECT_NE(s.impostor, before);
  EXPECT_EQ(s.uploaded, lod_levels);
  // Autumn renders it again too: the impostor shows the season's leaves, not summer's.
  const auto summer = s.impostor;
  rp.season = leaf_season::autumn;
  editor_lod_update(s, r, g, rp, cam, t.steps);
  EXPECT_EQ(s.impostor, nullptr);
  for (int k = 0; k < 20 && !s.impostor; ++k) editor_lod_update(s, r, g, rp, cam, t.steps);
  EXPECT_NE(s.impostor, nullptr);
  EXPECT_NE(s.impostor, summer);
  // Near the tree LOD0 returns; "Show LOD" 4 brings the impostor back at any distance.
  cam.distance = 2 * glm::length(m.bounds_max - m.bounds_min);
  editor_lod_update(s, r, g, rp, cam, t.steps);
  EXPECT_LT(s.uploaded, lod_levels);
  rp.lod.show = 4;
  editor_lod_update(s, r, g, rp, cam, t.steps);
  EXPECT_EQ(s.uploaded, lod_levels);
  // Scrubbing the growth shows LOD0.
  editor_lod_update(s, r, g, rp, cam, t.steps - 1);
  EXPECT_EQ(s.uploaded, 0);
}

// The atlas's state machine: complete only after every view; a new tree drops a half-built atlas and
// starts again; "Show LOD" 4 finishes a build in progress at once; near the tree nothing is built.
TEST_F(LodEditor, AtlasIsBuiltOverFramesRestartsForANewTreeAndShowLod4ForcesIt) {
  auto [p, t, m] = show_preset("species_cedar");
  const auto g = as_result(p, t, m);
  render_params rp = p.render;
  rp.lod.impostor_size = 64;
  editor_lod s;
  orbit_camera cam;
  cam.target = 0.5f * (m.bounds_min + m.bounds_max);
  // Near: LOD0, no atlas work.
  cam.distance = 2 * glm::length(m.bounds_max - m.bounds_min);
  for (int k = 0; k < 3; ++k) editor_lod_update(s, r, g, rp, cam, t.steps);
  EXPECT_EQ(s.build.st, impostor_build::state::idle);
  EXPECT_EQ(s.impostor, nullptr);
  if (!s.chain) {   // the chain is built off the UI thread; the next update takes it
    ASSERT_TRUE(editor_lod_wait(s, 120000));
  }
  // Far: begin, then one view per frame.
  cam.distance = 1000;
  editor_lod_update(s, r, g, rp, cam, t.steps);
  EXPECT_EQ(s.build.st, impostor_build::state::rendering);
  EXPECT_EQ(s.build.next, 0);
  for (int k = 1; k <= 5; ++k) {
    editor_lod_update(s, r, g, rp, cam, t.steps);
    EXPECT_EQ(s.build.next, k);
    EXPECT_EQ(s.impostor, nullptr);
    EXPECT_EQ(s.uploaded, lod_levels - 1);
  }
  EXPECT_NE(editor_lod_status(s).find("impostor atlas: 5 of 8 views"), std::string::npos) << editor_lod_status(s);
  // A new tree drops the half-built atlas; once settled the build starts from view 0.
  editor_lod_new_tree(s);
  EXPECT_EQ(s.build.st, impostor_build::state::idle);
  EXPECT_EQ(s.build.next, 0);
  EXPECT_EQ(s.impostor, nullptr);
  s.tree_time = {};   // skip the settling time
  editor_lod_update(s, r, g, rp, cam, t.steps);   // asks for the chain; LOD0 until it arrives
  EXPECT_EQ(s.build.st, impostor_build::state::idle);
  ASSERT_TRUE(editor_lod_wait(s, 120000));
  editor_lod_update(s, r, g, rp, cam, t.steps);
  EXPECT_EQ(s.build.st, impostor_build::state::rendering);
  EXPECT_EQ(s.build.next, 0);
  editor_lod_update(s, r, g, rp, cam, t.steps);
  EXPECT_EQ(s.build.next, 1);
  // "Show LOD" 4 completes it in the same frame and shows it.
  rp.lod.show = 4;
  editor_lod_update(s, r, g, rp, cam, t.steps);
  ASSERT_NE(s.impostor, nullptr);
  EXPECT_EQ(s.impostor->sets.size(), size_t(8));
  EXPECT_EQ(s.build.st, impostor_build::state::idle);
  EXPECT_EQ(s.atlas_frames, 3);   // begin, one view, then the rest at once
  EXPECT_EQ(s.uploaded, lod_levels);
  EXPECT_EQ(r.leaf_end.back(), 2u);
}
