// The parameter panel: one slider per declared parameter (visit_params), grouped as declared.
#include "app/editor/editor_state.h"
#include "app/editor/editor_panel_tabs.h"
#include "app/editor/editor_sliders.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>
#include <random>
#include <type_traits>
#include <utility>
#include <variant>

#include <imgui.h>
#include <imgui_stdlib.h>

namespace sylva::ed {

namespace {

// ---------------------------------------------------------------- parameter panel

// Collects pointers to each field of a defaults struct in visit order, so the drawer can reset
// field i to its default without a second declaration of anything.
template <class P>
std::vector<const void*> default_pointers(const P& defaults) {
  std::vector<const void*> out;
  visit_params(defaults, [&](const auto& value, const param_info&) { out.push_back(&value); });
  return out;
}

// A thin bar under a drag field: where the value sits in its range (on the log scale when log).
void range_bar(float value, const param_info& info) {
  const ImVec2 lo = ImGui::GetItemRectMin(), hi = ImGui::GetItemRectMax();
  const float w = std::min(ImGui::CalcItemWidth(), hi.x - lo.x);
  float f = 0;
  if (slider_is_log(info) && info.min > 0)
    f = std::log(std::max(value, info.min) / info.min) / std::log(info.max / info.min);
  else if (info.max > info.min)
    f = (value - info.min) / (info.max - info.min);
  f = std::clamp(f, 0.0f, 1.0f);
  ImGui::GetWindowDrawList()->AddRectFilled(ImVec2(lo.x, hi.y - 2 * ui_scale), ImVec2(lo.x + w * f, hi.y),
                                            IM_COL32(90, 150, 230, 255));
}

// A path parameter's field: typing edits `edit.text`; Enter or leaving the field applies it to `value`.
void draw_path_field(const char* label, std::string& value, path_field_edit& edit) {
  const ImGuiID id = ImGui::GetID(label);
  std::string shown = edit.id == id ? edit.text : value;
  const bool enter = ImGui::InputText(label, &shown, ImGuiInputTextFlags_EnterReturnsTrue);
  const bool active = ImGui::IsItemActive();
  if (active) edit.id = id, edit.text = shown;
  if (enter || ImGui::IsItemDeactivatedAfterEdit()) value = shown;
  if (!active && edit.id == id) edit.id = 0, edit.text.clear();
}

struct param_drawer {
  const std::vector<const void*>& defaults;
  const char* section;     // header for parameters before the first group
  const char* source;      // the paper the struct's parameters come from, with a trailing newline, or nullptr
  bool show_advanced;
  bool hold = false;       // an apply-on-release item is active
  bool open = true;
  bool header_drawn = false;
  const char* pending_header = nullptr;   // drawn before the group's first shown parameter
  const char* last_header = nullptr;      // the header drawn last
  bool relevant = true;                   // param_relevant() for the parameter being visited
  std::vector<step_column>* steps = nullptr;   // the struct's per-step schedules, drawn as one table
  const tree_spec* keyed_spec = nullptr;       // growth phases: mark the parameters keyed at keyed_step
  int keyed_step = -1;
  bool steps_drawn = false;
  size_t index = 0;
  const char* group_now = nullptr;             // the group of the parameter being visited
  const std::vector<const char*>* groups = nullptr;   // only these groups (nullptr: all)
  const std::string* filter = nullptr;         // the search box's text (nullptr or empty: no search)
  path_field_edit* path_edit = nullptr;        // the path being typed, if any
  std::map<std::string, std::array<float, 2>>* path_at = nullptr;   // where path fields are drawn
  int matched = 0;                             // parameters shown (or, count_only, that would be)
  bool count_only = false;                     // count the search's matches, draw nothing

  // "symbol  label##key" in a fixed buffer: building the panel allocates nothing per frame.
  char buffer[256];
  const char* label(const param_info& info) {
    if (info.symbol && *info.symbol) std::snprintf(buffer, sizeof buffer, "%s  %s##%s", info.symbol, info.label, info.key);
    else std::snprintf(buffer, sizeof buffer, "%s##%s", info.label, info.key);
    return buffer;
  }

