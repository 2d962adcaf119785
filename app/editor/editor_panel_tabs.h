// How the parameter panel is organised for a newcomer: tabs in the order one meets a tree (Tree,
// Leaves, Wood and bark, Scene, Output, then Pruning with the growth phases), and a search box that
// filters every parameter by name, symbol, key or help. Display-free, so it is tested.
#pragma once

#include <string>
#include <vector>

#include "generators/params.h"

namespace sylva {

enum class panel_tab : int { tree, leaves, wood, scene, output, pruning, count };
const char* panel_tab_label(panel_tab t);

// The params struct that declares a group of the shared (not generator) parameters.
enum class shared_params { mesh, wood, render };

// The tab of a group of the shared parameters: mesh, wood and render. Every group they declare
// has one; `known` is false for a group the table (editor_panel_tabs.cpp) does not list (a test
// keeps the table complete), which then shows under Scene.
panel_tab tab_of_group(const char* group, bool* known = nullptr);

// The groups `tab` shows from the struct `from` (in the struct's order), those before the tab's
// own controls or (after_controls) those after them: the Scene tab's time-of-day buttons come
// between its season and wind and its sky. From the same table as tab_of_group.
std::vector<const char*> groups_of_tab(panel_tab tab, shared_params from, bool after_controls = false);

// Whether a parameter matches the search text: every word of `filter` begins a word, ignoring
// ASCII case, of its label, symbol, key, help or group ("angle" finds "Branch angle", not
// "triangles"; a symbol matches anywhere). An empty filter matches everything.
bool param_matches(const param_info& info, const char* group, const std::string& filter);

}  // namespace sylva
