// The self-organizing generator's perception cone in the shadow environment (Palubicki et al.
// 2009 §4.2): the voxels a bud sees, and the least-shadowed one among them.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include <glm/vec3.hpp>

#include "generators/job_pool.h"
#include "generators/self_organizing_grid.h"
#include "generators/skeleton.h"

namespace sylva {

// Voxel offsets whose voxel can hold a point within the perception reach of a bud somewhere in
// voxel 0, in metres too, and by component for the vectorised cone test.
struct perception_cone {
  std::vector<glm::ivec3> offset;
  std::vector<glm::vec3> metres;
  std::vector<float> x, y, z;
  int radius = 0;   // in voxels
};
// perception_distance and voxel_size in internode lengths, voxel_metres the voxel's edge.
perception_cone make_perception_cone(float perception_distance, float voxel_size, float voxel_metres);

// The search for the least-shadowed voxel, in two parts: scan_cone reads the grid only (the
// environment stays as it was at the step's start) and lists the choices the search made, in
// order: each new best (ties = 1) and each tie met (ties = its count so far); pick_optimal replays
// the list on the shared RNG, drawing exactly the numbers a one-pass search draws, so a step's
// cones can be scanned in parallel first (scan_cones) and their choices replayed in order.
struct cone_choice {
  int ties;
  glm::vec3 dir;
};
struct cone_scratch {   // one per thread
  std::vector<uint8_t> in_cone;
  std::vector<const float*> near_chunks;
};
void scan_cone(const shadow_grid& grid, const perception_cone& cone, float cos_theta, float reach, const glm::vec3& pos,
               const glm::ivec3& v0, const glm::vec3& def, cone_scratch& sc, std::vector<cone_choice>& choices);
// Many cones' scans at once (scan_cones): cone j's choices are choices.count(j) from first(j).
struct cone_scans {
  chunked_results<cone_choice> choices;
  std::vector<cone_scratch> scratch;   // per chunk
};
// scan_cone for cones 0 .. count - 1, each from cone_of(j, pos, voxel, def), in chunks on the
// shared pool (job_pool.h); every cone's choices are the ones scan_cone lists for it alone.
void scan_cones(const shadow_grid& grid, const perception_cone& cone, float cos_theta, float reach, size_t count,
                const std::function<void(size_t, glm::vec3&, glm::ivec3&, glm::vec3&)>& cone_of, cone_scans& out);
// The direction to the chosen voxel; def when the cone held none. Ties go to the voxel closest to
// the default direction, then to the seeded RNG (reservoir sampling: each tied voxel is kept with
// probability 1/ties): seed 000's trees leaned because ties took the first voxel found.
glm::vec3 pick_optimal(rng& r, const cone_choice* choices, size_t count, const glm::vec3& def);

}  // namespace sylva