  template <class T>
  void operator()(T& value, const param_info& info) {
    const T& def = *static_cast<const T*>(defaults[index++]);
    if (info.group || !header_drawn) {
      pending_header = info.group ? info.group : section;
      group_now = pending_header;
      header_drawn = true;
    }
    // Hidden in the current mode; multi-line texts get their own panel (draw_generator_panel).
    if (!relevant || (info.flags & param_multiline)) return;
    // Another tab's group, or not what the search asks for.
    if (groups && std::none_of(groups->begin(), groups->end(), [&](const char* g) { return std::strcmp(g, group_now) == 0; }))
      return;
    const bool searching = filter && !filter->empty();
    if (searching && !param_matches(info, group_now, *filter)) return;
    ++matched;
    if (count_only) return;
    // A group that continues the one just drawn (nested structs may both name "Leaves") gets no
    // second header.
    if (pending_header && last_header && std::strcmp(pending_header, last_header) == 0) pending_header = nullptr;
    if (pending_header) {
      if (searching) ImGui::SetNextItemOpen(true);
      open = ImGui::CollapsingHeader(pending_header, ImGuiTreeNodeFlags_DefaultOpen);
      last_header = pending_header;
      pending_header = nullptr;
    }
    if (!open || ((info.flags & param_advanced) && !show_advanced && !searching)) return;
    if constexpr (std::is_same_v<T, std::vector<float>>) {
      if (steps && !steps->empty()) {   // all schedules in one table, where the first one is declared
        if (!steps_drawn) draw_step_table(*steps, hold);
        steps_drawn = true;
        return;
      }
    }
    ImGui::PushID(info.key);
    const char* l = label(info);
    const int slider_flags = slider_is_log(info) ? ImGuiSliderFlags_Logarithmic : 0;
    if constexpr (std::is_same_v<T, float>) {
      // A drag, not a jump to the pointer: the whole range takes ~600 pixels, Shift a tenth of
      // that (ImGui speeds Shift drags up tenfold, hence the extra tenth); Ctrl+click types.
      const bool fine = ImGui::GetIO().KeyShift;
      const std::string fmt = slider_format(info);
      ImGui::DragFloat(l, &value, drag_speed(info, fine) * (fine ? 0.1f : 1.0f), info.min, info.max, fmt.c_str(),
                       slider_flags | ImGuiSliderFlags_AlwaysClamp);
      range_bar(value, info);
    } else if constexpr (std::is_same_v<T, int>) {
      if (info.max - info.min > 200) {   // wide integer ranges drag too (point counts, caps)
        const bool fine = ImGui::GetIO().KeyShift;
        ImGui::DragInt(l, &value, std::max(drag_speed(info, fine) * (fine ? 0.1f : 1.0f), 0.02f), int(info.min),
                       int(info.max), "%d", slider_flags | ImGuiSliderFlags_AlwaysClamp);
        range_bar(float(value), info);
      } else {
        ImGui::SliderInt(l, &value, int(info.min), int(info.max), "%d", slider_flags);
      }
    } else if constexpr (std::is_same_v<T, bool>) {
      ImGui::Checkbox(l, &value);
    } else if constexpr (std::is_enum_v<T>) {
      int v = int(value);
      const int n = option_count(info);
      if (ImGui::Combo(l, &v, info.options, n)) value = T(v);
    } else if constexpr (std::is_same_v<T, glm::vec3>) {
      // A colour is a vec3 on [0,1] that is not a direction; sizes and offsets get plain drags.
      const bool colour = !(info.flags & param_direction) && info.min == 0 && info.max == 1;
      if (colour) ImGui::ColorEdit3(l, &value.x, ImGuiColorEditFlags_Float);
      else ImGui::DragFloat3(l, &value.x, std::max((info.max - info.min) * 0.001f, 0.001f), info.min, info.max);
    } else if constexpr (std::is_same_v<T, std::string>) {
      if (info.flags & param_multiline) {
        ImGui::TextUnformatted(info.label);
        ImGui::InputTextMultiline("##text", &value, ImVec2(-1, 180));
      } else if (info.flags & param_path) {
        // A path loads a file: it applies on Enter or when the field is left, not on every keystroke.
        draw_path_field(l, value, *path_edit);
        if (path_at) (*path_at)[info.key] = {0.5f * (ImGui::GetItemRectMin().x + ImGui::GetItemRectMax().x),
                                             0.5f * (ImGui::GetItemRectMin().y + ImGui::GetItemRectMax().y)};
      } else {
        ImGui::InputText(l, &value);
      }
    } else if constexpr (std::is_same_v<T, std::vector<float>>) {
      ImGui::TextUnformatted(l, std::strstr(l, "##"));
      for (size_t i = 0; i < value.size(); ++i) {
        ImGui::PushID(int(i));
        if (i) ImGui::SameLine();
        ImGui::SetNextItemWidth(52);
        ImGui::DragFloat("##v", &value[i], (info.max - info.min) * 0.002f, info.min, info.max, "%.2f");
        ImGui::PopID();
      }
      ImGui::SameLine();
      if (ImGui::SmallButton("+")) value.push_back(value.empty() ? info.min : value.back());
      ImGui::SameLine();
      if (ImGui::SmallButton("-") && !value.empty()) value.pop_back();
    } else if constexpr (std::is_same_v<T, std::vector<glm::vec3>>) {
      ImGui::TextUnformatted(l, std::strstr(l, "##"));
      for (size_t i = 0; i < value.size(); ++i) {
        ImGui::PushID(int(i));
        ImGui::DragFloat3("##v", &value[i].x, 0.01f, info.min, info.max);
        ImGui::PopID();
      }
      if (ImGui::SmallButton("+")) value.push_back(value.empty() ? glm::vec3(0) : value.back());
      ImGui::SameLine();
      if (ImGui::SmallButton("-") && !value.empty()) value.pop_back();
    }
    // The help beside the panel, not over it, and not while the slider is dragged: the tooltip
    // must not cover the sliders next to this one.
    if (ImGui::IsItemHovered() && !ImGui::IsItemActive() && !ImGui::IsMouseDown(ImGuiMouseButton_Left) && info.help && *info.help) {
      ImGui::SetNextWindowPos(ImVec2(panel_width() + 8 * ui_scale, ImGui::GetItemRectMin().y));
      ImGui::BeginTooltip();
      ImGui::PushTextWrapPos(ImGui::GetFontSize() * 30);
      ImGui::Text("%s\n%s%s(drag; Shift: fine; Ctrl+click: type; right-click: reset to default)", info.help,
                  source ? "Model: " : "", source ? source : "");
      ImGui::PopTextWrapPos();
      ImGui::EndTooltip();
    }
    if (ImGui::IsItemClicked(ImGuiMouseButton_Right) && !(value == def)) value = def;
    if ((info.flags & param_on_release) && ImGui::IsItemActive()) hold = true;
    if (keyed_spec && keyed_at(*keyed_spec, info.key, keyed_step)) {
      ImGui::SameLine(0, 2);
      ImGui::TextColored(ImVec4(0.5f, 0.85f, 1, 1), "•");
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("Keyed at step %d (Growth phases)", keyed_step);
    }
    ImGui::PopID();
  }
};

// True when the seed cannot change the skeleton (cached per L-system source).
bool skeleton_is_deterministic(const tree_spec& spec) {
  const auto* l = std::get_if<lsystem_params>(&spec.params);
  if (!l) return false;
  if (l->mode == lsystem_mode::honda) return true;
  static std::string cached_source;
  static bool cached = false;
  if (l->source != cached_source) {
    cached_source = l->source;
    lsystem_program prog;
    cached = compile_lsystem(l->source, prog).ok() && l->source.find("rand") == std::string::npos;
    if (cached)
      for (const lsystem_rule& r : prog.rules)
        if (r.successors.size() > 1) cached = false;
  }
  return cached;
}

// The paper each generator's parameters come from, named in every tooltip.
template <class P>
const char* param_source() {
  if constexpr (std::is_same_v<P, self_organizing_params>)
    return "Palubicki et al. 2009, Self-organizing tree models for image synthesis (SIGGRAPH)\n";
  else if constexpr (std::is_same_v<P, space_colonization_params>)
    return "Runions, Lane & Prusinkiewicz 2007, Modeling trees with a space colonization algorithm\n";
  else if constexpr (std::is_same_v<P, guiding_vectors_params>)
    return "Xu & Mould 2015, Procedural tree modeling with guiding vectors\n";
  else if constexpr (std::is_same_v<P, lsystem_params>)
    return "Honda 1971; Prusinkiewicz & Lindenmayer 1990, The Algorithmic Beauty of Plants (ch. 1-2)\n";
  else if constexpr (std::is_same_v<P, wood_params>)
    return "Beam bending with permanent set (Jirasek, Prusinkiewicz & Moulia 2000); green wood from the USDA Wood Handbook 2010\n";
  else
    return nullptr;
}

// Edits are noticed by comparing documents (record_undo, post_if_changed), so drawers return nothing.
// Returns the parameters shown (count_only: that match the search, none drawn).
template <class P>
int draw_params(P& p, const char* section, editor_state& e, const tree_spec* keyed = nullptr,
                const std::vector<const char*>* groups = nullptr, bool generator_leaves = true, bool count_only = false) {
  static const P defaults{};
  static const std::vector<const void*> pointers = default_pointers(defaults);
  param_drawer d{pointers, section, param_source<P>(), e.show_advanced};
  d.count_only = count_only;
  d.groups = groups;
  d.filter = &e.panel_search;
  d.path_edit = &e.path_edit;
  d.path_at = &e.path_field_at;
  std::vector<step_column> steps = collect_step_columns(p);
  d.steps = &steps;
  d.keyed_spec = keyed;
  d.keyed_step = e.step;
  visit_params(p, [&](auto& value, const param_info& info) {
    d.relevant = editor_shows(std::as_const(p), &value, info, generator_leaves);
    d(value, info);
  });
  e.hold_post |= d.hold;
  return d.matched;
}


// The parameters of `p` in `groups` back to their defaults (the struct's own, as the panel's reset).
template <class P>
void reset_groups(P& p, std::initializer_list<const char*> groups) {
  static const P defaults{};
  static const std::vector<const void*> pointers = default_pointers(defaults);
  size_t i = 0;
  const char* group = nullptr;
  visit_params(p, [&](auto& value, const param_info& info) {
    using T = std::remove_reference_t<decltype(value)>;
    const T& def = *static_cast<const T*>(pointers[i++]);
    if (info.group) group = info.group;
    if (group && std::any_of(groups.begin(), groups.end(), [&](const char* g) { return std::strcmp(g, group) == 0; })) value = def;
  });
}

}  // namespace

void switch_generator(editor_state& e, int g) {
  preset& doc = e.cur().doc;
  doc.spec.params = default_params(g);
  doc.spec.keyframes.clear();   // they name the old generator's parameters
  reset_groups(doc.mesh, {"Leaves", "Cones and fruit"});
  reset_groups(doc.render, {"Materials", "Textures"});
  const std::string label = generator_labels[g];
  doc.name = "New " + label.substr(0, label.find(" ("));   // "New Self-organizing" (the A/B labels)
  doc.description.clear();
  doc.tags.clear();
  e.frame_new = true;
}

namespace {

// The Tree tab: the generator (shown while searching too), its seed and its parameters (keyed at
// the step with "From this step on"), and its own panels (L-system text, envelope mesh...); while
// searching, the generator's parameters and #define constants that match. Returns how many match.
int draw_tree_tab(editor_state& e, std::string& key_error, bool searching, bool count_only = false) {
  tree_spec& spec = e.cur().doc.spec;
  if (!count_only) {
    int g = int(spec.params.index());
    if (ImGui::Combo("Generator", &g, generator_labels, generator_count) && g != int(spec.params.index()))
      switch_generator(e, g);
  }
  if (!searching) {
    int seed = int(spec.seed & 0x7fffffff);
    if (ImGui::InputInt("Seed", &seed)) spec.seed = uint64_t(std::max(seed, 0));
    ImGui::SameLine();
    // Randomize only where the seed changes something: Honda's model and L-systems without
    // stochastic productions or rand() are deterministic; then only the leaf scatter uses the seed.
    const bool random_tree = !skeleton_is_deterministic(spec);
    const bool random_leaves = e.cur().doc.mesh.leaves_enabled;
    if (!random_tree && !random_leaves) ImGui::BeginDisabled();
    if (ImGui::Button("Randomize")) spec.seed = std::random_device{}() & 0x7fffffff;
    if (!random_tree && !random_leaves) ImGui::EndDisabled();
    if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled) && !random_tree)
      ImGui::SetTooltip(random_leaves ? "This generator is deterministic: a new seed only scatters the leaves differently"
                                      : "This generator is deterministic and leaves are off: the seed changes nothing");
    // Growth phases: with "from this step on", the panel shows the values in effect at the scrubbed
    // step and an edit keys the new value there (app/editor/editor_keyframes.h).
    draw_from_step_switch(e.keys, spec, e.step);
  }
  const bool generator_leaves = e.cur().doc.mesh.leaves.mode == leaf_mode::generator;
  const char* section = generator_labels[spec.params.index()];
  int n = 0;
  if (e.keys.from_step && e.step >= 1) {
    const generator_params before = params_at_step(spec, e.step);
    generator_params shown = before;
    std::visit([&](auto& p) { n = draw_params(p, section, e, &spec, nullptr, generator_leaves, count_only); }, shown);
    if (!(shown == before)) key_error = key_edits(spec, before, shown, e.step);
  } else {
    std::visit([&](auto& p) { n = draw_params(p, section, e, &spec, nullptr, generator_leaves, count_only); }, spec.params);
  }
  if (searching) n += draw_matching_constants(e.generator_panels, spec, e.panel_search, count_only);
  else draw_generator_panel(e.generator_panels, spec, e.cur().shown.get());
  return n;
}

