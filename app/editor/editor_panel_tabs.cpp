// The parameter panel's tabs and search (see editor_panel_tabs.h).
#include "app/editor/editor_panel_tabs.h"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <sstream>

namespace sylva {

const char* panel_tab_label(panel_tab t) {
  static const char* labels[] = {"Tree", "Leaves", "Wood and bark", "Scene", "Output", "Pruning"};
  return labels[std::min(int(t), int(panel_tab::count) - 1)];
}

panel_tab tab_of_group(const char* group, bool* known) {
  static const struct { const char* group; panel_tab tab; } table[] = {
      {"Leaves", panel_tab::leaves},          {"Cones and fruit", panel_tab::leaves},
      {"Season", panel_tab::scene},
      {"Wood", panel_tab::wood},              {"Mesh", panel_tab::wood},
      {"Bark mesh", panel_tab::wood},         {"Bark shape", panel_tab::wood},
      {"Materials", panel_tab::wood},         {"Textures", panel_tab::wood},
      {"Sun and sky", panel_tab::scene},      {"Shadows", panel_tab::scene},
      {"Light shafts and fog", panel_tab::scene}, {"Wind", panel_tab::scene},
      {"Render", panel_tab::scene},           {"Level of detail", panel_tab::output},
  };
  for (const auto& row : table)
    if (group && std::strcmp(group, row.group) == 0) {
      if (known) *known = true;
      return row.tab;
    }
  if (known) *known = false;
  return panel_tab::scene;
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
