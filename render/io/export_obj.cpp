// OBJ + MTL + PNGs export.
#include "render/io/export_internal.h"

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

namespace sylva::export_internal {
namespace {

// ---------------------------------------------------------------- OBJ + MTL
void put_float(std::string& s, float v) {
  char buf[32];
  const auto res = std::to_chars(buf, buf + sizeof buf, std::isfinite(v) ? v : 0.0f);
  s.append(buf, res.ptr);
}

}  // namespace

// `collect` (--lods): the files are appended there, not written, for one all-or-nothing write of
// every level; `png_stem` then names the PNGs (shared by the levels), and `m` is used as is.
export_result export_obj(const tree_skeleton& t, const tree_mesh& m, const export_info& info, const std::string& path,
                         const export_options& o, std::vector<std::pair<std::string, std::string>>* collect,
                         const std::string& png_stem) {
  export_result r;
  const std::string stem = stem_path(path), stem_name = png_stem.empty() ? file_name(stem) : png_stem;
  const int s = collect ? std::max(t.steps, 0) : o.step < 0 ? std::max(t.steps, 0) : std::min(o.step, std::max(t.steps, 0));
  material_source src(o, r.warning);
  src.without_vertex_colors();
  step_view v;
  if (collect) v.skeleton = &t, v.mesh = &m;
  else view_at(v, t, m, o.mesh, s);
  std::vector<tree_part> parts = split_parts(*v.skeleton, *v.mesh, s, true, src.one_leaf_material(), src.leaf_looks());
  std::string text = "# Sylva tree: generator " + info.generator + ", seed " + std::to_string(info.seed) +
                     ", step " + std::to_string(s) + "\nmtllib " + file_name(stem) + ".mtl\n";
  size_t verts = 0;
  for (const tree_part& p : parts) {
    verts += p.bark.position.size();
    for (const geometry& g : p.leaves) verts += g.position.size();
  }
  text.reserve(verts * 110);
  auto vertices = [&](const geometry& g) {
    for (size_t k = 0; k < g.position.size(); ++k) {
      text += "v "; put_float(text, g.position[k].x); text += ' '; put_float(text, g.position[k].y); text += ' '; put_float(text, g.position[k].z);
      text += "\nvt "; put_float(text, g.uv[k].x); text += ' '; put_float(text, 1 - g.uv[k].y);  // OBJ's v runs up
      text += "\nvn "; put_float(text, g.normal[k].x); text += ' '; put_float(text, g.normal[k].y); text += ' '; put_float(text, g.normal[k].z);
      text += '\n';
    }
  };
  // All vertices first, then faces by material, so that each material is a single group.
  std::vector<size_t> bark_base;
  std::vector<std::array<size_t, leaf_slots>> leaf_base;
  size_t next = 1;  // OBJ indices start at 1
  for (const tree_part& p : parts) {
    bark_base.push_back(next);
    vertices(p.bark);
    next += p.bark.position.size();
    leaf_base.emplace_back();
    for (int slot = 0; slot < leaf_slots; ++slot) {
      leaf_base.back()[size_t(slot)] = next;
      vertices(p.leaves[size_t(slot)]);
      next += p.leaves[size_t(slot)].position.size();
    }
  }
  if (cancelled(o)) { r.error = "export cancelled"; return r; }
  auto faces = [&](const geometry& g, size_t base) {
    char buf[24];
    assert(std::all_of(g.index.begin(), g.index.end(), [&](uint32_t i) { return i < g.position.size(); }) &&
           "OBJ export: an index past its group's vertices");
    for (size_t k = 0; k < g.index.size(); k += 3) {
      text += 'f';
      for (int c = 0; c < 3; ++c) {
        const auto res = std::to_chars(buf, buf + sizeof buf, base + g.index[k + c]);
        const std::string_view id(buf, size_t(res.ptr - buf));
        text += ' '; text += id; text += '/'; text += id; text += '/'; text += id;
      }
      text += '\n';
    }
    r.triangles += g.index.size() / 3;
  };
  // The MTL and its PNGs: each material's textures beside the .obj, named after the material.
  std::string mtl = "# Sylva materials (map_Bump and norm: tangent-space normal maps)\n";
  std::vector<std::pair<std::string, std::string>> files;
  const std::string dir = std::filesystem::path(path).parent_path().string();
  auto png_file = [&](const std::string& name, const std::string& png) {
    const std::string file = stem_name + "_" + name + ".png";
    files.emplace_back((std::filesystem::path(dir) / file).string(), png);
    return file;
  };
  bool any_bark = false;
  for (const tree_part& p : parts) any_bark |= !p.bark.empty();
  if (any_bark) {
    const material_pngs* pngs = src.bark();
    if (!pngs) { r.error = src.error; return r; }
    const std::string name = src.bark_name();
    text += "g bark\nusemtl " + name + "\n";
    for (size_t k = 0; k < parts.size(); ++k) faces(parts[k].bark, bark_base[k]);
    mtl += "\nnewmtl " + name + "\nKa 0 0 0\nKd 1 1 1\nKs 0 0 0\nNs 0\nd 1\nillum 1\nmap_Kd " + png_file(name, pngs->color) + "\n";
    if (!pngs->normal.empty()) {
      const std::string normal = png_file(name + "_normal", pngs->normal);
      mtl += "map_Bump -bm 1 " + normal + "\nnorm " + normal + "\n";
    }
    if (!pngs->roughness.empty()) mtl += "Pr 1\nPm 0\nmap_Pr " + png_file(name + "_roughness", pngs->roughness) + "\n";
  }
  for (int slot = 0; slot < leaf_slots; ++slot) {
    bool used = false;
    for (const tree_part& p : parts) used |= !p.leaves[size_t(slot)].empty();
    if (!used) continue;
    const material_pngs* pngs = src.leaf(slot);
    if (!pngs) { r.error = src.error; return r; }
    const std::string name = src.leaf_name(slot);
    text += "g " + name + "\nusemtl " + name + "\n";
    for (size_t k = 0; k < parts.size(); ++k) faces(parts[k].leaves[size_t(slot)], leaf_base[k][size_t(slot)]);
    // The colour PNG carries the cut-out in its alpha: map_d reads that channel of the same file.
    const std::string color = png_file(name, pngs->color);
    mtl += "\nnewmtl " + name + "\nKa 0 0 0\nKd 1 1 1\nKs 0 0 0\nNs 40\nd 1\nillum 1\nmap_Kd " + color +
           "\nmap_d -imfchan m " + color + "\n";
    if (!pngs->normal.empty()) {
      const std::string normal = png_file(name + "_normal", pngs->normal);
      mtl += "map_Bump -bm 1 " + normal + "\nnorm " + normal + "\n";
    }
  }
  files.emplace_back(stem + ".mtl", std::move(mtl));
  files.emplace_back(path, std::move(text));
  r.bytes = files.back().second.size();
  if (collect) {
    for (auto& f : files)
      if (std::none_of(collect->begin(), collect->end(), [&](const auto& c) { return c.first == f.first; }))
        collect->push_back(std::move(f));
    return r;
  }
  if (o.dry_run) return r;
  r.error = write_all(files, r);
  return r;
}

}  // namespace sylva::export_internal
