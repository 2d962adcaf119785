// A/B comparison, the GL, worker and ImGui part. See app/editor/editor_ab.h.
#include "app/editor/editor_ab.h"

#include <algorithm>

#include <epoxy/gl.h>
#include <imgui.h>

#include "app/editor/editor_state.h"   // elide_text
#include "render/gl/overlays.h"
#include "render/gl/wind_gl.h"

namespace sylva {

namespace {

void show_result(slot_view& v, const std::shared_ptr<const grow_result>& r, int step,
                 std::shared_ptr<const overlay_geometry> overlays = {}) {
  v.shown = r;
  upload_tree(v.renderer, r->mesh);
  editor_lod_new_tree(v.lod);
  upload_wind(v.renderer, *r->skeleton);
  set_overlays(v.renderer, r->overlays ? r->overlays : std::move(overlays));
  set_tree_step(v.renderer, *r->skeleton, r->mesh_settings.min_radius, std::min(step, r->skeleton->steps));
}

}  // namespace

std::shared_ptr<const overlay_geometry> take_late_overlays(slot_view& v) {
  if (!v.worker || !v.shown || v.shown->overlays || v.renderer.overlay.geometry) return nullptr;
  return take_late_overlays(*v.worker, *v.shown);
}

std::string ab_start_view(slot_view& v, const std::shared_ptr<const grow_result>& shown, int step,
                          std::shared_ptr<gl_shared> shared, std::shared_ptr<const overlay_geometry> overlays) {
  ab_stop_view(v);
  v = slot_view{};
  v.worker = std::make_unique<worker_state>();
  start_worker(*v.worker);
  if (!init_renderer(v.renderer, std::move(shared))) return v.renderer.error;
  if (shown && shown->skeleton) {
    show_result(v, shown, step, std::move(overlays));
    v.posted_spec = shown->spec;
    v.posted_mesh = shown->mesh_settings;
    v.posted_once = true;
    v.overlay_generator = int(shown->spec.params.index());
  }
  return "";
}

void ab_stop_view(slot_view& v) {
  if (v.worker) stop_worker(*v.worker);
  v.worker.reset();
  if (v.renderer.ok) impostor_cancel(v.lod.build);   // a half-built impostor atlas too
  destroy_renderer(v.renderer);   // also what a failed init left
  v.renderer = renderer_gpu{};
  v.shown.reset();
  v.lod = editor_lod{};
}

void ab_poll_other(ab_state& s, int step) {
  if (!s.has_b || !s.other().worker) return;
  slot_view& v = s.other();
  if (std::shared_ptr<const overlay_geometry> geo = take_late_overlays(v)) set_overlays(v.renderer, std::move(geo));
  if (std::shared_ptr<const grow_result> r = take_result(*v.worker, v.seen_generation))
    if (ab_take_other_result(v, *r) == ab_result_use::show) show_result(v, r, step);
  if (v.shown && v.shown->skeleton) {
    const int st = std::clamp(step, 0, v.shown->skeleton->steps);
    if (st != v.renderer.step) set_tree_step(v.renderer, *v.shown->skeleton, v.shown->mesh_settings.min_radius, st);
  }
}

void ab_draw(ab_state& s, const orbit_camera& cam, int vx, int vy, int vw, int vh, const overlay_view* overlays) {
  renderer_gpu& selected = s.cur().renderer;
  renderer_gpu& other = s.other().renderer;
  const render_params& selected_render = s.cur().doc.render;
  // The same sun for both: the selected slot's.
  render_params other_p = s.other().doc.render;
  other_p.sun_azimuth = selected_render.sun_azimuth;
  other_p.sun_elevation = selected_render.sun_elevation;
  other.wind_time = selected.wind_time;
  renderer_gpu& a = s.slots[0].renderer;
  renderer_gpu& b = s.slots[1].renderer;
  const render_params& pa = s.selected == 0 ? selected_render : other_p;
  const render_params& pb = s.selected == 0 ? other_p : selected_render;
  const bool draw_b = other.ok;
  if (s.mode == ab_mode::side_by_side) {
    const int hw = std::max(1, vw / 2);
    draw_frame(a, pa, cam, hw, vh, {}, overlays, {vx, vy});
    if (draw_b) draw_frame(b, pb, cam, std::max(1, vw - hw), vh, {}, overlays, {vx + hw, vy});
    return;
  }
  // Split: A over the whole view, its left part kept, B over the whole view, A's part put back.
  const int cut = std::clamp(int(float(vw) * s.divider), 0, vw);
  draw_frame(a, pa, cam, vw, vh, {}, overlays, {vx, vy});
  if (!draw_b || cut >= vw) return;
  if (cut > 0) {
    if (s.keep_fbo == 0) {
      glGenFramebuffers(1, &s.keep_fbo);
      glGenRenderbuffers(1, &s.keep_color);
    }
    if (s.keep_w != vw || s.keep_h != vh) {
      glBindRenderbuffer(GL_RENDERBUFFER, s.keep_color);
      glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, vw, vh);
      glBindFramebuffer(GL_FRAMEBUFFER, s.keep_fbo);
      glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, s.keep_color);
      s.keep_w = vw, s.keep_h = vh;
    }
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, s.keep_fbo);
    glBlitFramebuffer(vx, vy, vx + cut, vy + vh, 0, 0, cut, vh, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  draw_frame(b, pb, cam, vw, vh, {}, overlays, {vx, vy});
  if (cut > 0) {
    glBindFramebuffer(GL_READ_FRAMEBUFFER, s.keep_fbo);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    glBlitFramebuffer(0, 0, cut, vh, vx, vy, vx + cut, vy + vh, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
  }
}

void ab_free_gl(ab_state& s) {
  ab_stop_view(s.slots[1]);
  ab_stop_view(s.slots[0]);
  if (s.keep_fbo) glDeleteFramebuffers(1, &s.keep_fbo);
  if (s.keep_color) glDeleteRenderbuffers(1, &s.keep_color);
  s.keep_fbo = s.keep_color = 0;
  s.keep_w = s.keep_h = 0;
}

ab_action draw_ab_controls(ab_state& s) {
  ab_action act = ab_action::none;
  ImGui::AlignTextToFramePadding();
  ImGui::TextUnformatted("A/B");
  ImGui::SameLine();
  if (!s.has_b || s.selected == 0) {
    if (ImGui::SmallButton(s.has_b ? "Duplicate to B (replace)" : "Duplicate to B")) act = ab_action::duplicate;
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("Copies this tree (spec, mesh, render) into slot B to compare; edit either slot");
  }
  if (s.has_b) {
    ImGui::SameLine();
    int sel = s.selected;
    if (ImGui::RadioButton("Edit A", &sel, 0) && s.selected != 0) act = ab_action::select_a;
    ImGui::SameLine();
    if (ImGui::RadioButton("Edit B", &sel, 1) && s.selected != 1) act = ab_action::select_b;
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("The panel, undo, Save and Export act on the selected slot; each slot has its own undo history");
    ImGui::SameLine();
    if (ImGui::SmallButton("Drop B")) act = ab_action::drop;
    int m = int(s.mode);
    const char* labels[] = {"off", "side by side", "split"};
    ImGui::SetNextItemWidth(140);
    if (ImGui::Combo("A/B view", &m, labels, 3)) s.mode = ab_mode(m);
  }
  return act;
}

bool draw_ab_overlay(ab_state& s, float x, float y, float w, float h, const std::string& a_label, const std::string& b_label,
                     bool a_stale, bool b_stale) {
  if (!ab_showing(s)) return false;
  ImDrawList* dl = ImGui::GetBackgroundDrawList();
  const ImU32 text = IM_COL32(235, 235, 235, 230), line = IM_COL32(255, 255, 255, 200);
  const float mid = s.mode == ab_mode::split ? x + w * s.divider : x + w * 0.5f;
  const float pad = 8;
  const ImU32 sel = IM_COL32(255, 200, 80, 255);
  // The stale mark goes first and "(selected)" last; the name between them is cut with "…" to
  // fit its part, so neither mark is ever clipped off.
  const char* stale = "stale (last tree, see the status bar) - ";
  auto width_of = [](std::string_view t) { return ImGui::CalcTextSize(t.data(), t.data() + t.size()).x; };
  auto label = [&](int slot, bool is_stale, const std::string& name, float room) {
    const std::string head = std::string(slot == 0 ? "A: " : "B: ") + (is_stale ? stale : "");
    const std::string tail = s.selected == slot ? "  (selected)" : "";
    return head + ed::elide_text(name, room - width_of(head) - width_of(tail), width_of) + tail;
  };
  const std::string a = label(0, a_stale, a_label, mid - x - 2 * pad), b = label(1, b_stale, b_label, x + w - mid - 2 * pad);
  s.labels_shown[0] = a, s.labels_shown[1] = b;
  s.labels_fit = width_of(a) <= mid - x - 2 * pad && width_of(b) <= x + w - mid - 2 * pad;
  const ImU32 red = IM_COL32(255, 115, 100, 255);
  const ImVec4 clip_a(x, y, mid - pad, y + h), clip_b(mid, y, x + w - pad, y + h);   // each label stays in its part
  // A dark band under each label keeps it readable over a bright sky.
  const float band = ImGui::GetTextLineHeight() + pad;
  dl->AddRectFilled(ImVec2(x, y), ImVec2(std::min(mid, x + width_of(a) + 2 * pad), y + band + pad * 0.5f), IM_COL32(0, 0, 0, 120));
  dl->AddRectFilled(ImVec2(mid, y), ImVec2(std::min(x + w, mid + width_of(b) + 2 * pad), y + band + pad * 0.5f), IM_COL32(0, 0, 0, 120));
  dl->AddText(nullptr, 0, ImVec2(x + pad, y + pad), a_stale ? red : s.selected == 0 ? sel : text, a.c_str(), nullptr, 0, &clip_a);
  dl->AddText(nullptr, 0, ImVec2(mid + pad, y + pad), b_stale ? red : s.selected == 1 ? sel : text, b.c_str(), nullptr, 0, &clip_b);
  dl->AddLine(ImVec2(mid, y), ImVec2(mid, y + h), line, s.mode == ab_mode::split ? 2.0f : 1.0f);
  if (s.mode != ab_mode::split) {
    s.dragging = false;
    return false;
  }
  const ImGuiIO& io = ImGui::GetIO();
  const ImVec2 m = io.MousePos;
  const bool near = std::abs(m.x - mid) < 6 && m.y >= y && m.y <= y + h;
  if (near || s.dragging) {
    dl->AddRectFilled(ImVec2(mid - 4, y + h * 0.5f - 20), ImVec2(mid + 4, y + h * 0.5f + 20), line, 3);
    ImGui::SetMouseCursor(ImGuiMouseCursor_ResizeEW);
  }
  if (near && ImGui::IsMouseClicked(0) && !io.WantCaptureMouse) s.dragging = true;
  if (s.dragging) {
    if (!ImGui::IsMouseDown(0)) s.dragging = false;
    else s.divider = std::clamp((m.x - x) / std::max(1.0f, w), 0.02f, 0.98f);
  }
  return s.dragging;
}

}  // namespace sylva
