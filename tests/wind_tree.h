// The small Honda tree the wind tests grow (CPU and GL), and the wind they blow over it.
#pragma once

#include "generators/lsystem.h"
#include "render/mesh/mesh.h"
#include "render/mesh/wind.h"

namespace sylva_test {

// Honda's tree a after `n` derivations, meshed with six sides and a leaf at each tip.
struct honda_tree {
  sylva::tree_skeleton t;
  sylva::tree_mesh m;
  sylva::mesh_params p;
  explicit honda_tree(int n) {
    sylva::lsystem_params lp;
    lp.derivations = n;
    t = sylva::grow_honda(lp, {});
    p.radial_segments = 6;
    p.leaves.mode = sylva::leaf_mode::tips;
    p.leaves.min_order = 1;
    m = sylva::mesh_tree(t, p);
  }
};

// Wind on, at strength 1.
inline sylva::wind_params blowing() {
  sylva::wind_params w;
  w.enabled = true;
  w.strength = 1.0f;
  return w;
}

}  // namespace sylva_test
