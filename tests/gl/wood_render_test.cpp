// Scrubbing a bent tree: the viewport shows the bend of the shown step through the
// per-node buffer, without re-meshing, and matches the export of that step. GL: runs under Xvfb.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include <epoxy/gl.h>

#include "generators/tree_spec.h"
#include "render/gl/renderer.h"
#include "render/mesh/mesh.h"
#include "tests/gl/gl_test_context.h"

using namespace sylva;
using WoodRender = sylva_test::renderer_test;

namespace {

using byte_target = sylva_test::color_target<unsigned char>;

// Pixels whose colour differs by more than a small threshold.
int differing(const std::vector<unsigned char>& a, const std::vector<unsigned char>& b) {
  int n = 0;
  for (size_t i = 0; i + 3 < a.size(); i += 4)
    n += std::abs(a[i] - b[i]) + std::abs(a[i + 1] - b[i + 1]) + std::abs(a[i + 2] - b[i + 2]) > 24;
  return n;
}

}  // namespace

TEST_F(WoodRender, ScrubbingShowsTheBendOfTheStepLikeItsExport) {
  tree_spec spec;
  self_organizing_params so;
  so.steps = 16;
  spec.params = so;
  spec.wood.gravity = 3;   // a clear sag
  const tree_skeleton t = grow(spec, {});
  ASSERT_NE(t.wood, nullptr);
  mesh_params mp;
  mp.leaves_enabled = false;   // bark only: leaves' cards face differently in the two paths
  // The bend alone: gnarl grows with age and the collar/flare swell is sized for the final tree
  // (render/mesh/mesh.h), so a younger tree's re-mesh differs from the scrubbed final mesh by those too.
  mp.gnarl = 0;
  mp.collar = 0;
  mp.flare_strength = 0;
  mp.caps = false;
  const tree_mesh full = mesh_tree(t, mp);
  const int step = t.steps * 2 / 3;

  render_params rp;
  rp.shadows = false;
  rp.shafts = light_shafts::off;
  rp.ground = false;
  orbit_camera cam;
  frame_camera(cam, full.bounds_min, full.bounds_max, 1.0f);
  const int w = 256, h = 256;
  byte_target target(w, h);
  auto shot = [&](const tree_mesh& m, const tree_skeleton& s, int at) {
    upload_tree(r, m);
    set_tree_step(r, s, mp.min_radius, at);
    draw_frame(r, rp, cam, w, h, target.fbo);
    return target.read();
  };
  // The viewport: the final mesh, scrubbed to `step`.
  const std::vector<unsigned char> scrubbed = shot(full, t, step);
  // The export of that step: re-meshed from skeleton_at_step, nothing left to offset.
  const tree_skeleton at = skeleton_at_step(t, step);
  const std::vector<unsigned char> exported = shot(mesh_tree_at_step(t, full, mp, step), at, step);
  // The final mesh scrubbed without the bend of the step (the renderer before the bending pass).
  tree_skeleton unbent = t;
  unbent.wood.reset();
  const std::vector<unsigned char> no_bend = shot(full, unbent, step);
  const int d_scrub = differing(scrubbed, exported), d_plain = differing(no_bend, exported);
  std::printf("  pixels differing from the export of step %d: scrubbed %d, without the bend %d\n", step, d_scrub, d_plain);
  EXPECT_GT(d_plain, 200) << "the step's bend differs visibly from the final bend";
  EXPECT_LT(d_scrub * 4, d_plain) << "scrubbed " << d_scrub << " without the bend " << d_plain;
}