// Time-of-day presets: a starting point for the lighting sliders.
void draw_time_of_day(editor_state& e) {
  render_params& rp = e.cur().doc.render;
  ImGui::Separator();
  ImGui::TextUnformatted("Time of day");
  ImGui::SameLine();
  if (ImGui::SmallButton("Noon")) {
    rp.sun_elevation = 70, rp.sun_azimuth = 25, rp.sun_color = {1.0f, 0.97f, 0.92f}, rp.sun_intensity = 2.4f;
    rp.sky_zenith = {0.22f, 0.42f, 0.85f}, rp.sky_horizon = {0.72f, 0.83f, 0.95f};
    rp.fog_density = 0.005f, rp.haze = 0.0003f;   // a clear midday: little air to light up
  }
  ImGui::SameLine();
  if (ImGui::SmallButton("Golden hour")) {
    rp.sun_elevation = 10, rp.sun_azimuth = std::remainder(e.camera.yaw + 60.0f, 360.0f), rp.sun_color = {1.0f, 0.72f, 0.42f}, rp.sun_intensity = 2.0f;
    rp.sky_zenith = {0.28f, 0.38f, 0.68f}, rp.sky_horizon = {0.95f, 0.76f, 0.55f};
    rp.fog_density = 0.018f, rp.haze = 0.0005f;
  }
  ImGui::SameLine();
  if (ImGui::SmallButton("Backlit rays")) {   // the sun straight behind the tree as seen now
    place_sun_behind(rp, e.camera.yaw);
    rp.sun_color = {1.0f, 0.88f, 0.7f}, rp.sun_intensity = 2.2f;
    if (rp.shafts == light_shafts::off) rp.shafts = light_shafts::volumetric;
    rp.fog_density = std::max(rp.fog_density, 0.025f);   // enough air for the shafts to show
  }
}

