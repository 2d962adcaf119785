// Growth phases in the editor: "from this step on" edits, the keyframe list and the timeline markers.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "generators/keyframes.h"
#include "generators/tree_spec.h"

namespace sylva {

struct keyframe_panel_state {
  bool from_step = false;   // slider edits of generator parameters become keyframes at the current step
  int from_step_at = -1;    // the step "from this step on" was switched on at
  int drag_from = -1;       // the step of the marker being dragged (-1: none)
  int drag_to = -1;         // where it would land
  int popup_step = -1;      // the marker whose popup is open
  // The markers drawn last frame: (keyed step, place along the timeline from 0 at its start to 1 at
  // its end), for the scripted test.
  std::vector<std::pair<int, float>> drawn;
};

// ---------------------------------------------------------------- display-free (tested)

// "From this step on" keys edits at the step where it was switched on, and only there: moving the
// timeline to another step switches it off, so that later edits are not keyed without notice.
// Returns true when it switched off.
bool follow_step(keyframe_panel_state& s, int step);

// The generator params in effect during growth step `step`.
generator_params params_at_step(const tree_spec& spec, int step);
// The panel showed `before` (params_at_step(spec, step)) and the user turned it into `after`: each
// parameter that differs becomes a keyframe at `step`. A value equal to what is in effect without
// the keyframe at `step` removes that keyframe. Returns "" or why a key cannot be keyed; on an
// error nothing changes.
std::string key_edits(tree_spec& spec, const generator_params& before, const generator_params& after, int step);
// Moves every keyframe at step `from` to step `to`. Refused (spec unchanged) when `to` is out of
// 1..max_keyframe_step or one of the keys is already keyed at `to` (past the last step it is kept,
// inactive, like any keyframe there).
std::string move_keyframes(tree_spec& spec, int from, int to);
// The steps that hold keyframes, ascending, without repeats.
std::vector<int> keyed_steps(const tree_spec& spec);
// Calls f(value, info) once with a copy of k's parameter set to k's value, typed as the parameter
// (float, int, bool, enum or vec3); nothing when the spec's generator has no such keyable key.
template <class F>
void visit_keyed_value(const tree_spec& spec, const keyframe& k, F&& f) {
  std::visit(
      [&](const auto& p) {
        auto copy = p;
        visit_params(copy, [&](auto& value, const param_info& info) {
          if constexpr (keyable_type<std::remove_cvref_t<decltype(value)>>) {
            if (k.key != info.key) return;
            from_key_value(k.value, value);
            f(value, info);
          }
        });
      },
      spec.params);
}
// "lambda = 0.7" for a keyframe, the value written as its parameter's type.
std::string keyframe_text(const tree_spec& spec, const keyframe& k);

// ---------------------------------------------------------------- ImGui

// The "From this step on" switch, drawn above the generator's sliders it applies to.
void draw_from_step_switch(keyframe_panel_state& s, const tree_spec& spec, int step);
// The "Growth phases" section of the parameter panel: what a step means for this generator, and
// the list (step, key, value, delete). Returns true when the spec changed; `error` gets a message
// for the status bar.
bool draw_keyframe_panel(keyframe_panel_state& s, tree_spec& spec, int step, std::string& error);
// Markers under the timeline's step slider, spanning [x0, x1] on screen at height y: click jumps to
// the step, drag moves the step's keyframes, right-click edits or deletes them.
bool draw_keyframe_markers(keyframe_panel_state& s, tree_spec& spec, int steps, float x0, float x1, float y,
                           int& step, std::string& error);
// Whether a parameter is keyed exactly at `step` (the panel marks it).
bool keyed_at(const tree_spec& spec, const char* key, int step);

}  // namespace sylva
