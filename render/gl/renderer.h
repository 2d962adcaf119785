// The frame renderer (docs/design/08-renderer.md): shadow -> lit (physical sky, ground, tree) -> light
// shafts (volumetric ray march at half resolution, or occlusion + radial blur) -> auto exposure ->
// composite with fog and tonemap.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "generators/skeleton.h"
#include "render/camera.h"   // orbit_camera: draw_frame's view
#include "render/gl/gl_shared.h"
#include "render/gl/gl_util.h"
#include "render/gl/overlays.h"
#include "render/mesh/mesh.h"
#include "render/mesh/render_params.h"
#include "render/gl/sky.h"
#include "render/gl/wind_gl.h"   // upload_wind, set by every caller of upload_tree that shows wind

namespace sylva {

// Milliseconds per pass (with measure_passes): occlusion + blur are the radial shafts, march the
// volumetric ones, exposure the auto-exposure reduction; a pass that did not run reads 0.
struct pass_timings { double shadow = 0, lit = 0, occlusion = 0, blur = 0, march = 0, exposure = 0, composite = 0; };

// What the last draw_frame issued, so that tests and `sylva bench --render` can check that leaves
// stay one instanced call per pass and that an unchanged frame uploads nothing.
struct frame_counts {
  int draw_calls = 0;        // every glDraw* of the frame
  int leaf_draw_calls = 0;   // of which leaf draws (one instanced call per pass, whatever the leaf count)
  int uploads = 0;           // GL data uploads or storage (re)allocations made inside the frame
  int wind_motions = 0;      // wind motions computed (render/gl/wind_gl.h): one per frame, whatever the programs
};

// What one tree holds on the GPU: its buffers and vertex arrays, the per-node radius and wind
// tables, its overlays' buffers, and its own textures where they are not its context's shared
// procedural ones (the user's PNGs, a LOD level's baked cards). Every renderer has one.
struct tree_gpu {
  gl_vertex_array bark_vao, leaf_vao;
  gl_buffer bark_position, bark_normal, bark_uv, bark_node, bark_ao, bark_index, leaf_corner, leaf_instances, node_radius;
  gl_texture node_radius_tex;
  // The leaves' blade grids (render/mesh/leaf_blade.h): their triangles (bound to leaf_vao) and the
  // table of every prototype's vertices the leaf vertex shader reads, for the shape shown.
  gl_buffer blade_index, blade_table;
  gl_texture blade_tex;
  leaf_blade_shape blade_shown;
  bool blade_flat_shown = false, blade_uploaded = false;
  bool has_shoots = false;   // some leaf is a needle shoot's archetype (render/mesh/leaf_shoot.h): a second call draws them
  // The textures the tree is drawn with: the shared procedural maps (gl_shared), or its own when
  // own_bark / own_leaves (then freed with it).
  gl_texture bark_tex, bark_normal_tex, bark_rough_tex, leaf_tex, leaf_normal_tex, leaf_thickness_tex;
  bool own_bark = false, own_leaves = false;
  int leaf_layers = 1;
  // Textures: the user's PNG paths as last loaded, and why a load failed ("" when none).
  std::string bark_texture_path, leaf_texture_path, leaf_opacity_path, texture_message;
  bool user_bark = false, user_leaf = false;
  int user_texture_loads = 0;         // user texture files read so far (bark, leaf, opacity)
  int bark_shown = -1;                // the bark archetype shown; -1 none or the user's texture
  // LOD levels' baked cluster cards (render/mesh/lod_cards.h): layers after the archetypes' in the leaf arrays.
  std::shared_ptr<const baked_card_textures> cards;
  const void* cards_shown = nullptr;
  // The uploaded tree.
  std::vector<uint32_t> index_end, leaf_end;
  std::vector<float> final_radius;
  std::vector<float> radius_upload;   // reused scratch: (bend offset xyz, shown - built radius) per node
  int steps = 0, step = 0, node_count = 0;
  glm::vec3 bounds_min{-1, 0, -1}, bounds_max{1, 2, 1};
  glm::vec3 crown_centre{0, 1, 0}, crown_radii{1};   // the leaves' ellipsoid (render/mesh/leaf_shading.h)
  bool has_tree = false;
  glm::vec3 root{0};                  // centre of the trunk's base ring, and its radius (ground contact)
  float root_radius = 0.1f;
  overlay_gpu overlay;                // growth-debug overlays (render/gl/overlays.h); what shows is the caller's overlay_view
  // Wind (render/gl/wind_gl.h): per-node sway data uploaded once per tree; the time is a uniform.
  gl_buffer wind_nodes;
  gl_texture wind_tex;
  int wind_node_count = 0;
  float wind_ground = 0, wind_height = 1;
};

// A renderer: its tree (tree_gpu), the programs and procedural textures of its GL context
// (gl_shared, held with every other renderer there) and its own frame: render targets, the sky,
// the wind's clock and the measurements.
struct renderer_gpu : tree_gpu {
  bool ok = false;
  std::string error;
  std::shared_ptr<gl_shared> shared;   // the context's programs and procedural textures
  gl_vertex_array empty_vao;
  gl_texture shadow_tex, hdr_color, hdr_depth, occlusion_tex, rays_tex, march_tex, average_tex;
  gl_framebuffer shadow_fbo, hdr_fbo, occlusion_fbo, rays_fbo, march_fbo, average_fbo, msaa_fbo;
  gl_renderbuffer msaa_color, msaa_depth;   // multisampled lit pass, resolved into hdr_color/hdr_depth
  int shadow_size = 0, width = 0, height = 0, samples = 0;
  // The sky (render/gl/sky.h), recomputed only when the parameters it depends on change.
  sky_model daylight;
  render_params sky_inputs;
  bool sky_valid = false;
  // Measurements.
  bool measure_passes = false;        // glFinish after each pass to time it (benchmarks only)
  pass_timings timings;
  size_t triangles_drawn = 0, leaves_drawn = 0;
  frame_counts counts;                // of the last draw_frame
  uint64_t uploads_total = 0;         // every glBufferData/SubData, glTexImage* and storage call so far
  float wind_time = 0;                // seconds; the editor advances it, exports and tests set it
  // The shadow map of an earlier frame is used again (no shadow pass) while this is set and one
  // has been drawn since the tree, its step or the map's size last changed: the editor's cheaper
  // view while the user drags (app/editor/view_quality.h).
  bool keep_shadow = false;
  bool shadow_drawn = false;
  float wind_reach = 0;               // metres the sway may carry the tree past its bounds (shadow fit)
};

// Sets up a renderer in the current GL 3.3 core context. `shared`: the programs and procedural
// textures of another renderer in this context (its `shared`), so nothing is compiled again; none
// compiles a new set for this renderer (and any given it later).
bool init_renderer(renderer_gpu& r, std::shared_ptr<gl_shared> shared = nullptr);
// Frees the renderer's objects, and its context's shared set when it is the last renderer holding it.
void destroy_renderer(renderer_gpu& r);

// Uploads a meshed tree; the scrub position is then set with set_tree_step.
void upload_tree(renderer_gpu& r, const tree_mesh& m);

// Points attributes 1-7 (position, orientation, size, born/died, texture, occlusion, node; one per
// instance) at the bound GL_ARRAY_BUFFER of leaf_instance records, in the bound vertex array.
void leaf_instance_attributes();
// Shows the tree as it stood at `step`: draw counts plus one small per-node upload (radius and, for
// a bent tree, the bend of that step replayed by positions_at_step).
void set_tree_step(renderer_gpu& r, const tree_skeleton& t, float min_radius, int step);
// The tree's growth-debug overlays, built with it on the worker (null clears them). No GL work
// here: they are uploaded by the first draw_frame that shows them.
void set_overlays(renderer_gpu& r, std::shared_ptr<const overlay_geometry> g);

// Draws one frame into `target` (id 0: the window). `overlays`, when given, draws the growth-debug
// layers it chooses (UI state, kept by the editor).
// `origin` places the image inside the target (the editor's viewport beside its panels).
void draw_frame(renderer_gpu& r, const render_params& p, const orbit_camera& cam, int width, int height,
                gl_framebuffer target = {}, const overlay_view* overlays = nullptr, glm::ivec2 origin = {0, 0});

}  // namespace sylva
