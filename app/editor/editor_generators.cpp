// Generator-specific editor panels: L-system text, constants and inspector; per-step tables; overlay toggles.
#include "app/editor/editor_generators.h"

#include "app/common/wake.h"
#include "app/editor/editor_panel_tabs.h"

#include <algorithm>
#include <chrono>
#include <cstdio>

#include <imgui.h>
#include <imgui_stdlib.h>

namespace sylva {

namespace {

const ImVec4 error_colour(1, 0.45f, 0.4f, 1);

// Re-parses only when the text changed: parsing is cheap, but not every frame.
void refresh_check(lsystem_panel_state& s, const std::string& source) {
  if (s.checked && s.checked_source == source) return;
  s.checked_source = source;
  s.checked = true;
  s.error = lsystem_check(source);
  s.warnings = lsystem_warnings(source);
  s.constants = lsystem_constants(source);
}

// The inspector derives the whole string, which may take a while: it runs on its own thread, one
// at a time, and the UI shows the newest finished result.
void refresh_inspection(lsystem_panel_state& s, const lsystem_params& p, uint64_t seed) {
  using namespace std::chrono_literals;
  if (s.pending.valid() && s.pending.wait_for(0s) == std::future_status::ready) {
    s.inspection = s.pending.get();
    s.inspected_source = s.pending_source;
    s.inspected_derivations = s.pending_derivations;
    s.inspected_seed = s.pending_seed;
    s.has_inspection = true;
  }
  if (s.pending.valid()) return;
  const bool current = s.has_inspection && s.inspected_derivations == p.derivations && s.inspected_seed == seed &&
                       s.inspected_source == p.source;
  if (current || !s.error.ok()) return;
  s.pending_source = p.source;
  s.pending_derivations = p.derivations;
  s.pending_seed = seed;
  const int64_t cap = std::min<int64_t>(p.module_cap, 2000000);   // the inspector never outgrows the tree's own cap
  s.pending = std::async(std::launch::async, [src = p.source, n = p.derivations, first = s.first_n, seed, cap] {
    lsystem_inspection r = inspect_lsystem(src, n, first, seed, cap);
    wake_ui();   // an idle editor shows it
    return r;
  });
}

// The source box, with the offending line tinted red when the error is on a visible line.
void draw_source_box(lsystem_panel_state& s, std::string& source) {
  const float line_h = ImGui::GetTextLineHeight();
  const int lines = int(std::count(source.begin(), source.end(), '\n')) + 1;
  const float pad = ImGui::GetStyle().FramePadding.y;
  const float fit = float(lines + 1) * line_h + 2 * pad;
  const float height = std::clamp(fit, 6 * line_h, 22 * line_h);
  ImGui::InputTextMultiline("##lsystem_source", &source, ImVec2(-1, height), ImGuiInputTextFlags_AllowTabInput);
  if (!s.error.ok() && s.error.line > 0 && fit <= height) {   // no scrolling: line rows are exact
    const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
    const float y = a.y + pad + float(s.error.line - 1) * line_h;
    if (y + line_h <= b.y) {
      ImDrawList* dl = ImGui::GetWindowDrawList();
      dl->AddRectFilled(ImVec2(a.x + 1, y), ImVec2(b.x - 1, y + line_h), IM_COL32(255, 60, 50, 60));
      dl->AddRectFilled(ImVec2(a.x, y), ImVec2(a.x + 3, y + line_h), IM_COL32(255, 80, 60, 255));
    }
  }
}

// "line L:C message", then the line itself with a caret under the column.
void draw_error(const lsystem_error& err, const std::string& source) {
  ImGui::PushStyleColor(ImGuiCol_Text, error_colour);
  ImGui::TextWrapped("line %d:%d  %s", err.line, err.column, err.message.c_str());
  ImGui::PopStyleColor();
  if (err.line <= 0) return;
  size_t begin = 0;
  for (int l = 1; l < err.line && begin != std::string::npos; ++l) {
    begin = source.find('\n', begin);
    if (begin != std::string::npos) ++begin;
  }
  if (begin == std::string::npos || begin > source.size()) return;
  const size_t end = std::min(source.find('\n', begin), source.size());
  const std::string text = source.substr(begin, end - begin);
  ImGui::TextUnformatted(text.c_str());
  const size_t col = std::min(size_t(std::max(err.column - 1, 0)), text.size());
  const float x = ImGui::CalcTextSize(text.c_str(), text.c_str() + col).x;
  ImGui::SetCursorPosX(ImGui::GetCursorPosX() + x);
  ImGui::TextColored(error_colour, "^");
}

void draw_constant(lsystem_panel_state& s, const lsystem_constant& c, std::string& source) {
  ImGui::PushID(c.name.c_str());
  float v = c.value;
  // A value outside its comment's range widens the slider rather than being clamped on touch.
  const float lo = std::min(c.min, v), hi = std::max(c.max, v);
  if (ImGui::SliderFloat(c.name.c_str(), &v, lo, hi, "%.4g")) {   // Ctrl+click types: "1e999" is inf
    s.refused = finite_refusal(c.name, v);
    if (s.refused.empty()) set_lsystem_constant(source, c.name, v);
  }
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("%s\n#define on line %d; dragging rewrites the text", c.help.empty() ? c.name.c_str() : c.help.c_str(), c.line);
  ImGui::PopID();
}

void draw_constants(lsystem_panel_state& s, std::string& source) {
  if (s.constants.empty()) {
    ImGui::TextDisabled("No #define constants (\"#define NAME value // [min,max] help\" makes a slider).");
    return;
  }
  for (const lsystem_constant& c : std::vector<lsystem_constant>(s.constants)) draw_constant(s, c, source);
  if (!s.refused.empty()) ImGui::TextColored(error_colour, "Not applied: %s", s.refused.c_str());
}

void draw_inspector(lsystem_panel_state& s) {
  if (!s.has_inspection) {
    ImGui::TextDisabled(s.pending.valid() ? "deriving..." : "no derivation yet");
    return;
  }
  const lsystem_inspection& in = s.inspection;
  if (s.pending.valid()) ImGui::TextDisabled("deriving the newest text...");
  if (!in.message.empty()) ImGui::TextColored(error_colour, "%s", in.message.c_str());
  if (ImGui::BeginTable("counts", 2, ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg | ImGuiTableFlags_ScrollY,
                        ImVec2(0, std::min(8.0f, float(in.module_counts.size()) + 1.5f) * ImGui::GetFrameHeight()))) {
    ImGui::TableSetupScrollFreeze(0, 1);
    ImGui::TableSetupColumn("step");
    ImGui::TableSetupColumn("modules");
    ImGui::TableHeadersRow();
    for (size_t k = 0; k < in.module_counts.size(); ++k) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::Text("%zu", k);
      ImGui::TableNextColumn();
      ImGui::Text("%zu", in.module_counts[k]);
    }
    ImGui::EndTable();
  }
  ImGui::Text("First %d modules of the last string:", s.first_n);
  ImGui::PushTextWrapPos(0);
  ImGui::TextUnformatted(in.first_modules.c_str());
  ImGui::PopTextWrapPos();
}

void draw_lsystem_text(lsystem_panel_state& s, lsystem_params& p, uint64_t seed, const grow_result* shown) {
  refresh_check(s, p.source);
  if (ImGui::CollapsingHeader("L-system source", ImGuiTreeNodeFlags_DefaultOpen)) {
    ImGui::PushItemWidth(-1);
    draw_source_box(s, p.source);
    ImGui::PopItemWidth();
    refresh_check(s, p.source);
    if (!s.error.ok()) {
      draw_error(s.error, p.source);
      ImGui::TextDisabled("The last good tree stays on screen until the text parses.");
    } else if (shown && shown->report.stop == grow_stop::evaluation_error) {
      ImGui::TextColored(error_colour, "%s", shown->report.message.c_str());
    } else if (!s.warnings.empty()) {
      const ImVec4 warn(1, 0.78f, 0.35f, 1);
      for (const lsystem_error& w : s.warnings) {
        ImGui::PushStyleColor(ImGuiCol_Text, warn);
        ImGui::TextWrapped("line %d:%d  warning: %s", w.line, w.column, w.message.c_str());
        ImGui::PopStyleColor();
      }
      ImGui::TextDisabled("The tree grows as written.");
    } else {
      ImGui::TextColored(ImVec4(0.6f, 0.85f, 0.6f, 1), "ok");
    }
  }
  if (ImGui::CollapsingHeader("Constants (#define)", ImGuiTreeNodeFlags_DefaultOpen)) draw_constants(s, p.source);
  refresh_inspection(s, p, seed);
  if (ImGui::CollapsingHeader("Derivation inspector", ImGuiTreeNodeFlags_DefaultOpen)) draw_inspector(s);
}

}  // namespace

