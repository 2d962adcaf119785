// Wind in the viewport: the per-node sway table as a buffer texture, and the uniforms
// of render/mesh/wind.h's GLSL. The bark and leaf programs (lit and shadow) all sway; nothing is
// re-uploaded per frame and no draw call is added.
#pragma once

#include "generators/skeleton.h"
#include "render/gl/gl_util.h"
#include "render/mesh/render_params.h"
#include "render/mesh/wind.h"

namespace sylva {

struct renderer_gpu;

// Builds the tree's wind_rig and uploads it (3 RGBA32F texels per node). Call after upload_tree
// with the skeleton the mesh was built from; until then (or for an empty tree) nothing sways.
void upload_wind(renderer_gpu& r, const tree_skeleton& t);

// The vertex shader source with render/mesh/wind.h's GLSL inserted after its #version line.
std::string with_wind_glsl(const char* vertex_src);

// The wind of one frame: render/mesh/wind.h's motion at r.wind_time, computed once per frame (counted
// in r.counts.wind_motions) and then set on every program that sways.
struct wind_frame {
  wind_motion motion;
  bool on = false;     // the wind blows and the tree's sway table is uploaded
  float time = 0, gust = 1, trunk = 0;
};
wind_frame wind_frame_of(renderer_gpu& r, const render_params& rp);

// How far (metres) the sway can carry any point past the tree's rest bounds, for the sun's shadow
// frustum; 0 while the wind is off. Bounded by the motion's caps (render/mesh/wind.h).
float wind_reach(const renderer_gpu& r, const wind_frame& w);

// Sets the wind uniforms of program `p` for this frame; binds the table to unit 8.
void set_wind_uniforms(const renderer_gpu& r, const gl_program& p, const wind_frame& w);

}  // namespace sylva
