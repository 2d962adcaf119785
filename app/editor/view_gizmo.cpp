// The view gizmo and the front / side / top views (see view_gizmo.h).
#include "app/editor/view_gizmo.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/geometric.hpp>
#include <imgui.h>

namespace sylva {

void snap_view(orbit_camera& c, view_axis a) {
  // camera_eye: yaw 0 puts the eye on +Z (the front), yaw 90 on +X (the right side).
  switch (a) {
    case view_axis::front: c.yaw = 0, c.pitch = 0; break;
    case view_axis::back: c.yaw = 180, c.pitch = 0; break;
    case view_axis::right: c.yaw = 90, c.pitch = 0; break;
    case view_axis::left: c.yaw = -90, c.pitch = 0; break;
    case view_axis::top: c.yaw = 0, c.pitch = 89; break;       // the orbit stops short of the pole
    case view_axis::bottom: c.yaw = 0, c.pitch = -89; break;
  }
}

const char* view_axis_name(view_axis a) {
  static const char* names[] = {"Front", "Back", "Right", "Left", "Top", "Bottom"};
  return names[int(a)];
}

bool draw_view_gizmo(orbit_camera& c, const view_rect& v) {
  const float scale = ImGui::GetFontSize() / 16.0f;
  const float radius = 34 * scale, knob = 8 * scale;
  const ImVec2 centre(v.x + v.w - radius - 14 * scale, v.y + radius + 14 * scale);
  if (v.w < 4 * radius || v.h < 4 * radius) return false;
  const camera_basis basis = camera_basis_of(c);
  const glm::vec3 fwd = basis.forward, right = basis.right, up = basis.up;
  struct end { glm::vec3 dir; view_axis axis; ImU32 col; const char* label; };
  // The eye sits on the clicked axis end's side: the +Z end is the front view, +X the right.
  const std::array<end, 6> ends = {{{{1, 0, 0}, view_axis::right, IM_COL32(230, 80, 80, 255), "X"},
                                    {{0, 1, 0}, view_axis::top, IM_COL32(120, 210, 90, 255), "Y"},
                                    {{0, 0, 1}, view_axis::front, IM_COL32(90, 140, 240, 255), "Z"},
                                    {{-1, 0, 0}, view_axis::left, IM_COL32(150, 70, 70, 255), nullptr},
                                    {{0, -1, 0}, view_axis::bottom, IM_COL32(80, 130, 70, 255), nullptr},
                                    {{0, 0, -1}, view_axis::back, IM_COL32(70, 90, 150, 255), nullptr}}};
  ImDrawList* dl = ImGui::GetForegroundDrawList();
  const ImVec2 mouse = ImGui::GetIO().MousePos;
  const float dx = mouse.x - centre.x, dy = mouse.y - centre.y;
  const bool over = dx * dx + dy * dy <= (radius + knob) * (radius + knob) && !ImGui::GetIO().WantCaptureMouse;
  if (over) dl->AddCircleFilled(centre, radius + knob, IM_COL32(255, 255, 255, 30));
  // Far ends first, so that the near ones are drawn over them.
  std::array<int, 6> order = {0, 1, 2, 3, 4, 5};
  std::sort(order.begin(), order.end(), [&](int a, int b) { return glm::dot(ends[a].dir, fwd) > glm::dot(ends[b].dir, fwd); });
  int hit = -1;
  float hit_depth = 1e9f;
  for (int i : order) {
    const end& e = ends[size_t(i)];
    const ImVec2 p(centre.x + radius * glm::dot(e.dir, right), centre.y - radius * glm::dot(e.dir, up));
    if (e.label) dl->AddLine(centre, p, e.col, 2 * scale);
    dl->AddCircleFilled(p, e.label ? knob : knob * 0.7f, e.col);
    if (e.label) dl->AddText(ImVec2(p.x - 4 * scale, p.y - 8 * scale), IM_COL32(20, 20, 20, 255), e.label);
    const float ex = mouse.x - p.x, ey = mouse.y - p.y, depth = glm::dot(e.dir, fwd);
    if (over && ex * ex + ey * ey <= knob * knob && depth < hit_depth) hit = i, hit_depth = depth;
  }
  if (hit >= 0) {
    ImGui::SetTooltip("%s view (%s)", view_axis_name(ends[size_t(hit)].axis),
                      ends[size_t(hit)].axis == view_axis::front ? "numpad 1" : ends[size_t(hit)].axis == view_axis::right ? "numpad 3"
                      : ends[size_t(hit)].axis == view_axis::top ? "numpad 7" : "Ctrl + numpad");
    if (ImGui::IsMouseClicked(ImGuiMouseButton_Left)) snap_view(c, ends[size_t(hit)].axis);
  }
  return over && !ImGui::IsMouseDragging(ImGuiMouseButton_Left, 3);
}

}  // namespace sylva