// One tab's contents; while searching, only its parameters that match. Returns how many
// parameters it shows (count_only: how many match the search, nothing drawn).
int draw_tab(editor_state& e, panel_tab t, std::string& key_error, bool count_only) {
  // The groups of the shared parameters each tab shows (editor_panel_tabs.h).
  using sp = shared_params;
  static const std::vector<const char*> leaves = groups_of_tab(panel_tab::leaves, sp::mesh),
                                        wood = groups_of_tab(panel_tab::wood, sp::wood),
                                        bark_mesh = groups_of_tab(panel_tab::wood, sp::mesh),
                                        materials = groups_of_tab(panel_tab::wood, sp::render),
                                        season_wind = groups_of_tab(panel_tab::scene, sp::render),
                                        sky = groups_of_tab(panel_tab::scene, sp::render, true),
                                        output = groups_of_tab(panel_tab::output, sp::render);
  const bool searching = !e.panel_search.empty();
  tree_spec& spec = e.cur().doc.spec;
  preset& doc = e.cur().doc;
  int n = 0;
  switch (t) {
    case panel_tab::tree: return draw_tree_tab(e, key_error, searching, count_only);
    case panel_tab::leaves: return draw_params(doc.mesh, "Mesh", e, nullptr, &leaves, true, count_only);
    case panel_tab::wood:
      n += draw_params(spec.wood, "Wood", e, nullptr, &wood, true, count_only);
      n += draw_params(doc.mesh, "Mesh", e, nullptr, &bark_mesh, true, count_only);
      return n + draw_params(doc.render, "Render", e, nullptr, &materials, true, count_only);
    case panel_tab::scene:
      n += draw_params(doc.render, "Render", e, nullptr, &season_wind, true, count_only);
      if (!searching) draw_time_of_day(e);
      return n + draw_params(doc.render, "Render", e, nullptr, &sky, true, count_only);
    case panel_tab::output:
      n = draw_params(doc.render, "Render", e, nullptr, &output, true, count_only);
      if (!searching) draw_output_extras(e);
      return n;
    case panel_tab::pruning:
      if (searching) return 0;
      if (draw_prune_panel(e.prune, spec, e.cur().shown.get(), e.step, key_error)) clear_error(e);
      if (draw_keyframe_panel(e.keys, spec, e.step, key_error)) clear_error(e);
      return 0;
    case panel_tab::count: break;
  }
  return 0;
}

}  // namespace

