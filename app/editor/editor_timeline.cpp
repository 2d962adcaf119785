// The timeline: transport buttons, the step slider, keyframe markers and playback.
#include "app/editor/editor_state.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <imgui.h>

namespace sylva::ed {

void draw_timeline(editor_state& e, float x, float y, float w) {
  ImGui::SetNextWindowPos(ImVec2(x, y));
  ImGui::SetNextWindowSize(ImVec2(w, timeline_height()));
  ImGui::Begin("Timeline", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoTitleBar |
                   ImGuiWindowFlags_NoScrollbar);
  const int steps = e.cur().shown && e.cur().shown->skeleton ? e.cur().shown->skeleton->steps : 0;
  if (ImGui::Button("|<")) e.step = 0;
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Jump to the start (Home)");
  ImGui::SameLine();
  if (ImGui::Button("<")) e.step = std::max(0, e.step - 1);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("One step back (Left)");
  ImGui::SameLine();
  if (ImGui::Button(e.playing ? "Pause" : "Play")) {
    e.playing = !e.playing;
    if (e.playing && e.step >= steps) e.step = 0;
  }
  ImGui::SameLine();
  if (ImGui::Button(">")) e.step = std::min(steps, e.step + 1);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("One step forward (Right)");
  ImGui::SameLine();
  if (ImGui::Button(">|")) e.step = steps;
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Jump to the end (End)");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(110);
  ImGui::SliderFloat("##speed", &e.speed, 0.25f, 30, "%.2g steps/s", ImGuiSliderFlags_Logarithmic);
  ImGui::SameLine();
  ImGui::SetNextItemWidth(-1);
  char step_format[48];
  std::snprintf(step_format, sizeof step_format, "step %%d / %d", std::max(steps, 0));
  ImGui::SliderInt("##step", &e.step, 0, std::max(steps, 0), step_format);
  if (timeline_markers) {   // growth phases and cuts: markers under the slider
    const ImVec2 lo = ImGui::GetItemRectMin(), hi = ImGui::GetItemRectMax();
    const float grab = ImGui::GetStyle().GrabMinSize * 0.5f + ImGui::GetStyle().FramePadding.x;
    // Scaled to the steps the tree grew, which can be far fewer than the Growth steps setting.
    const int span = steps > 0 ? steps : last_keyframe_step(e.cur().doc.spec);
    std::string key_error;
    draw_cut_markers(e.cur().doc.spec, span, lo.x + grab, hi.x - grab, hi.y + 2, e.step);
    draw_keyframe_markers(e.keys, e.cur().doc.spec, span, lo.x + grab, hi.x - grab, hi.y + 2, e.step, key_error);
    if (!key_error.empty()) set_status(e, key_error, true);
  } else {
    e.keys.drawn.clear();
  }
  ImGui::End();
}

// Nodes alive at the scrubbed step, like the leaf and triangle counts (O(n), once per step change).
size_t nodes_at_step(editor_state& e) {
  const tree_skeleton* t = e.cur().shown ? e.cur().shown->skeleton.get() : nullptr;
  if (!t) return 0;
  if (t != e.counted_tree || e.step != e.counted_step) {
    size_t n = 0;
    for (size_t i = 0; i < t->size(); ++i) n += t->alive(i, e.step);
    e.counted_tree = t, e.counted_step = e.step, e.counted_nodes = n;
  }
  return e.counted_nodes;
}

// Playback and scrubbing: draw counts plus a small per-node upload, never a re-mesh.
void advance_playback(editor_state& e, double dt) {
  if (!e.cur().shown || !e.cur().shown->skeleton) return;
  const int steps = e.cur().shown->skeleton->steps;
  if (e.playing) {
    e.play_accum += dt * e.speed;
    while (e.play_accum >= 1.0) {
      e.play_accum -= 1.0;
      if (++e.step > steps) e.step = 0;
    }
  }
  e.step = std::clamp(e.step, 0, steps);
  if (e.step != e.cur().renderer.step) set_tree_step(e.cur().renderer, *e.cur().shown->skeleton, e.cur().shown->mesh_settings.min_radius, e.step);
}

}  // namespace sylva::ed
