// Names for undo entries (see editor_undo_names.h).
#include "app/editor/editor_undo_names.h"

#include <type_traits>
#include <vector>

namespace sylva {

namespace {

// Appends the label of every parameter that differs between two params structs of one type.
template <class P>
void changed_labels(const P& before, const P& after, std::vector<std::string>& out) {
  std::vector<const void*> old;
  visit_params(before, [&](const auto& value, const param_info&) { old.push_back(&value); });
  size_t i = 0;
  visit_params(after, [&](const auto& value, const param_info& info) {
    using T = std::remove_cvref_t<decltype(value)>;
    if (!(value == *static_cast<const T*>(old[i++]))) out.push_back(info.label);
  });
}

}  // namespace

std::string change_name(const preset& before, const preset& after) {
  if (before == after) return "";
  if (before.name != after.name) return "Open " + after.name;
  const tree_spec &a = before.spec, &b = after.spec;
  if (a.params.index() != b.params.index()) return "Generator";
  if (a.cuts.size() < b.cuts.size()) return "Cut at step " + std::to_string(b.cuts.back().step);
  if (a.cuts.size() > b.cuts.size()) return "Delete a cut";
  if (!(a.cuts == b.cuts)) return "Cuts";
  std::vector<std::string> labels;
  if (a.seed != b.seed) labels.push_back("Seed");
  if (!(a.keyframes == b.keyframes)) labels.push_back("Keyframes");
  std::visit(
      [&](const auto& pa) {
        using P = std::decay_t<decltype(pa)>;
        changed_labels(pa, std::get<P>(b.params), labels);
      },
      a.params);
  changed_labels(a.wood, b.wood, labels);
  changed_labels(before.mesh, after.mesh, labels);
  changed_labels(before.render, after.render, labels);
  if (labels.empty()) return "Edit";
  if (labels.size() == 1) return labels[0];
  return labels[0] + " and " + std::to_string(labels.size() - 1) + " more";
}

}  // namespace sylva
