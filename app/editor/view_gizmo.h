// The view gizmo and the camera keys a Blender user expects: front, side and top views (numpad 1,
// 3, 7; Ctrl for the opposite side; the row digits too, for keyboards without a numpad) and a
// small axis gizmo in the corner of the 3D view whose axis ends snap the view when clicked.
#pragma once

#include "render/camera.h"

namespace sylva {

enum class view_axis { front, back, right, left, top, bottom };

// Turns the orbit camera to look along an axis at its target (distance and target stay).
void snap_view(orbit_camera& c, view_axis a);
const char* view_axis_name(view_axis a);

// Draws the gizmo in the top-right corner of `v` (window pixels) over the 3D view; a click on an
// axis end snaps the camera. Returns true when it took the mouse (the view must not orbit).
bool draw_view_gizmo(orbit_camera& c, const view_rect& v);

}  // namespace sylva
