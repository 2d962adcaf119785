// Generator-specific editor panels: L-system text, constants and inspector; per-step tables; overlay toggles.
#pragma once

#include <cstddef>
#include <future>
#include <string>
#include <vector>

#include "app/common/worker.h"
#include "generators/lsystem_engine.h"
#include "generators/tree_spec.h"
#include "render/gl/overlays.h"

namespace sylva {

// What the parameter panel shows: what param_relevant keeps within the struct, and the generator's
// own leaf rule (param_own_leaves) only when the mesh's leaf mode is generator.
template <class P>
bool editor_shows(const P& p, const void* field, const param_info& info, bool generator_leaves) {
  return param_relevant(p, field, info) && (generator_leaves || !(info.flags & param_own_leaves));
}

// ---------------------------------------------------------------- per-step tables (display-free)

// The std::vector<float> parameters of one params struct are per-step schedules (guiding vectors'
// t, endpoint count, hop distance): the editor shows them together as one table, rows = steps,
// one column each. A schedule's last entry repeats for later steps (schedule_at in
// guiding_vectors.cpp), so a short column shows its repeated value in the rows past its end.
struct step_column {
  std::vector<float>* values = nullptr;
  param_info info{};
};

template <class P>
std::vector<step_column> collect_step_columns(P& p) {
  std::vector<step_column> out;
  visit_params(p, [&](auto& value, const param_info& info) {
    if constexpr (std::is_same_v<std::remove_cvref_t<decltype(value)>, std::vector<float>>) out.push_back({&value, info});
  });
  return out;
}

// Rows of the table: the longest column.
inline size_t step_rows(const std::vector<step_column>& cols) {
  size_t n = 0;
  for (const step_column& c : cols) n = std::max(n, c.values->size());
  return n;
}

// The value in effect at row r (0-based, step r + 1): the entry, or the last one repeated. The
// column's minimum when it is empty.
inline float step_cell(const step_column& c, size_t row) {
  if (c.values->empty()) return c.info.min;
  return (*c.values)[std::min(row, c.values->size() - 1)];
}

// Writes row r; a short column is first padded with its repeated last value so that the steps
// before r keep what they had.
inline void set_step_cell(step_column& c, size_t row, float value) {
  std::vector<float>& v = *c.values;
  const float fill = step_cell(c, row);
  if (v.size() <= row) v.resize(row + 1, fill);
  v[row] = value;
}

// Appends a step to every column, repeating its last value (so the new step changes nothing until edited).
inline void add_step(std::vector<step_column>& cols) {
  const size_t rows = step_rows(cols);
  for (step_column& c : cols) {
    const float fill = step_cell(c, rows);
    c.values->resize(rows + 1, fill);
  }
}

// Removes the last step from the columns that reach it; a table keeps at least one step.
inline void remove_step(std::vector<step_column>& cols) {
  const size_t rows = step_rows(cols);
  if (rows <= 1) return;
  for (step_column& c : cols)
    if (c.values->size() == rows) c.values->pop_back();
}

// ---------------------------------------------------------------- L-system text panel state

struct lsystem_panel_state {
  // Parse results of `checked_source`, redone only when the source changes.
  std::string checked_source;
  bool checked = false;
  lsystem_error error;
  std::vector<lsystem_error> warnings;   // lsystem_warnings(): unbalanced brackets, idle parameters, dead productions
  std::vector<lsystem_constant> constants;
  std::string refused;                   // a constant typed as NaN or infinity: why it was not applied
  // The derivation inspector runs off the UI thread; the newest finished one is shown.
  std::future<lsystem_inspection> pending;
  std::string pending_source, inspected_source;
  int pending_derivations = -1, inspected_derivations = -1;
  uint64_t pending_seed = 0, inspected_seed = 0;
  lsystem_inspection inspection;
  bool has_inspection = false;
  int first_n = 200;
};

struct generator_panel_state {
  lsystem_panel_state lsystem;
};

// Draws the panels that the generic parameter drawer cannot: for L-systems in text mode, the
// source editor with its error, the #define sliders and the inspector. `shown` is the tree on
// screen (for evaluation errors). Edits are noticed by comparing documents, not returned.
void draw_generator_panel(generator_panel_state& s, tree_spec& spec, const grow_result* shown);
// While the panel is searched: a text L-system's #define constants whose name or help comment
// matches `filter` (param_matches), as sliders; none drawn with `count_only`. Returns how many match.
int draw_matching_constants(generator_panel_state& s, tree_spec& spec, const std::string& filter, bool count_only);

// The per-step table of `cols`; `hold` is set while an apply-on-release cell is dragged.
void draw_step_table(std::vector<step_column>& cols, bool& hold);

// View-menu items: one toggle per overlay kind, and the shadow-grid slice.
void draw_overlay_menu(overlay_view& view, const overlay_gpu& gpu);

// A growth that failed to parse is not shown: the last good tree stays on screen.
inline bool keeps_last_tree(const grow_result& r) { return r.report.stop == grow_stop::parse_error; }

}  // namespace sylva