void draw_panel(editor_state& e, float top, float bottom) {
  ImGui::SetNextWindowPos(ImVec2(0, top));
  ImGui::SetNextWindowSize(ImVec2(panel_width(), bottom - top));
  ImGui::Begin("Parameters", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                   ImGuiWindowFlags_NoTitleBar);
  ImGui::PushItemWidth(-205 * ui_scale);
  if (const ab_action a = draw_ab_controls(e.ab); a != ab_action::none) handle_ab(e, a);
  if (follow_step(e.keys, e.step)) set_status(e, "\"From this step on\" is off again: the timeline moved to another step");
  ImGui::SetNextItemWidth(-1);
  ImGui::InputTextWithHint("##search", "Search parameters: name, symbol or help", &e.panel_search);
  const bool searching = !e.panel_search.empty();
  std::string key_error;
  // While searching, each tab keeps its place and shows its own matches, their count in its label;
  // a new search opens the first tab with any, and none at all says so.
  int counts[int(panel_tab::count)] = {};
  e.search_matches = -1;
  if (searching) {
    e.search_matches = 0;
    for (int t = 0; t < int(panel_tab::count); ++t) e.search_matches += counts[t] = draw_tab(e, panel_tab(t), key_error, true);
    if (e.search_matches == 0)
      ImGui::TextColored(ImVec4(1, 0.8f, 0.4f, 1), "No parameter matches \"%s\" (names, symbols, help and #define comments)",
                         e.panel_search.c_str());
  }
  const bool new_search = e.panel_search != e.searched;
  e.searched = e.panel_search;
  int open_tab = -1;   // a new search whose matches are all in other tabs opens the first of them
  if (searching && new_search && e.search_matches > 0 && counts[e.panel_tab_shown] == 0)
    for (int t = 0; t < int(panel_tab::count) && open_tab < 0; ++t)
      if (counts[t] > 0) open_tab = t;
  if (ImGui::BeginTabBar("##panel_tabs")) {
    for (int t = 0; t < int(panel_tab::count); ++t) {
      char label[64];
      if (searching) std::snprintf(label, sizeof label, "%s (%d)###tab%d", panel_tab_label(panel_tab(t)), counts[t], t);
      else std::snprintf(label, sizeof label, "%s###tab%d", panel_tab_label(panel_tab(t)), t);
      if (!ImGui::BeginTabItem(label, nullptr, t == open_tab ? ImGuiTabItemFlags_SetSelected : 0)) continue;
      e.panel_tab_shown = t;
      if (searching && counts[t] == 0 && e.search_matches > 0) ImGui::TextDisabled("No match in this tab: see the tabs with a count.");
      draw_tab(e, panel_tab(t), key_error, false);
      ImGui::EndTabItem();
    }
    ImGui::EndTabBar();
  }
  if (!key_error.empty()) set_status(e, key_error, true);
  ImGui::PopItemWidth();
  ImGui::End();
}

}  // namespace sylva::ed
