// Exporters' front door: the format dispatch, the season pass, the skeleton JSON and the render
// parameters an export takes (glTF in export_gltf.cpp, OBJ in export_obj.cpp, FBX in export_fbx.cpp).
#include "render/io/export.h"
#include "render/mesh/lod_cards.h"
#include "render/io/export_wind.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include <algorithm>
#include <array>
#include <cassert>
#include <atomic>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cctype>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string_view>
#include <thread>
#include <tuple>

#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>
#include <stb_image.h>

#include "render/io/preset.h"
#include "render/assets/textures.h"
#include "render/io/export_internal.h"

namespace sylva {

using namespace export_internal;

// ---------------------------------------------------------------- skeleton JSON (docs/design/10-files.md)
std::string skeleton_json(const tree_skeleton& full, const export_info& info, int step) {
  const tree_skeleton t = step >= 0 && step < full.steps ? skeleton_at_step(full, step) : full;
  json nodes;
  json pos = json::array(), par = json::array(), rad = json::array(), born = json::array(), died = json::array(), ord = json::array();
  json dead = json::array();   // the step from which a node stands as dead wood (a stub), or null
  for (size_t i = 0; i < t.size(); ++i) {
    pos.push_back({t.position[i].x, t.position[i].y, t.position[i].z});
    par.push_back(t.parent[i]);
    rad.push_back(t.radius[i]);
    born.push_back(t.born[i]);
    if (t.died[i] == never_died) died.push_back(nullptr); else died.push_back(t.died[i]);
    ord.push_back(t.order[i]);
    if (t.dead_from(i) == never_died) dead.push_back(nullptr); else dead.push_back(t.dead_from(i));
  }
  nodes = {{"position", pos}, {"parent", par}, {"radius", rad}, {"born", born}, {"died", died}, {"order", ord},
           {"dead", dead}};
  json leaves = json::array();
  for (const leaf& l : t.leaves)
    leaves.push_back({{"position", {l.position.x, l.position.y, l.position.z}},
                      {"orientation", {l.orientation.x, l.orientation.y, l.orientation.z, l.orientation.w}},
                      {"size", l.size}, {"born", l.born},
                      {"died", l.died == never_died ? json(nullptr) : json(l.died)}, {"node", l.node}});
  json doc = {{"sylva_skeleton", 1}, {"generator", info.generator}, {"seed", info.seed}, {"steps", t.steps},
              {"tree_count", t.tree_count}, {"nodes", nodes}, {"leaves", leaves}};
  return doc.dump(-1, ' ', false, json::error_handler_t::replace);
}

void apply_render_params(export_options& o, const render_params& rp) {
  o.bark = rp.bark;
  o.bark_color = rp.bark_color;
  o.bark_base_color = rp.bark_base_color;
  o.bark_base_height = rp.bark_base_height;
  o.season = season_leaf_look(rp);
  o.leaf_color = o.season.evergreen_color;
  o.alpha_cutoff = rp.alpha_cutoff;
  o.leaf_normal_blend = rp.leaf_normal_blend;
  o.leaf_color_variation = rp.leaf_color_variation;
  o.leaf_sun_tone = rp.leaf_sun_tone;
  o.bark_texture = rp.bark_texture;
  o.leaf_texture = rp.leaf_texture;
  o.leaf_opacity = rp.leaf_opacity;
  o.wind = rp.wind;
}

const export_format* find_export_format(const std::string& ext) {
  std::string e = ext;
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  for (const export_format& f : export_format_table)
    if (e == f.ext) return &f;
  return nullptr;
}

std::string export_format_list(bool export_format::*has, const char* sep) {
  std::string out;
  for (const export_format& f : export_format_table)
    if (!has || f.*has) out += (out.empty() ? "" : sep) + std::string(f.ext);
  return out;
}

export_result export_tree(const tree_skeleton& t, const tree_mesh& m, const export_info& info, const std::string& path,
                          const export_options& o) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  export_result r;
  // Numbers passed on from the user (the CLI checks its options first, the dialog's fields can be
  // typed): written out, a NaN or infinity makes an invalid file.
  for (const auto& [name, v] : {std::pair{"seconds per step", o.seconds_per_step}, {"wind loop seconds", o.wind_seconds}})
    if (std::string e = finite_refusal(name, v); !e.empty()) {
      r.error = e;
      return r;
    }
  const export_format* format = find_export_format(ext);
  if (!format || !format->writer) {
    r.error = "cannot export " + path + ": unknown extension \"" + ext + "\" (use .glb, .gltf, .obj, .fbx or .json)";
    return r;
  }
  if (format->mesh && season_changes_leaves(o.season)) {
    // Fallen leaves out, spring's smaller: on LOD0 and on every level (their baked cards fall with
    // the leaves they were baked from). The copy's look keeps its colours but no longer drops or
    // scales leaves, so the second pass below writes the seasonal meshes as they are.
    const tree_mesh seasonal = apply_season(m, o.season);
    std::vector<tree_mesh> levels;
    levels.reserve(o.lods.size());
    export_options so = o;
    for (export_lod_level& l : so.lods)
      if (l.mesh) {
        levels.push_back(apply_season(*l.mesh, o.season));
        l.mesh = &levels.back();
      }
    so.season.deciduous_keep = 1.0f;
    so.season.deciduous_scale = 1.0f;
    return export_tree(t, seasonal, info, path, so);
  }
  return format->writer(t, m, info, path, o);
}

export_result write_glb(const tree_skeleton& t, const tree_mesh& m, const export_info& info, const std::string& path,
                        const export_options& o) {
  return export_gltf(t, m, info, path, o, true);
}

export_result write_gltf(const tree_skeleton& t, const tree_mesh& m, const export_info& info, const std::string& path,
                         const export_options& o) {
  return export_gltf(t, m, info, path, o, false);
}

export_result write_fbx(const tree_skeleton& t, const tree_mesh& m, const export_info& info, const std::string& path,
                        const export_options& o) {
  return export_fbx(t, m, info, path, o);
}

export_result write_obj(const tree_skeleton& t, const tree_mesh& m, const export_info& info, const std::string& path,
                        const export_options& o) {
  if (o.lods.empty()) return export_obj(t, m, info, path, o);
  // One OBJ (and MTL) per level, PNGs shared: tree.obj is LOD0, tree_lod1.obj ... All or nothing.
  export_result r;
  const std::string stem = stem_path(path), ext_text = std::filesystem::path(path).extension().string();
  std::vector<std::pair<std::string, std::string>> files;
  r = export_obj(t, m, info, path, o, &files, file_name(stem));
  for (size_t k = 0; k < o.lods.size() && r.error.empty(); ++k) {
    if (!o.lods[k].mesh) continue;
    const export_result l = export_obj(t, *o.lods[k].mesh, info, stem + "_lod" + std::to_string(k + 1) + ext_text, o,
                                       &files, file_name(stem));
    if (!l.error.empty()) r.error = l.error;
  }
  if (!r.error.empty() || o.dry_run) return r;
  // The main OBJ last: write_all commits the last file last.
  std::stable_partition(files.begin(), files.end(), [&](const auto& f) { return f.first != path; });
  r.error = write_all(files, r);
  return r;
}

export_result write_skeleton_json(const tree_skeleton& t, const tree_mesh&, const export_info& info, const std::string& path,
                                  const export_options& o) {
  export_result r;
  const std::string text = skeleton_json(t, info, o.step);
  r.bytes = text.size();
  if (o.dry_run) return r;
  r.error = write_all({{path, text}}, r);
  return r;
}

}  // namespace sylva
