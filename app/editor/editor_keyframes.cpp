// Growth phases in the editor: "from this step on" edits, the keyframe list and the timeline markers.
#include "app/editor/editor_keyframes.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <imgui.h>

namespace sylva {

namespace {

// Edits one keyframe's value with a widget of its parameter's type; true when it changed.
bool edit_keyframe_value(tree_spec& spec, keyframe& k, std::string& error) {
  bool changed = false;
  visit_keyed_value(spec, k, [&](auto& value, const param_info& info) {
    using T = std::remove_cvref_t<decltype(value)>;
    bool edited = false;
    if constexpr (std::is_same_v<T, float>)
      edited = ImGui::SliderFloat("##v", &value, info.min, info.max, "%.4g",
                                  (info.flags & param_log) ? ImGuiSliderFlags_Logarithmic : 0);
    else if constexpr (std::is_same_v<T, int>)
      edited = ImGui::SliderInt("##v", &value, int(info.min), int(info.max));
    else if constexpr (std::is_same_v<T, bool>)
      edited = ImGui::Checkbox("##v", &value);
    else if constexpr (std::is_enum_v<T>) {
      int v = int(value);
      if (ImGui::Combo("##v", &v, info.options, option_count(info))) value = T(v), edited = true;
    } else
      edited = ImGui::DragFloat3("##v", &value.x, 0.01f, info.min, info.max);
    if (!edited) return;
    clamp_param(value, info);
    keyframe changed_k = k;
    changed_k.value = to_key_value(value);
    tree_spec out = spec;
    if (std::string e = set_keyframe(out, changed_k); !e.empty()) error = e;
    else spec = std::move(out), changed = true;
  });
  return changed;
}

}  // namespace

void draw_from_step_switch(keyframe_panel_state& s, const tree_spec& spec, int step) {
  const char* meaning = keyframe_step_meaning(spec);
  const auto* l = std::get_if<lsystem_params>(&spec.params);
  const bool available = !(l && l->mode == lsystem_mode::text) && step >= 1;
  if (!available) ImGui::BeginDisabled();
  if (ImGui::Checkbox("From this step on", &s.from_step) && s.from_step) s.from_step_at = step;
  if (!available) {
    ImGui::EndDisabled();
    s.from_step = false;
  }
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip("On: moving a generator slider keys its new value from the timeline's step on (a growth\n"
                      "phase); the tree before that step stays exactly as it is. Off: the slider sets the value\n"
                      "for the whole growth. It switches itself off when the timeline moves to another step.%s\n\n%s",
                      step < 1 ? "\n\nScrub to step 1 or later first." : "", meaning);
  if (s.from_step) {
    ImGui::SameLine();
    ImGui::TextColored(ImVec4(0.5f, 0.85f, 1, 1), "edits are keyed at step %d (•)", step);
  }
}

bool draw_keyframe_panel(keyframe_panel_state& s, tree_spec& spec, int step, std::string& error) {
  (void)s;
  if (!ImGui::CollapsingHeader("Growth phases", ImGuiTreeNodeFlags_DefaultOpen)) return false;
  bool changed = false;
  ImGui::TextWrapped("Keyframes change a generator parameter from a step on: tick \"From this step on\" on the Tree "
                     "tab at a step, then move a slider (%s).", keyframe_step_meaning(spec));
  int remove = -1;
  if (!spec.keyframes.empty() && ImGui::BeginTable("##keys", 3, ImGuiTableFlags_SizingStretchProp | ImGuiTableFlags_RowBg)) {
    ImGui::TableSetupColumn("step", ImGuiTableColumnFlags_WidthFixed, 44);
    ImGui::TableSetupColumn("key");
    ImGui::TableSetupColumn("", ImGuiTableColumnFlags_WidthFixed, 24);
    for (size_t i = 0; i < spec.keyframes.size(); ++i) {
      keyframe& k = spec.keyframes[i];
      ImGui::PushID(int(i));
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      if (!step_active(spec, k.step)) {
        ImGui::TextDisabled("%d", k.step);
        if (ImGui::IsItemHovered())
          ImGui::SetTooltip("Inactive: step %d is past the last step (%d). The keyframe is kept, saved and\n"
                            "applied again once Growth steps reaches %d.", k.step, last_keyframe_step(spec), k.step);
      } else if (k.step == step) ImGui::TextColored(ImVec4(0.5f, 0.85f, 1, 1), "%d", k.step);
      else ImGui::Text("%d", k.step);
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(k.key.c_str());
      ImGui::SameLine();
      ImGui::SetNextItemWidth(-1);
      changed |= edit_keyframe_value(spec, k, error);
      ImGui::TableNextColumn();
      if (ImGui::SmallButton("x")) remove = int(i);
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("Delete this keyframe");
      ImGui::PopID();
    }
    ImGui::EndTable();
  }
  if (remove >= 0) {
    spec.keyframes.erase(spec.keyframes.begin() + remove);
    changed = true;
  }
  if (spec.keyframes.empty()) ImGui::TextDisabled("No keyframes.");
  return changed;
}

bool draw_keyframe_markers(keyframe_panel_state& s, tree_spec& spec, int steps, float x0, float x1, float y,
                           int& step, std::string& error) {
  s.drawn.clear();
  if (spec.keyframes.empty() || steps <= 0) return false;
  bool changed = false;
  ImDrawList* dl = ImGui::GetWindowDrawList();
  auto x_of = [&](int k) { return x0 + (x1 - x0) * float(std::clamp(k, 0, steps)) / float(steps); };
  const float h = 6;
  for (int k : keyed_steps(spec)) {
    ImGui::PushID(k);
    const float x = x_of(s.drag_from == k && s.drag_to >= 0 ? s.drag_to : k);
    s.drawn.emplace_back(k, (x - x0) / std::max(x1 - x0, 1.0f));
    ImGui::SetCursorScreenPos(ImVec2(x - h - 1, y));
    ImGui::InvisibleButton("##marker", ImVec2(2 * h + 2, 2 * h + 2), ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonRight);
    const bool hovered = ImGui::IsItemHovered(), active = ImGui::IsItemActive();
    if (active && ImGui::IsMouseDragging(ImGuiMouseButton_Left, 2)) {
      s.drag_from = k;
      const float f = (ImGui::GetIO().MousePos.x - x0) / std::max(x1 - x0, 1.0f);
      s.drag_to = std::clamp(int(std::lround(f * float(steps))), 1, steps);
    }
    if (ImGui::IsItemDeactivated()) {
      if (s.drag_from == k && s.drag_to >= 0 && s.drag_to != k) {
        if (std::string e = move_keyframes(spec, k, s.drag_to); !e.empty()) error = e;
        else step = s.drag_to, changed = true;
      } else if (s.drag_from < 0) {
        step = k;  // a click: jump to the keyed step
      }
      s.drag_from = s.drag_to = -1;
    }
    if (ImGui::IsItemClicked(ImGuiMouseButton_Right)) {
      s.popup_step = k;
      ImGui::OpenPopup("##keyed");
    }
    const bool in_growth = step_active(spec, k);   // past the last step: kept, inactive, drawn hollow at the end
    const ImU32 col = hovered || active ? IM_COL32(140, 220, 255, 255) : k == step ? IM_COL32(90, 190, 255, 255)
                                        : in_growth ? IM_COL32(255, 200, 90, 255) : IM_COL32(150, 150, 150, 255);
    const float cy = y + h + 1;
    if (in_growth) dl->AddQuadFilled(ImVec2(x, cy - h), ImVec2(x + h, cy), ImVec2(x, cy + h), ImVec2(x - h, cy), col);
    else dl->AddQuad(ImVec2(x, cy - h), ImVec2(x + h, cy), ImVec2(x, cy + h), ImVec2(x - h, cy), col, 1.5f);
    if (hovered && !active) {
      std::string tip = "Step " + std::to_string(k) + " (drag to move, right-click to edit or delete):";
      if (!in_growth)
        tip += "\nInactive: past the last step (" + std::to_string(last_keyframe_step(spec)) +
               "). Kept, and applied again once Growth steps reaches " + std::to_string(k) + ".";
      for (const keyframe& kf : spec.keyframes)
        if (kf.step == k) tip += "\n  " + keyframe_text(spec, kf);
      ImGui::SetTooltip("%s", tip.c_str());
    }
    if (ImGui::BeginPopup("##keyed")) {
      ImGui::Text("Keyframes at step %d", s.popup_step);
      ImGui::Separator();
      int remove = -1;
      for (size_t i = 0; i < spec.keyframes.size(); ++i) {
        keyframe& kf = spec.keyframes[i];
        if (kf.step != s.popup_step) continue;
        ImGui::PushID(int(i));
        ImGui::TextUnformatted(kf.key.c_str());
        ImGui::SameLine(140);
        ImGui::SetNextItemWidth(160);
        changed |= edit_keyframe_value(spec, kf, error);
        ImGui::SameLine();
        if (ImGui::SmallButton("Delete")) remove = int(i);
        ImGui::PopID();
      }
      if (remove >= 0) spec.keyframes.erase(spec.keyframes.begin() + remove), changed = true;
      if (ImGui::Button("Delete all at this step")) {
        std::erase_if(spec.keyframes, [&](const keyframe& kf) { return kf.step == s.popup_step; });
        changed = true;
        ImGui::CloseCurrentPopup();
      }
      ImGui::EndPopup();
    }
    ImGui::PopID();
  }
  return changed;
}

}  // namespace sylva
