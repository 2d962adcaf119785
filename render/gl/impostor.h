// Impostor atlas (issue 17): the tree seen from 8 or 16 directions around its trunk, rendered
// off-screen by Sylva's renderer into one atlas of colour with alpha and one of normals.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "render/gl/renderer.h"
#include "render/lod_cards.h"

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

// Writes the two atlases as PNG bytes ("" or the error).
std::string impostor_pngs(const impostor_atlas& a, std::string& color_png, std::string& normal_png);

// The impostor as the viewport draws it (issue 17): one card of the renderer's leaf pipeline, so it
// is lit from the atlas's normals, shadowed and fogged as the tree is. The atlas views become leaf
// layers (colour final: leaf_instance::texture >= impostor_texture_base skips the leaf tint; normals
// turned into each view's card frame); the card turns about the vertical to face the camera and
// shows the view nearest the camera's azimuth.
inline constexpr int impostor_texture_base = 128;
std::shared_ptr<const baked_card_textures> impostor_layers(const impostor_atlas& a);
// View index for a camera at azimuth `azimuth_deg` (degrees from +Z toward +X, as the atlas's).
int impostor_view(const impostor_atlas& a, float azimuth_deg);
// A mesh of one card: `like`'s steps, node radii and bounds, no bark; the card faces `azimuth_deg`.
tree_mesh impostor_mesh(const impostor_atlas& a, std::shared_ptr<const baked_card_textures> layers, const tree_mesh& like,
                        float azimuth_deg);

}  // namespace sylva
