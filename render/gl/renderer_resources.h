// The renderer's GPU resources: the procedural leaf and bark archetypes and the user's own PNGs
// (leaf cards with alpha-coverage-preserving mipmaps), and the render targets of the passes.
#pragma once

#include "render/gl/renderer.h"
#include "render/mesh/render_params.h"

namespace sylva {

// The leaf archetypes' colour, normal and thickness arrays (the context's shared ones), or with a LOD
// level's baked cards after them (the tree's own).
void upload_procedural_leaves(renderer_gpu& r);
// The procedural bark archetype's colour, normal and roughness maps (the context's shared ones).
void upload_procedural_bark(renderer_gpu& r, bark_archetype a);
// Frees the tree's own textures (not its context's shared ones) and forgets the ones it drew with.
void release_tree_textures(renderer_gpu& r);
// Loads the user's bark and leaf PNGs when their paths change (a file that cannot be used is
// reported and the procedural texture stays); re-uploads the archetypes as needed.
void update_user_textures(renderer_gpu& r, const render_params& rp);
// The blade table (render/mesh/leaf_blade.h) for `shape`: every archetype's grid cut to its
// picture's outline, or every grid the flat card while the user's leaf picture shows; uploads only
// when the shape or that choice changes.
void upload_blades(renderer_gpu& r, const leaf_blade_shape& shape);
// The uniforms of glsl::bark_tint_glsl (the bark's tint by height) on program p, which is in use.
void set_bark_tint_uniforms(const gl_program& p, const render_params& rp);

// Render targets: a colour texture, a framebuffer of colour + depth, a depth texture (with
// comparison for the shadow map); the frame's targets at a size and sample count; the shadow map.
gl_texture make_color_target(int w, int h, GLenum internal_format);
gl_framebuffer make_framebuffer(const gl_texture& color, const gl_texture& depth);
gl_texture make_depth_texture(int w, int h, bool compare);
void resize_targets(renderer_gpu& r, int w, int h, int samples);
void resize_shadow(renderer_gpu& r, int size);

}  // namespace sylva
