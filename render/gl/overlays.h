// Growth-debug overlays on the GPU: the geometry built on the worker (render/mesh/overlay_geometry.h),
// uploaded when first shown, each kind with a View toggle, filtered by the timeline step on the GPU.
#pragma once

#include <cstdint>
#include <memory>

#include <glm/mat4x4.hpp>

#include "render/gl/gl_util.h"
#include "render/mesh/overlay_geometry.h"

namespace sylva {

// GL side: one program, one buffer, two draws. Main thread only.
struct overlay_gpu : overlay_ranges {   // the ranges of the geometry set last
  gl_program program;   // the context's (render/gl/gl_shared.h), not this tree's to free
  gl_vertex_array vao;
  gl_buffer vertices;
  int line_vertices = 0, point_vertices = 0;
  std::shared_ptr<const overlay_geometry> geometry;   // the shown tree's; uploaded when `stale` and drawn
  bool stale = false;
};

// The overlays' program, compiled once per GL context (render/gl/gl_shared.h).
gl_program compile_overlay_program();
// A tree's overlay buffers, drawn with `program` (compile_overlay_program's).
bool init_overlays(overlay_gpu& g, const gl_program& program);
void destroy_overlays(overlay_gpu& g);   // the buffers; the program stays with its context
// Takes a tree's overlays without touching GL (null: none); the upload waits for sync_overlays,
// so that hidden overlays cost nothing per tree.
void set_overlays(overlay_gpu& g, std::shared_ptr<const overlay_geometry> geo);
// Uploads the geometry set last if it is not on the GPU yet; returns whether it uploaded.
bool sync_overlays(overlay_gpu& g);
// Draws the kinds `v` shows into the bound framebuffer with the current depth buffer; returns the
// draw calls issued.
int draw_overlays(const overlay_gpu& g, const overlay_view& v, const glm::mat4& viewproj, int step);

}  // namespace sylva
