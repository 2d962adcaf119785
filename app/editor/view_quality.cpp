// The cheaper 3D view while the user interacts (app/editor/view_quality.h).
#include "app/editor/view_quality.h"

#include <algorithm>

#include <epoxy/gl.h>
#include <imgui.h>

namespace sylva {

bool interacting(const ImGuiIO& io, bool item_active, int keys_fed) {
  const bool held = io.MouseDown[0] || io.MouseDown[1] || io.MouseDown[2];
  return (held && (item_active || !io.WantCaptureMouse)) || (keys_fed > 0 && io.WantTextInput);
}

render_params interactive_params(const render_params& rp) {
  render_params p = rp;
  p.shafts = light_shafts::off;
  p.msaa = 0;
  return p;
}

bool draw_interactive(interactive_view& v, renderer_gpu& r, const render_params& rp, const orbit_camera& cam, int vx,
                      int vy, int vw, int vh, const overlay_view* overlays) {
  const int w = std::max(16, vw / 2), h = std::max(16, vh / 2);
  if (v.width != w || v.height != h) {
    free_interactive(v);
    if (!create_color_target(w, h, v.color, v.fbo).empty()) {
      free_interactive(v);
      return false;
    }
    v.width = w, v.height = h;
  }
  r.keep_shadow = true;
  draw_frame(r, interactive_params(rp), cam, w, h, v.fbo, overlays);
  r.keep_shadow = false;
  glBindFramebuffer(GL_READ_FRAMEBUFFER, v.fbo.id);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  glBlitFramebuffer(0, 0, w, h, vx, vy, vx + vw, vy + vh, GL_COLOR_BUFFER_BIT, GL_LINEAR);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  return true;
}

bool view_key::operator==(const view_key& o) const {
  return renderer == o.renderer && uploads == o.uploads && target == o.target && distance == o.distance && yaw == o.yaw &&
         pitch == o.pitch && fov == o.fov && render == o.render && show_overlays == o.show_overlays &&
         overlay_geometry == o.overlay_geometry &&
         (!show_overlays || (overlays.kinds == o.overlays.kinds && overlays.combine == o.overlays.combine &&
                             overlays.shadow_slice == o.overlays.shadow_slice && overlays.slice_height == o.overlays.slice_height)) &&
         x == o.x && y == o.y && width == o.width && height == o.height;
}

view_key view_key_of(const renderer_gpu& r, const orbit_camera& cam, const render_params& rp, const overlay_view* overlays,
                     int x, int y, int w, int h) {
  view_key k;
  k.renderer = &r;
  k.uploads = r.uploads_total;
  k.target = cam.target, k.distance = cam.distance, k.yaw = cam.yaw, k.pitch = cam.pitch, k.fov = cam.fov;
  k.render = rp;
  k.show_overlays = overlays != nullptr;
  if (overlays) k.overlays = *overlays;
  if (overlays) k.overlay_geometry = r.overlay.geometry.get(), k.overlays_stale = r.overlay.stale;
  k.x = x, k.y = y, k.width = w, k.height = h;
  return k;
}

bool show_kept_view(view_cache& c, const view_key& k) {
  if (!c.valid || !(c.key == k) || k.render.wind.enabled || k.overlays_stale) return false;
  glBindFramebuffer(GL_READ_FRAMEBUFFER, c.fbo.id);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  glBlitFramebuffer(0, 0, k.width, k.height, k.x, k.y, k.x + k.width, k.y + k.height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  return true;
}

void keep_view(view_cache& c, const view_key& k) {
  c.valid = false;
  if (c.width != k.width || c.height != k.height) {
    free_view_cache(c);
    if (!create_color_target(k.width, k.height, c.color, c.fbo).empty()) return free_view_cache(c);
    c.width = k.width, c.height = k.height;
  }
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, c.fbo.id);
  glBlitFramebuffer(k.x, k.y, k.x + k.width, k.y + k.height, 0, 0, k.width, k.height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  c.key = k;
  c.valid = true;
}

void free_view_cache(view_cache& c) {
  delete_gl(c.fbo);
  delete_gl(c.color);
  c.width = c.height = 0;
  c.valid = false;
}

void free_interactive(interactive_view& v) {
  delete_gl(v.fbo);
  delete_gl(v.color);
  v.width = v.height = 0;
}

}  // namespace sylva
