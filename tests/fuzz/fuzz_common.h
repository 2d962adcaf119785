// Shared by the libFuzzer harnesses: small, fast growth settings so that one input stays cheap.
#pragma once

#include <cstdlib>
#include <string>

#include "render/mesh/mesh.h"
#include "render/io/preset.h"

namespace sylva {

// Keeps a fuzzed spec to a few steps and a small tree: the harnesses look for crashes and
// undefined behaviour, not for the cost of large trees (the node caps cover that).
inline void make_growth_small(preset& p) {
  std::visit(
      [](auto& gp) {
        using P = std::decay_t<decltype(gp)>;
        gp.node_cap = 1000;
        if constexpr (std::is_same_v<P, self_organizing_params>) {
          gp.steps = std::min(gp.steps, 4);
        } else if constexpr (std::is_same_v<P, space_colonization_params>) {
          gp.steps = std::min(gp.steps, 40);
          gp.points = std::min(gp.points, 300);
          gp.envelope_mesh.clear();  // no file reads from fuzzed text
        } else if constexpr (std::is_same_v<P, guiding_vectors_params>) {
          gp.steps = std::min(gp.steps, 2);
          gp.spacing = std::max(gp.spacing, 0.3f);
          gp.domain_size = glm::min(gp.domain_size, glm::vec3(4));
          for (float& e : gp.step_endpoints) e = std::min(e, 20.0f);
        } else if constexpr (std::is_same_v<P, lsystem_params>) {
          gp.derivations = std::min(gp.derivations, 5);
          gp.module_cap = 1000;
        }
      },
      p.spec.params);
  p.mesh.radial_segments = std::min(p.mesh.radial_segments, 6);
}

// A failed invariant: print it and abort, so libFuzzer keeps the input as a crash.
inline void fuzz_check(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "fuzz invariant failed: %s\n", what);
    std::abort();
  }
}

// Grows the preset made small (make_growth_small) and meshes it, checking the invariants every
// tree keeps: parents precede children and the mesh is valid.
inline void grow_small_and_check(preset& p) {
  make_growth_small(p);
  grow_report report;
  const tree_skeleton t = grow(p.spec, grow_options{}, &report);
  for (size_t i = 0; i < t.size(); ++i) fuzz_check(t.parent[i] < int32_t(i), "parent precedes child");
  const tree_mesh m = mesh_tree(t, p.mesh, p.spec.seed);
  fuzz_check(validate_mesh(m).empty(), "mesh is valid");
}

}  // namespace sylva
