// The editor's level choice with the impostor (issue 17, app/editor_lod.h): far away the renderer
// holds one camera-facing card showing the nearest atlas view, "Show LOD" 4 asks for it anywhere,
// and near the tree LOD0 comes back.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "app/editor_lod.h"
#include "generators/tree_spec.h"
#include "gl_test_context.h"
#include "render/preset.h"

using namespace sylva;

namespace {
class LodEditor : public sylva_test::renderer_test {};
}  // namespace

TEST_F(LodEditor, FarAwayTheImpostorCardStandsInAndTurnsWithTheCamera) {
  preset p;
  ASSERT_TRUE(load_preset_file(std::string(SYLVA_SOURCE_DIR) + "/presets/species_cedar.json", p).ok);
  const tree_skeleton t = grow(p.spec, grow_options{});
  const tree_mesh m = mesh_tree(t, p.mesh, p.spec.seed);
  upload_tree(r, m);
  set_tree_step(r, t, p.mesh.min_radius, t.steps);
  render_params rp = p.render;
  rp.lod.impostor_size = 128;
  editor_lod s;   // no editor_lod_new_tree: the chain is built on the first update
  orbit_camera cam;
  cam.target = 0.5f * (m.bounds_min + m.bounds_max);
  cam.distance = 1000;   // far below LOD3's coverage
  cam.yaw = 10;
  editor_lod_update(s, r, t, m, p.mesh, rp, cam, t.steps);
  ASSERT_NE(s.chain, nullptr);
  EXPECT_EQ(s.wanted, lod_levels);
  ASSERT_EQ(s.impostor_error, "");
  ASSERT_EQ(s.uploaded, lod_levels);
  ASSERT_NE(s.impostor, nullptr);
  EXPECT_EQ(s.impostor->sets.size(), size_t(8));
  EXPECT_EQ(r.cards, s.impostor);
  EXPECT_EQ(r.leaf_end.back(), 1u);                    // one card
  EXPECT_EQ(r.index_end.back(), 0u);                   // no bark
  draw_frame(r, rp, cam, 64, 64);                      // leaf layers are updated by the next frame
  EXPECT_EQ(r.leaf_layers, leaf_archetype_count + 8);   // the views after the archetypes
  EXPECT_NE(editor_lod_status(s).find("Impostor"), std::string::npos) << editor_lod_status(s);
  // Turning the camera by half a view re-uploads the card with the next view.
  const uint64_t uploads = r.uploads_total;
  editor_lod_update(s, r, t, m, p.mesh, rp, cam, t.steps);
  EXPECT_EQ(r.uploads_total, uploads);                 // unchanged camera: nothing uploaded
  cam.yaw = 10 + 45;
  editor_lod_update(s, r, t, m, p.mesh, rp, cam, t.steps);
  EXPECT_GT(r.uploads_total, uploads);
  // A new leaf colour renders the atlas again.
  const auto before = s.impostor;
  rp.leaf_color = glm::vec3(0.8f, 0.2f, 0.1f);
  editor_lod_update(s, r, t, m, p.mesh, rp, cam, t.steps);
  EXPECT_NE(s.impostor, before);
  EXPECT_EQ(s.uploaded, lod_levels);
  // Near the tree LOD0 returns; "Show LOD" 4 brings the impostor back at any distance.
  cam.distance = 2 * glm::length(m.bounds_max - m.bounds_min);
  editor_lod_update(s, r, t, m, p.mesh, rp, cam, t.steps);
  EXPECT_LT(s.uploaded, lod_levels);
  rp.lod.show = 4;
  editor_lod_update(s, r, t, m, p.mesh, rp, cam, t.steps);
  EXPECT_EQ(s.uploaded, lod_levels);
  // Scrubbing the growth shows LOD0.
  editor_lod_update(s, r, t, m, p.mesh, rp, cam, t.steps - 1);
  EXPECT_EQ(s.uploaded, 0);
}
