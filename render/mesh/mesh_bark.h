// The bark stage of mesh_tree (render/mesh/mesh_bark.cpp), inside render/mesh only.
#pragma once

#include <vector>

#include <glm/vec3.hpp>

#include "generators/vec_util.h"
#include "render/mesh/mesh.h"

namespace sylva {

// The bark: the frame, budget, rings and index stages of mesh_tree (their times in st); turn and
// disp are the gnarl, which the leaves follow too.
void mesh_bark(const tree_skeleton& t, const mesh_params& p, tree_mesh& m, mesh_stage_times& st,
               std::vector<rotation_terms>& turn, std::vector<glm::vec3>& disp);

}  // namespace sylva
