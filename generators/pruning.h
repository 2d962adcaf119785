// Pruning: cuts made during growth, which the generators answer by regrowing.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "generators/skeleton.h"

namespace sylva {

enum class prune_shape : int { branch = 0, outside_ellipsoid = 1, outside_box = 2 };
inline constexpr const char* prune_shape_names[] = {"branch", "outside_ellipsoid", "outside_box", nullptr};

// A cut, made at the top of growth step `step` (after the tree of step − 1 is complete, before
// anything of step `step` is computed). A branch cut names its internode by a point, not by a node
// index, so it survives a regrow with changed earlier parameters: the internode ending at the node
// nearest `point` among those alive at step − 1, within `reach`. The brush shapes (centre `point`,
// half extents `size`) shear at their surface: every internode that starts inside and ends outside
// is cut; what never entered the shape (the trunk below a crown) stays. Either way the internode's
// whole subtree goes with it.
struct prune_cut {
  int step = 1;
  prune_shape shape = prune_shape::branch;
  glm::vec3 point{0};
  glm::vec3 size{1};     // brushes: half extents in metres
  float reach = 0.25f;   // branch: metres
  bool operator==(const prune_cut&) const = default;
};

// Marks in `removed` (one byte per node, resized to the tree) the nodes the cut takes: those alive
// at step − 1 and their alive descendants. Roots are never cut. Returns false when a branch cut
// finds no node within reach (the caller reports it).
bool select_cut(const tree_skeleton& t, const prune_cut& c, std::vector<uint8_t>& removed);

// What a generator calls at the top of step `step`: applies every cut of that step, sets died =
// step on each node it removes and returns them, ascending. A branch cut that finds nothing is
// reported in rep (missed_cuts, message) and changes nothing.
std::vector<int32_t> apply_cuts(tree_skeleton& t, const std::vector<prune_cut>* cuts, int step, grow_report& rep);

struct tree_spec;

// Checks a cut against the spec: a generator that supports cuts (not text L-systems), a step in
// 1..last step, a finite point, positive reach and size. Returns "" or a message.
std::string check_cut(const tree_spec& spec, const prune_cut& c);
std::string check_cuts(const tree_spec& spec);
// Appends a checked cut; on a bad one returns the message and leaves the spec as it was.
// The field its shape does not use (a branch's size, a brush's reach) is kept at its default.
std::string add_cut(tree_spec& spec, const prune_cut& c);
// What a cut does in the spec's generator (the panel's help and the design notes).
const char* cut_response(const tree_spec& spec);

}  // namespace sylva