int draw_matching_constants(generator_panel_state& s, tree_spec& spec, const std::string& filter, bool count_only) {
  auto* p = std::get_if<lsystem_params>(&spec.params);
  if (!p || p->mode != lsystem_mode::text) return 0;
  refresh_check(s.lsystem, p->source);
  int n = 0;
  for (const lsystem_constant& c : std::vector<lsystem_constant>(s.lsystem.constants)) {
    const param_info as_param{c.name.c_str(), c.name.c_str(), "", c.min, c.max, c.help.c_str()};
    if (!param_matches(as_param, "Constants (#define)", filter)) continue;
    if (!count_only && n == 0) {
      ImGui::Separator();
      ImGui::TextDisabled("Constants (#define)");
    }
    ++n;
    if (!count_only) draw_constant(s.lsystem, c, p->source);
  }
  return n;
}

void draw_generator_panel(generator_panel_state& s, tree_spec& spec, const grow_result* shown) {
  if (auto* p = std::get_if<lsystem_params>(&spec.params); p && p->mode == lsystem_mode::text)
    draw_lsystem_text(s.lsystem, *p, spec.seed, shown);
}

void draw_step_table(std::vector<step_column>& cols, bool& hold) {
  if (cols.empty()) return;
  const size_t rows = step_rows(cols);
  ImGui::TextUnformatted("Steps");
  ImGui::SameLine();
  if (ImGui::SmallButton("+ step")) add_step(cols);
  ImGui::SameLine();
  if (ImGui::SmallButton("- step") && rows > 1) remove_step(cols);
  const ImGuiTableFlags flags = ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingStretchSame;
  if (!ImGui::BeginTable("steps", int(cols.size()) + 1, flags)) return;
  ImGui::TableSetupColumn("#", ImGuiTableColumnFlags_WidthFixed, 22);
  for (const step_column& c : cols) ImGui::TableSetupColumn(c.info.symbol && *c.info.symbol ? c.info.symbol : c.info.label);
  ImGui::TableNextRow(ImGuiTableRowFlags_Headers);
  ImGui::TableNextColumn();
  ImGui::TextUnformatted("#");
  for (const step_column& c : cols) {
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(c.info.label);
    if (ImGui::IsItemHovered() && c.info.help) ImGui::SetTooltip("%s", c.info.help);
  }
  for (size_t r = 0; r < step_rows(cols); ++r) {
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    ImGui::Text("%zu", r + 1);
    for (size_t k = 0; k < cols.size(); ++k) {
      step_column& c = cols[k];
      ImGui::TableNextColumn();
      ImGui::PushID(int(r * cols.size() + k));
      float v = step_cell(c, r);
      const bool repeated = r >= c.values->size();   // the last entry repeats here
      if (repeated) ImGui::PushStyleVar(ImGuiStyleVar_Alpha, 0.5f);
      ImGui::SetNextItemWidth(-1);
      const char* fmt = (c.info.flags & param_degrees) ? "%.1f°" : "%.4g";
      if (ImGui::DragFloat("##cell", &v, std::max((c.info.max - c.info.min) * 0.002f, 0.01f), c.info.min, c.info.max, fmt))
        set_step_cell(c, r, std::clamp(v, c.info.min, c.info.max));
      if ((c.info.flags & param_on_release) && ImGui::IsItemActive()) hold = true;
      if (repeated) {
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("repeats the last entry; edit to set it for this step");
        ImGui::PopStyleVar();
      }
      ImGui::PopID();
    }
  }
  ImGui::EndTable();
}

void draw_overlay_menu(overlay_view& view, const overlay_gpu& gpu) {
  if (!ImGui::BeginMenu("Overlay layers")) return;
  // One layer at a time unless "Combine layers" is on: several at once bury the tree.
  for (int k = 0; k < overlay_kind_count; ++k) {
    const bool present = (gpu.present >> k) & 1u;
    bool on = (view.kinds >> k) & 1u;
    if (ImGui::MenuItem(overlay_kind_labels[k], nullptr, &on, present)) {
      if (view.combine) view.kinds = on ? view.kinds | (1u << k) : view.kinds & ~(1u << k);
      else view.kinds = on ? 1u << k : 0u;
    }
  }
  ImGui::Separator();
  ImGui::MenuItem("Combine layers", nullptr, &view.combine);
  ImGui::MenuItem("Shadow grid as a slice", nullptr, &view.shadow_slice);
  if (gpu.shadow_max_y > gpu.shadow_min_y) {
    ImGui::SetNextItemWidth(180);
    ImGui::SliderFloat("Slice height (m)", &view.slice_height, gpu.shadow_min_y, gpu.shadow_max_y, "%.2f");
  }
  ImGui::EndMenu();
}

}  // namespace sylva
