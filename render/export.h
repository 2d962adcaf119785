// Exporters: glTF 2.0 (.glb/.gltf), OBJ+MTL, and the skeleton JSON (DESIGN §6).
#pragma once

#include <atomic>
#include <functional>
#include <string>

#include "generators/tree_spec.h"
#include "render/mesh.h"

namespace sylva {

struct export_options {
  int step = -1;                        // export the tree as it stood at this step (-1: final)
  bool gltf_instancing = false;         // EXT_mesh_gpu_instancing for leaves instead of baked quads
  bool growth_animation = false;        // glTF: steps 0..N as STEP-interpolated scale keyframes
  float seconds_per_step = 0.5f;
  int max_animation_steps = 64;         // caps on the growth animation's size
  size_t max_animation_triangles = 4000000;
  const std::atomic<uint32_t>* cancel = nullptr;  // non-zero: stop, write nothing
  std::function<void(float)> progress;
  mesh_params mesh;             // the params `m` was built with: re-meshes step views and animation steps
  bool dry_run = false;         // compute export_result.bytes (the size) without writing anything
  int texture_size = 256;       // bark texture edge in pixels (leaves get half, in a 2x2 atlas)
  uint64_t texture_seed = 1;
  // The user's PNGs instead of the procedural textures ("" = procedural). A user leaf texture
  // fills all four cells of the leaf atlas.
  std::string bark_texture, bark_normal_texture, leaf_texture;
};

struct export_info {
  std::string generator;   // generator name, written into the files
  uint64_t seed = 1;
};

struct export_result {
  std::string error;        // "" on success
  size_t bytes = 0;         // size of the main file written
  std::vector<std::string> files;  // every file written
  size_t triangles = 0;     // in the main mesh (all steps for a growth animation)
  int animation_steps = 0;  // steps in the growth animation after the caps
};

// Picks the format from the extension of `path`: .glb .gltf .obj .json. Writes atomically.
export_result export_tree(const tree_skeleton& t, const tree_mesh& m, const export_info& info,
                          const std::string& path, const export_options& o = {});

// The skeleton JSON document (DESIGN §6) as text.
std::string skeleton_json(const tree_skeleton& t, const export_info& info, int step = -1);

}  // namespace sylva
