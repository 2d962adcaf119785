// The parameter panel's tabs and search (see editor_panel_tabs.h).
#include "app/editor/editor_panel_tabs.h"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <iterator>
#include <sstream>

namespace sylva {

namespace {

constexpr const char* panel_tab_labels[] = {"Tree", "Leaves", "Wood and bark", "Scene", "Output", "Pruning"};
static_assert(std::size(panel_tab_labels) == size_t(panel_tab::count), "one label per panel_tab");

// The shared parameters' groups: each one's tab, the struct that declares it, and whether its tab
// shows it after the tab's own controls. ("Render" is the render struct's section name, for any
// parameter before its first group.)
constexpr struct {
  const char* group;
  panel_tab tab;
  shared_params from;
  bool after_controls;
} group_table[] = {
    {"Leaves", panel_tab::leaves, shared_params::mesh, false},
    {"Cones and fruit", panel_tab::leaves, shared_params::mesh, false},
    {"Wood", panel_tab::wood, shared_params::wood, false},
    {"Mesh", panel_tab::wood, shared_params::mesh, false},
    {"Bark mesh", panel_tab::wood, shared_params::mesh, false},
    {"Bark shape", panel_tab::wood, shared_params::mesh, false},
    {"Materials", panel_tab::wood, shared_params::render, false},
    {"Textures", panel_tab::wood, shared_params::render, false},
    {"Season", panel_tab::scene, shared_params::render, false},
    {"Wind", panel_tab::scene, shared_params::render, false},
    {"Sun and sky", panel_tab::scene, shared_params::render, true},
    {"Shadows", panel_tab::scene, shared_params::render, true},
    {"Light shafts and fog", panel_tab::scene, shared_params::render, true},
    {"Render", panel_tab::scene, shared_params::render, true},
    {"Level of detail", panel_tab::output, shared_params::render, false},
};

}  // namespace

const char* panel_tab_label(panel_tab t) { return panel_tab_labels[std::min(int(t), int(panel_tab::count) - 1)]; }

panel_tab tab_of_group(const char* group, bool* known) {
  for (const auto& row : group_table)
    if (group && std::strcmp(group, row.group) == 0) {
      if (known) *known = true;
      return row.tab;
    }
  if (known) *known = false;
  return panel_tab::scene;
}

std::vector<const char*> groups_of_tab(panel_tab tab, shared_params from, bool after_controls) {
  std::vector<const char*> out;
  for (const auto& row : group_table)
    if (row.tab == tab && row.from == from && row.after_controls == after_controls) out.push_back(row.group);
  return out;
}

namespace {

// Whether `word` begins a word of `text`, ignoring ASCII case: "angle" finds "angle" and "angles",
// not "triangles". A word that starts with a non-ASCII byte (a symbol such as "τ") matches anywhere.
bool contains_nocase(const char* text, const std::string& word) {
  if (!text || word.empty()) return word.empty();
  const size_t n = std::strlen(text);
  const bool anywhere = static_cast<unsigned char>(word[0]) >= 0x80;
  for (size_t i = 0; i + word.size() <= n; ++i) {
    if (!anywhere && i > 0 && std::isalnum(static_cast<unsigned char>(text[i - 1]))) continue;
    size_t k = 0;
    while (k < word.size() && std::tolower(static_cast<unsigned char>(text[i + k])) ==
                                  std::tolower(static_cast<unsigned char>(word[k])))
      ++k;
    if (k == word.size()) return true;
  }
  return false;
}

}  // namespace

bool param_matches(const param_info& info, const char* group, const std::string& filter) {
  std::istringstream words(filter);
  std::string w;
  while (words >> w)
    if (!contains_nocase(info.label, w) && !contains_nocase(info.symbol, w) && !contains_nocase(info.key, w) &&
        !contains_nocase(info.help, w) && !contains_nocase(group, w))
      return false;
  return true;
}

}  // namespace sylva
