// Pruning in the editor: click a branch in the view, "cut here", the list of cuts and the brush.
#include "app/editor/editor_prune.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include <glm/geometric.hpp>
#include <imgui.h>

#include "generators/keyframes.h"
#include "generators/timing.h"
#include "render/mesh/pick.h"

namespace sylva {

namespace {

void line(ImDrawList* dl, const camera_basis& f, const orbit_camera& cam, const view_rect& v, const glm::vec3& a,
          const glm::vec3& b, ImU32 col, float width) {
  glm::vec2 pa, pb;
  if (view_pixel(cam, f, v, a, pa) && view_pixel(cam, f, v, b, pb)) dl->AddLine(ImVec2(pa.x, pa.y), ImVec2(pb.x, pb.y), col, width);
}

const char* const brush_labels[] = {"Outside an ellipsoid", "Outside a box"};

}  // namespace

void pick_in_view(prune_panel_state& s, const tree_skeleton& t, int step, const orbit_camera& cam, const view_rect& v,
                  float mx, float my) {
  const auto t0 = std::chrono::steady_clock::now();
  glm::vec3 o, d;
  view_ray(cam, v, mx, my, o, d);
  // Three pixels of slack, so that a twig thinner than a pixel can be clicked.
  const float pixel = view_pixel_angle(cam, v);
  const pick_hit h = pick_branch(t, radii_at_step(t, step), step, o, d, 3 * pixel);
  s.pick_ms = ms_since(t0);
  s.selected = h.node;
  s.picked_in = &t;
  s.picked_step = step;
}

std::string cut_refusal(const tree_spec& spec, int grown_steps, int step, const char* what) {
  const int last = grown_steps >= 0 ? std::min(last_keyframe_step(spec), grown_steps) : last_keyframe_step(spec);
  if (step + 1 <= last) return "";
  return std::string(what) + " at step " + std::to_string(step) + " of " + std::to_string(last) +
         ": the tree grows no step after this one, so the cut would change nothing; scrub back to an earlier step first";
}

bool draw_prune_panel(prune_panel_state& s, tree_spec& spec, const grow_result* shown, int& step, std::string& error) {
  s.brush_open = false;
  if (!ImGui::CollapsingHeader("Pruning", ImGuiTreeNodeFlags_DefaultOpen)) return false;
  const tree_skeleton* t = shown && shown->skeleton ? shown->skeleton.get() : nullptr;
  if (s.picked_in != t || s.picked_step != step) s.selected = -1;   // a new tree or step: pick again
  bool changed = false;
  ImGui::TextWrapped("Click a branch in the view, then cut it: %s.", cut_response(spec));
  const int grown = t ? t->steps : -1;
  if (t && s.selected >= 0 && size_t(s.selected) < t->size()) {
    const size_t i = size_t(s.selected);
    const glm::vec3 a = t->position[size_t(t->parent[i])], b = t->position[i];
    ImGui::Text("Branch: node %d, order %d, born in step %d (picked in %.2f ms)", s.selected, int(t->order[i]),
                int(t->born[i]), s.pick_ms);
    // What the cut takes: the picked internode and everything it carries at this step (drawn in
    // orange over the view).
    size_t below = 0;
    std::vector<uint8_t> in(t->size(), 0);
    for (size_t j = i; j < t->size(); ++j) {
      in[j] = j == i || (t->parent[j] >= 0 && in[size_t(t->parent[j])]);
      below += in[j] && t->alive(j, step);
    }
    ImGui::TextDisabled("The cut takes %zu of the %zu nodes shown (orange in the view); the tree then regrows.", below,
                        [&] { size_t n = 0; for (size_t j = 0; j < t->size(); ++j) n += t->alive(j, step); return n; }());
    if (ImGui::Button("Cut here")) {
      prune_cut c;
      c.step = step + 1;   // made before the next step grows: the tree of this step keeps it
      c.point = b;
      c.reach = std::clamp(1.5f * glm::length(b - a), 0.02f, 1.0f);
      if (std::string why = cut_refusal(spec, grown, step, "A cut"); !why.empty()) error = why;
      else if (std::string e = add_cut(spec, c); !e.empty()) error = e;
      else step = c.step, s.selected = -1, changed = true;
    }
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("The branch goes from step %d on and the tree regrows without it. The cut finds its branch\n"
                        "again as the node nearest this point, so it survives changes to earlier steps.",
                        step + 1);
    ImGui::SameLine();
    if (ImGui::Button("Clear pick")) s.selected = -1;
  } else {
    ImGui::TextDisabled(t ? "No branch picked." : "No tree yet.");
  }

  // The cuts, oldest first; those the last growth of this spec could not find are marked.
  const bool current = shown && shown->spec == spec;
  int remove = -1;
  for (size_t k = 0; k < spec.cuts.size(); ++k) {
    const prune_cut& c = spec.cuts[k];
    ImGui::PushID(int(k));
    const bool missed = current && std::find(shown->report.missed_cuts.begin(), shown->report.missed_cuts.end(),
                                             int(k)) != shown->report.missed_cuts.end();
    char b[160];
    if (c.shape == prune_shape::branch)
      std::snprintf(b, sizeof b, "step %d: branch at (%.2f, %.2f, %.2f)", c.step, double(c.point.x), double(c.point.y),
                    double(c.point.z));
    else
      std::snprintf(b, sizeof b, "step %d: %s (%.2f, %.2f, %.2f)", c.step, brush_labels[int(c.shape) - 1],
                    double(c.size.x), double(c.size.y), double(c.size.z));
    if (ImGui::SmallButton("x")) remove = int(k);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Delete this cut");
    ImGui::SameLine();
    if (!step_active(spec, c.step)) {
      ImGui::TextDisabled("%s (inactive: past the last step)", b);
      if (ImGui::IsItemHovered())
        ImGui::SetTooltip("Kept and saved; it applies again once Growth steps reaches %d.", c.step);
    } else if (missed) ImGui::TextColored(ImVec4(1, 0.45f, 0.35f, 1), "%s: no branch found", b);
    else ImGui::TextUnformatted(b);
    if (ImGui::IsItemClicked()) step = std::max(0, c.step);
    ImGui::PopID();
  }
  if (remove >= 0) spec.cuts.erase(spec.cuts.begin() + remove), changed = true;

  ImGui::Separator();
  if (!ImGui::TreeNode("Brush (topiary, hedges)")) return changed;
  s.brush_open = true;
  int shape = std::clamp(int(s.brush_shape) - 1, 0, 1);
  if (ImGui::Combo("Shape##brush", &shape, brush_labels, 2)) s.brush_shape = prune_shape(shape + 1);
  ImGui::DragFloat3("Centre##brush", &s.brush_centre.x, 0.02f, -100, 100, "%.2f");
  ImGui::DragFloat3("Half size##brush", &s.brush_size.x, 0.02f, 0.01f, 100, "%.2f");
  ImGui::Checkbox("Show the brush", &s.brush_preview);
  ImGui::SameLine();
  if (ImGui::Button("Fit to the tree") && t) {
    glm::vec3 lo(1e9f), hi(-1e9f);
    for (size_t i = 0; i < t->size(); ++i)
      if (t->alive(i, step)) lo = glm::min(lo, t->position[i]), hi = glm::max(hi, t->position[i]);
    if (lo.x <= hi.x) s.brush_centre = 0.5f * (lo + hi), s.brush_size = glm::max(0.5f * (hi - lo), glm::vec3(0.05f));
    s.brush_preview = true;
  }
  if (ImGui::Button("Cut outside from the next step")) {
    prune_cut c;
    c.step = step + 1;
    c.shape = s.brush_shape;
    c.point = s.brush_centre;
    c.size = s.brush_size;
    if (std::string why = cut_refusal(spec, grown, step, "The brush"); !why.empty()) error = why;
    else if (std::string e = add_cut(spec, c); !e.empty()) error = e;
    else step = c.step, changed = true;
  }
  ImGui::TreePop();
  return changed;
}

void draw_cut_markers(const tree_spec& spec, int steps, float x0, float x1, float y, int& step) {
  if (spec.cuts.empty() || steps <= 0) return;
  ImDrawList* dl = ImGui::GetWindowDrawList();
  for (size_t k = 0; k < spec.cuts.size(); ++k) {
    const prune_cut& c = spec.cuts[k];
    const float x = x0 + (x1 - x0) * float(std::clamp(c.step, 0, steps)) / float(steps);
    ImGui::PushID(int(k) + 100000);
    ImGui::SetCursorScreenPos(ImVec2(x - 4, y));
    if (ImGui::InvisibleButton("##cut", ImVec2(8, 14))) step = std::clamp(c.step, 0, steps);
    const bool hovered = ImGui::IsItemHovered(), active = step_active(spec, c.step);
    const ImVec2 p0(x - 4, y + 13), p1(x + 4, y + 13), p2(x, y + 1);
    const ImU32 col = hovered ? IM_COL32(255, 150, 130, 255) : IM_COL32(230, 70, 60, 255);
    if (active) dl->AddTriangleFilled(p0, p1, p2, col);
    else dl->AddTriangle(p0, p1, p2, hovered ? col : IM_COL32(150, 150, 150, 255), 1.5f);   // kept, inactive
    if (hovered)
      ImGui::SetTooltip("Cut at step %d: %s (click to go there; delete it under Pruning)%s", c.step,
                        c.shape == prune_shape::branch ? "a branch" : brush_labels[std::clamp(int(c.shape) - 1, 0, 1)],
                        active ? "" : "\nInactive: past the last step. It is kept and applies again once Growth steps reaches it.");
    ImGui::PopID();
  }
}

void draw_prune_overlay(prune_panel_state& s, const tree_skeleton* t, int step, const orbit_camera& cam,
                        const view_rect& v) {
  ImDrawList* dl = ImGui::GetBackgroundDrawList();
  const camera_basis f = camera_basis_of(cam);
  if (t && s.picked_in == t && s.picked_step == step && s.selected >= 0 && size_t(s.selected) < t->size()) {
    // The picked branch: its internode and, thinner, everything it carries.
    std::vector<uint8_t> in(t->size(), 0);
    for (size_t i = size_t(s.selected); i < t->size(); ++i) {
      in[i] = int32_t(i) == s.selected || (t->parent[i] >= 0 && in[size_t(t->parent[i])]);
      if (in[i] && t->alive(i, step))
        line(dl, f, cam, v, t->position[size_t(t->parent[i])], t->position[i],
             int32_t(i) == s.selected ? IM_COL32(255, 90, 60, 255) : IM_COL32(255, 150, 60, 160),
             int32_t(i) == s.selected ? 4.0f : 1.5f);
    }
  }
  if (!s.brush_preview || !s.brush_open) return;   // the brush shows only while its section is open
  const ImU32 col = IM_COL32(120, 255, 160, 200);
  const glm::vec3 c = s.brush_centre, h = s.brush_size;
  if (s.brush_shape == prune_shape::outside_box) {
    for (int e = 0; e < 12; ++e) {   // the 12 edges: 4 along each axis
      const int axis = e / 4, a = (axis + 1) % 3, b = (axis + 2) % 3;
      glm::vec3 p(0), q(0);
      p[a] = q[a] = (e & 1) ? 1.0f : -1.0f;
      p[b] = q[b] = (e & 2) ? 1.0f : -1.0f;
      p[axis] = -1, q[axis] = 1;
      line(dl, f, cam, v, c + p * h, c + q * h, col, 1.5f);
    }
    return;
  }
  for (int plane = 0; plane < 3; ++plane) {   // three principal ellipses
    const int a = plane, b = (plane + 1) % 3;
    glm::vec3 prev(0);
    for (int k = 0; k <= 48; ++k) {
      const float th = 6.2831853f * float(k) / 48.0f;
      glm::vec3 p(0);
      p[a] = std::cos(th), p[b] = std::sin(th);
      const glm::vec3 w = c + p * h;
      if (k) line(dl, f, cam, v, prev, w, col, 1.5f);
      prev = w;
    }
  }
}

}  // namespace sylva
