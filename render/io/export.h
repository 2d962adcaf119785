// Exporters: glTF 2.0 (.glb/.gltf), OBJ+MTL, and the skeleton JSON (docs/design/10-files.md).
#pragma once

#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "generators/archetypes.h"
#include "generators/tree_spec.h"
#include "render/mesh/mesh.h"
#include "render/mesh/render_params.h"
#include "render/mesh/season.h"

namespace sylva {

// Level of detail (render/mesh/lod.h): the lower levels written beside the main mesh (LOD0).
struct export_lod_level {
  const tree_mesh* mesh = nullptr;   // node ids of the exported skeleton, final tree
  float coverage = 0;                // screen coverage down to which this level is shown
  size_t budget = 0;                 // its triangle budget, recorded in extras
};
// The impostor: a billboard atlas of `views` views around the trunk, `columns` x `rows` cells, view
// k at azimuth 360 k / views degrees from +Z toward +X; colour with alpha, and normals.
struct export_impostor {
  std::string color_png, normal_png;
  int views = 8, columns = 4, rows = 2;
  float width = 1, height = 1;       // metres one cell spans
  glm::vec3 centre{0};               // world point at the centre of every cell
  float coverage = 0;                // shown below this screen coverage
};

struct export_options {
  int step = -1;                        // export the tree as it stood at this step (-1: final)
  bool gltf_instancing = false;         // EXT_mesh_gpu_instancing for leaves instead of baked quads
  // Baked leaves as the mesh's blades (render/mesh/leaf_blade.h, the hero profile) instead of flat
  // cards: 24 triangles a leaf instead of 4, so off by default (docs/design/03-foliage.md). An
  // instanced prototype is always the blade when the mesh has blades on.
  bool baked_blades = false;
  // glTF: KHR_mesh_quantization (16-bit positions on a grid per mesh, 8-bit normals and tangents)
  // and EXT_meshopt_compression of every buffer view; textures without alpha as JPEG.
  bool compact = false;
  bool growth_animation = false;        // glTF: steps 0..N as STEP-interpolated scale keyframes
  float seconds_per_step = 0.5f;
  int max_animation_steps = 64;         // caps on the growth animation's size
  size_t max_animation_triangles = 4000000;
  const std::atomic<uint32_t>* cancel = nullptr;  // non-zero: stop, write nothing
  std::function<void(float)> progress;
  mesh_params mesh;             // the params `m` was built with: re-meshes step views and animation steps
  bool dry_run = false;         // compute export_result.bytes (the size) without writing anything
  // Materials (fill them from the preset with apply_render_params). Bark: one material from the
  // archetype's texture set; leaves: one material per leaf archetype present (leaf_instance::texture).
  int texture_size = 512;               // edge in pixels of every texture (bark and each leaf card)
  uint64_t texture_seed = 1;
  bark_archetype bark = bark_archetype::furrowed;
  glm::vec3 bark_color{0.45f, 0.34f, 0.25f};  // linear RGB tints, baked into the procedural textures'
  glm::vec3 leaf_color{0.30f, 0.55f, 0.18f};  // PNGs by tinted_texture (the viewport's formula)
  // Bark colour by height (render/mesh/bark_tint.h): with bark_base_height > 0 the texture takes the
  // brighter tint and the bark's COLOR_0 the blend; OBJ and FBX keep the bark colour alone.
  glm::vec3 bark_base_color{0.3f, 0.28f, 0.26f};
  float bark_base_height = 0;
  float alpha_cutoff = 0.5f;            // leaves: glTF alphaCutoff
  float leaf_normal_blend = 0.6f;       // leaf normals bent toward the crown (render/mesh/leaf_shading.h)
  // Each leaf's colour factor in its COLOR_0 (leaf_color_factor, render/mesh/leaf_shading.h).
  float leaf_color_variation = 0.15f, leaf_sun_tone = 0.6f;
  // The season (render/mesh/season.h): deciduous archetypes' materials take the middle of its colour
  // range, and its fallen leaves are left out. The default changes nothing (leaf_color is used).
  season_look season;
  // The user's PNGs instead of the procedural textures ("" = procedural). A user leaf texture
  // replaces every archetype's colour (one leaf material); leaf_opacity (same size, grey: white is
  // leaf) becomes its alpha. A missing, corrupt or huge file is a warning and the export falls back
  // to the procedural texture.
  std::string bark_texture, bark_normal_texture, leaf_texture, leaf_opacity;
  // --lods: LOD1.. written with the main mesh as LOD0 (glTF: MSFT_lod; OBJ: one file per level).
  std::vector<export_lod_level> lods;
  float lod0_coverage = 0;
  const export_impostor* impostor = nullptr;   // glTF only: a textured quad node after the levels
  // glTF and FBX: > 0 bakes the wind (render/io/export_wind.h) as a skin and a loop of this many seconds.
  float wind_seconds = 0;
  wind_params wind;                     // from the preset's render section (apply_render_params)
};

// Export profiles (docs/design/03-foliage.md), offered by `sylva export --profile` and the export
// dialog: how a file carries the leaves.
enum class export_profile : int { plain = 0, hero, hero_baked, game };
inline constexpr const char* export_profile_names[] = {"plain", "hero", "hero-baked", "game", nullptr};
inline constexpr const char* export_profile_help[] = {
    "flat cards baked in: every importer opens it, Blender 3.4 included",
    "leaves as blade meshes; glTF instances them (EXT_mesh_gpu_instancing) for three.js, engines and film",
    "blade meshes baked in, for importers without instancing: about 2.6 times plain's size",
    "the LOD chain with baked cards and the impostor (as --lods)"};
// The leaf options of a profile: hero instances the blades in glTF and bakes them elsewhere,
// hero-baked bakes them; plain and game bake cards (game's LOD chain is prepared by the caller).
inline void apply_export_profile(export_options& o, export_profile p, bool gltf) {
  o.baked_blades = p == export_profile::hero || p == export_profile::hero_baked;
  if (p == export_profile::hero && gltf) o.gltf_instancing = true;
}

// The material settings of a preset's render params: bark archetype, tints, alpha cutoff and the
// user's texture paths. The CLI and the export dialog both fill export_options through this.
void apply_render_params(export_options& o, const render_params& rp);

struct export_info {
  std::string generator;   // generator name, written into the files
  uint64_t seed = 1;
};

struct export_result {
  std::string error;        // "" on success
  std::string warning;      // "" or lines (\n-separated) the user should see; the export was written
  size_t bytes = 0;         // size of the main file written
  std::vector<std::string> files;  // every file written
  size_t triangles = 0;     // in the main mesh (all steps for a growth animation)
  int animation_steps = 0;  // steps in the growth animation after the caps
};

// A format's writer: the tree to `path`, atomically (render/io/export.cpp).
using export_writer = export_result (*)(const tree_skeleton& t, const tree_mesh& m, const export_info& info,
                                        const std::string& path, const export_options& o);
export_result write_glb(const tree_skeleton& t, const tree_mesh& m, const export_info& info, const std::string& path,
                        const export_options& o);
export_result write_gltf(const tree_skeleton& t, const tree_mesh& m, const export_info& info, const std::string& path,
                         const export_options& o);
export_result write_obj(const tree_skeleton& t, const tree_mesh& m, const export_info& info, const std::string& path,
                        const export_options& o);   // with --lods, one OBJ per level
export_result write_skeleton_json(const tree_skeleton& t, const tree_mesh& m, const export_info& info, const std::string& path,
                                  const export_options& o);
export_result write_fbx(const tree_skeleton& t, const tree_mesh& m, const export_info& info, const std::string& path,
                        const export_options& o);

// Every format `sylva export` and the editor's export dialog write, in the dialog's order, with
// what each can carry and its writer. The CLI's checks, its messages, the dialog and export_tree
// all read this one table: a new format is a row here and its writer (or, for a render, none here:
// app/common/gl_window.h).
struct export_format {
  const char* ext;      // lower case, with the dot
  const char* label;    // for people: "glTF binary"
  bool lods;            // --lods: the LOD chain and the impostor
  bool wind;            // --wind: the wind as a skin and a loop (a render shows the wind's pose)
  bool render;          // a picture of the tree, drawn by the GL renderer (main thread only)
  bool manifest;        // a batch of these gets a manifest (seed, file, counts, hash)
  bool gltf;            // the glTF family: --animation, --instancing and --compact apply
  bool mesh;            // written from the mesh (the skeleton JSON needs none: nothing is meshed for it)
  // What the writer (or the renderer) holds on top of the mesh, per bark triangle and per leaf, for
  // the mesh budget (render/io/mesh_bound.h): measured peaks (`/usr/bin/time -v sylva export`) on bark-
  // and leaf-heavy trees, with room for vector slack (docs/DESIGN-NOTES.md "Mesh bound"). A baked
  // leaf is a blade of 24 vertices (render/mesh/leaf_blade.h, two faces of 12) where a card had 8,
  // so the per-leaf figures measured on cards are taken three times.
  float writer_triangle_bytes, writer_leaf_bytes;
  export_writer writer;   // null: not written by export_tree (a render)
};
inline constexpr export_format export_format_table[] = {
    // ext     label            lods   wind   render manifest gltf   mesh   writer B/triangle, B/leaf, writer
    {".glb",  "glTF binary",   true,  true,  false, true,  true,  true, 340,  5100, write_glb},
    {".gltf", "glTF + .bin",   true,  true,  false, true,  true,  true, 340,  5100, write_gltf},
    {".obj",  "OBJ + MTL",     true,  false, false, true,  false, true, 420,  5100, write_obj},
    {".json", "skeleton JSON", false, false, false, true,  false, false, 0,    0,    write_skeleton_json},
    {".png",  "render (PNG)",  false, true,  true,  false, false, true, 250,  120,  nullptr},
    {".fbx",  "FBX (assimp)",  true,  true,  false, true,  false, true, 1800, 8700, write_fbx},
};
inline constexpr int export_format_count = int(sizeof export_format_table / sizeof export_format_table[0]);

// The row for an extension (any case, with the dot), or nullptr.
const export_format* find_export_format(const std::string& ext);
// The extensions of the rows that `has` accepts, joined by `sep` (every row when `has` is null).
std::string export_format_list(bool export_format::*has = nullptr, const char* sep = ", ");

// Picks the format from the extension of `path`: .glb .gltf .obj .fbx .json. Writes atomically.
export_result export_tree(const tree_skeleton& t, const tree_mesh& m, const export_info& info,
                          const std::string& path, const export_options& o = {});

// The skeleton JSON document (docs/design/10-files.md, "Exports") as text.
std::string skeleton_json(const tree_skeleton& t, const export_info& info, int step = -1);

}  // namespace sylva
