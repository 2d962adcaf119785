// Impostor atlas: the tree seen from 8 or 16 directions around its trunk, rendered
// off-screen by Sylva's renderer into one atlas of colour with alpha and one of normals.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "render/gl/renderer.h"
#include "render/mesh/lod_cards.h"

namespace sylva {

struct impostor_atlas {
  int views = 0, columns = 0, rows = 0;
  int cell = 0;                          // pixels per view (square)
  int width = 0, height = 0;             // atlas pixels: columns * cell x rows * cell
  std::vector<unsigned char> color;      // RGBA8, rows top to bottom: sRGB albedo, alpha = coverage
  std::vector<unsigned char> normal;     // RGBA8: world-space unit normal * 0.5 + 0.5, alpha = coverage
  float cell_metres = 0;                 // world size one cell spans (square, orthographic)
  glm::vec3 centre{0};                   // world point at the centre of every cell
  double ms = 0;                         // time to render and read back
  std::string error;                     // "" on success
};

// Renders the atlas of the tree uploaded to `r` (upload_tree; its final step). View k looks at the
// tree from azimuth 360 k / views degrees (from +Z toward +X), orthographic, level, cell k at
// column k % columns, row k / columns from the top (4 columns). `views` is 8 or 16 (others round
// to the nearer one); `cell` is clamped to 16..2048. Needs a current GL context.
impostor_atlas render_impostor(renderer_gpu& r, const render_params& rp, int views, int cell);

// The atlas built a view at a time (no pause): impostor_begin prepares the target (and,
// given a mesh, copies it into the build's own buffers, so the renderer may show another level
// meanwhile); each impostor_step renders one view, and the step after the last reads the atlas back.
// So the editor spreads the work over frames and never stalls for the whole atlas.
struct impostor_build {
  enum class state { idle, rendering, complete, failed };
  state st = state::idle;
  int next = 0;                    // views rendered so far
  impostor_atlas atlas;            // size and framing from begin; pixels (or the error) once complete
  render_params rp;                // tints and cut-off the views are drawn with
  double ms = 0, worst_step_ms = 0;   // all steps so far, and the longest one (begin counts as one)
  // GL objects, freed when the atlas is read back or the build is cancelled (the programs are the
  // context's: render/gl/gl_shared.h).
  gl_program bark, leaf;
  gl_texture color, normal;
  gl_renderbuffer depth;
  gl_framebuffer fbo;
  gl_vertex_array bark_vao, leaf_vao;
  gl_buffer position, normal_buf, uv, index, corner, instances;
  bool own_mesh = false;
  uint32_t bark_count = 0, leaf_count = 0;
  int steps = 0;
};
// Starts a build of the tree `m` (null: the tree uploaded to `r`, which must then stay uploaded
// until the build completes). Returns "" or the error (state failed). Needs a current GL context;
// `r` lends its bark and leaf textures at every step.
std::string impostor_begin(impostor_build& b, renderer_gpu& r, const render_params& rp, int views, int cell,
                           const tree_mesh* m);
// One view, or the read-back after the last. True once the build is complete or failed.
bool impostor_step(impostor_build& b, renderer_gpu& r);
// Drops a build in progress (a new tree) and frees its GL objects; the state is idle again.
void impostor_cancel(impostor_build& b);

// Writes the two atlases as PNG bytes ("" or the error).
std::string impostor_pngs(const impostor_atlas& a, std::string& color_png, std::string& normal_png);

// The impostor as the viewport draws it: one card of the renderer's leaf pipeline, so it
// is lit from the atlas's normals, shadowed and fogged as the tree is. The atlas views become leaf
// layers (colour final: leaf_instance::texture >= impostor_texture_base skips the leaf tint; normals
// turned into each view's card frame); the card turns about the vertical to face the camera and
// shows the view nearest the camera's azimuth.
inline constexpr int impostor_texture_base = 128;
std::shared_ptr<const baked_card_textures> impostor_layers(const impostor_atlas& a);
// View index for a camera at azimuth `azimuth_deg` (degrees from +Z toward +X, as the atlas's).
int impostor_view(const impostor_atlas& a, float azimuth_deg);
// A mesh of two cards: `like`'s steps, node radii and bounds, no bark. The first faces `azimuth_deg`
// (the camera) and is drawn by the lit pass only; the second, texture + impostor_sun_card, faces
// `sun_azimuth_deg` with the view nearest the sun and is drawn by the shadow pass only, so the
// ground shadow keeps the crown's shape whatever the camera.
inline constexpr int impostor_sun_card = 64;
tree_mesh impostor_mesh(const impostor_atlas& a, std::shared_ptr<const baked_card_textures> layers, const tree_mesh& like,
                        float azimuth_deg, float sun_azimuth_deg);
// The sun's azimuth in the atlas's convention (degrees from +Z toward +X).
float impostor_sun_azimuth(const render_params& rp);

}  // namespace sylva
