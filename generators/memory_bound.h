// The documented peak memory of one growth: every generator's memory is held by
// caps, so no parameter combination grows past the bound below. The bound covers the growth itself
// (the generator's state and the tree it returns, with its debug overlay); the process, the mesh
// and the renderer come on top (README "Memory").
//
//   bound = fixed + node_cap × per_node + points × per_point
//
// per_node and per_point are the generators' worst cases from their data structures, vector slack
// included (a vector that doubles holds up to 3× its data while it moves), and checked against
// `sylva bench`'s peak RSS on the big workloads in bench/ and on extreme parameters
// (tests/generators/memory_bound_test.cpp, docs/DESIGN-NOTES.md "Memory bound").
#pragma once

#include <string>

#include "generators/tree_spec.h"

namespace sylva {

struct memory_bound {
  double fixed = 0;       // bytes: tables, grids with their own caps, the overlay sample
  double nodes = 0;       // the node cap
  double per_node = 0;    // bytes per node
  double points = 0;      // markers, attraction points, graph points or L-system modules, at their cap
  double per_point = 0;   // bytes per point
  const char* points_are = "";
  double bytes() const { return fixed + nodes * per_node + points * per_point; }
};

// The bound of this request, at its own caps and point counts.
memory_bound growth_memory_bound(const tree_spec& spec);
// The worst case over every parameter in its range, for `sylva params` and the README.
memory_bound worst_memory_bound(int generator);
// "1.23 GB" from 1e9 bytes up, else "456 MB": the growth and mesh bounds' messages.
std::string size_text(double bytes);
// One line: "peak growth memory <= 1.23 GB = 1.2 MB + node_cap x 200 B + ...".
std::string memory_bound_text(int generator);

}  // namespace sylva
