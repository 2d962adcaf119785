// Pruning in the editor: click a branch in the view, "cut here", the list of cuts and the brush.
#pragma once

#include <string>

#include <glm/vec3.hpp>

#include "app/common/worker.h"
#include "generators/tree_spec.h"
#include "render/camera.h"   // orbit_camera, view_rect, view_ray

namespace sylva {

struct prune_panel_state {
  int32_t selected = -1;                 // the node whose internode was clicked (-1: none)
  const tree_skeleton* picked_in = nullptr;   // the tree it was picked in; another tree drops the pick
  int picked_step = -1;
  double pick_ms = 0;                    // the last pick's time, shown in the panel
  prune_shape brush_shape = prune_shape::outside_ellipsoid;
  glm::vec3 brush_centre{0, 3, 0}, brush_size{2, 2, 2};
  bool brush_preview = false;
  bool brush_open = false;               // the brush's section is open in the panel (this frame)
};

// A click in the view at (mx, my): selects the branch under it in the tree at `step`.
void pick_in_view(prune_panel_state& s, const tree_skeleton& t, int step, const orbit_camera& cam, const view_rect& v,
                  float mx, float my);

// Why a cut made while the timeline shows `step` cannot be made ("" when it can). A cut acts from
// the next step on, so it needs a step after `step` both in the spec and in the tree that grew
// (`grown_steps`: the steps the shown tree grew, which can stop well before the Growth steps
// setting; -1 when no tree is shown). `what` names the tool in the message ("cut", "brush").
std::string cut_refusal(const tree_spec& spec, int grown_steps, int step, const char* what);

// The "Pruning" section of the parameter panel: the picked branch and "Cut here", the cut list
// (with the cuts the last growth could not find), the brush. Returns true when the spec changed;
// `step` may move to show a new cut; `error` gets a message for the status bar.
bool draw_prune_panel(prune_panel_state& s, tree_spec& spec, const grow_result* shown, int& step, std::string& error);

// The cuts as red ticks under the timeline's step slider, spanning [x0, x1] at height y (the
// keyframe markers' row): hovering names the cut, a click jumps to its step.
void draw_cut_markers(const tree_spec& spec, int steps, float x0, float x1, float y, int& step);

// The picked internode and the brush outline, drawn over the view.
void draw_prune_overlay(prune_panel_state& s, const tree_skeleton* shown, int step, const orbit_camera& cam,
                        const view_rect& v);

}  // namespace sylva
