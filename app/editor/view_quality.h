// The 3D view while the user drags a slider, orbits, pans or types: drawn cheaper, at half the
// resolution (scaled up), without light shafts or MSAA and with the last shadow map; the full
// picture comes back on the frame after release (docs/design/09-editor.md "Responsive on software GL").
#pragma once

#include "render/gl/gl_util.h"
#include "render/gl/overlays.h"
#include "render/gl/renderer.h"

struct ImGuiIO;

namespace sylva {

struct interactive_view {
  gl_texture color;
  gl_framebuffer fbo;
  int width = 0, height = 0;   // of the target (half the view's)
};

// Whether this frame is an interaction the view may draw cheaper for: a button held on an active
// item (a slider's drag) or on the 3D view (orbit, pan), or keys typed into a text field this frame.
bool interacting(const ImGuiIO& io, bool item_active, int keys_fed);

// The render settings of the cheaper view: no light shafts, no MSAA.
render_params interactive_params(const render_params& rp);

// Draws r's frame at half of (vw, vh) into v's target with the last shadow map, then scales it into
// the window's framebuffer at (vx, vy). False (nothing drawn) when the target cannot be made.
bool draw_interactive(interactive_view& v, renderer_gpu& r, const render_params& rp, const orbit_camera& cam, int vx,
                      int vy, int vw, int vh, const overlay_view* overlays);

void free_interactive(interactive_view& v);

// What the 3D view's picture depends on: when none of it changed since the last full frame, that
// frame is shown again (a blit) and the UI over it is never held back by a slow 3D frame (a hover,
// a menu, a dialog). Wind moves every frame and is never kept.
struct view_key {
  const renderer_gpu* renderer = nullptr;
  uint64_t uploads = 0;       // the renderer's uploads: a new tree, level, step or texture
  glm::vec3 target{0};
  float distance = 0, yaw = 0, pitch = 0, fov = 0;
  render_params render;
  bool show_overlays = false;
  overlay_view overlays;
  const void* overlay_geometry = nullptr;   // the overlays set last
  bool overlays_stale = false;              // set and not yet uploaded: the next frame draws in full
  int x = 0, y = 0, width = 0, height = 0;
  bool operator==(const view_key& o) const;
};
struct view_cache {
  gl_texture color;
  gl_framebuffer fbo;
  int width = 0, height = 0;
  bool valid = false;
  view_key key;
};
view_key view_key_of(const renderer_gpu& r, const orbit_camera& cam, const render_params& rp, const overlay_view* overlays,
                     int x, int y, int w, int h);
// Shows the kept picture when `k` matches it (true), else false and the caller draws.
bool show_kept_view(view_cache& c, const view_key& k);
// Keeps the picture just drawn at the key's place in the window, under `k` (taken after drawing).
void keep_view(view_cache& c, const view_key& k);
void free_view_cache(view_cache& c);

}  // namespace sylva
