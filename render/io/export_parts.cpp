// Export parts: a tree split per forest member, leaves baked into cards, step views, and the
// all-or-nothing write of an export's files.
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
#include "render/mesh/season.h"
#include "render/assets/textures.h"

namespace sylva::export_internal {

int leaf_slot(const leaf_instance& l, bool one_leaf_material) {
  return one_leaf_material ? 0 : std::clamp(int(l.texture), 0, leaf_slots - 1);
}

blade_mesh export_blade_mesh(leaf_archetype a, const leaf_blade_shape& s, bool full_grid, const leaf_look& look) {
  if (s.on && archetype_is_shoot(a)) {   // a needle shoot (render/mesh/leaf_shoot.h), sampling the material's own picture
    blade_mesh shoot = shoot_prototype(a, s, full_grid ? shoot_pieces_fine : shoot_pieces_coarse,
                                       archetype_swatches(a, std::clamp(look.texture_size, 16, 4096), look.texture_seed));
    shoot.closed = true;
    return shoot;
  }
  blade_mesh b;
  const blade_outline& o = archetype_outline(a);
  if (full_grid) {
    const auto grid = blade_prototype(o, s);
    b.vertex.assign(grid.begin(), grid.end());
    b.index.assign(blade_indices().begin(), blade_indices().end());
  } else {
    const auto grid = coarse_blade(o, s);
    b.vertex.assign(grid.begin(), grid.end());
    b.index.assign(coarse_blade_indices().begin(), coarse_blade_indices().end());
  }
  return b;
}

std::array<blade_mesh, leaf_slots> slot_blades(const leaf_blade_shape& s, bool one_leaf_material, bool full_grid, const leaf_look& look) {
  std::array<blade_mesh, leaf_slots> out;
  if (!s.on || one_leaf_material) return out;
  for (int k = 0; k < leaf_archetype_count; ++k)
    if (!archetype_is_fruit(leaf_archetype(k))) out[size_t(k)] = export_blade_mesh(leaf_archetype(k), s, full_grid, look);
  return out;
}

glm::vec3 leaf_color_of(const leaf_instance& l, size_t index, int slot, bool one_leaf_material, const leaf_look& look) {
  const bool own = slot >= leaf_archetype_count || (!one_leaf_material && archetype_is_fruit(leaf_archetype(slot)));
  return own ? glm::vec3(1) : leaf_color_factor(l.node, uint32_t(index), float(l.occlusion) / 255.0f, look.variation, look.sun_tone);
}

// A leaf instance as a card of one blade length square (or its blade mesh), base at the petiole
// (leaf frame of skeleton.h: blade in local XY, normal +Z, petiole along -Y) with the whole texture
// on it: the petiole at the bottom edge of the image (v = 1, glTF's origin is the top-left corner).
// Each side is a face of its own (render/mesh/leaf_shading.h): the side that looks out of the crown
// first, then, with b.two_sided, the other a hair behind it; each normal is that side's, bent toward
// the crown's outward direction by b.normal_blend.
void bake_leaf(geometry& g, const leaf_instance& l, const leaf_bake& b) {
  static const blade_mesh card = [] {
    blade_mesh c;
    // The card's corners in the order of before: petiole left, petiole right, tip right, tip left.
    for (const glm::vec2 p : {glm::vec2(-0.5f, 0), glm::vec2(0.5f, 0), glm::vec2(0.5f, 1), glm::vec2(-0.5f, 1)})
      c.vertex.push_back({glm::vec3(p, 0), glm::vec3(0, 0, 1), glm::vec2(p.x + 0.5f, 1 - p.y)});
    c.index = {0, 1, 2, 0, 2, 3};
    return c;
  }();
  const blade_mesh& shape = b.blade && !b.blade->vertex.empty() ? *b.blade : card;
  const glm::quat q(l.orientation.w, l.orientation.x, l.orientation.y, l.orientation.z);
  auto unit = [](glm::vec3 v, glm::vec3 fallback) {
    const float len = glm::length(v);
    return len > 1e-6f ? v / len : fallback;
  };
  const glm::vec3 n = unit(q * glm::vec3(0, 0, 1), glm::vec3(0, 0, 1));
  const glm::vec3 across = unit(q * glm::vec3(1, 0, 0), glm::vec3(1, 0, 0));
  const glm::vec3 out = b.crown ? crown_outward(*b.crown, l.position) : n;
  const glm::vec3 occlusion(float(l.occlusion) / 255.0f);
  const float outer = glm::dot(n, out) < 0 ? -1.0f : 1.0f;   // the side that looks out of the crown
  const size_t count = shape.vertex.size();
  auto face = [&](float side) {
    const glm::vec3 shift = side == outer || shape.closed ? glm::vec3(0) : -outer * n * (leaf_back_offset * l.size);
    const uint32_t base = uint32_t(g.position.size());
    for (size_t j = 0; j < count; ++j) {
      // The back face lists the first two vertices swapped, so both faces' triangles use their
      // vertices in order (vertex-fetch order, which meshoptimizer's index codec packs best).
      const size_t k = side > 0 || count < 2 || j > 1 ? j : 1 - j;
      const blade_vertex& v = shape.vertex[k];
      const glm::vec3 nf = blend_leaf_normal(side * unit(q * v.normal, n), out, b.normal_blend);
      // Tangent along +u (local +X), made orthogonal to the bent normal. The bitangent normal x
      // tangent runs up the image (local +Y) on the front, so w = +1; on the back the normal is
      // turned over, so w = -1 keeps it running up the image.
      const glm::vec4 t(unit(across - nf * glm::dot(nf, across), across), side);
      g.position.push_back(l.position + q * (v.position * l.size) + shift);
      g.normal.push_back(nf);
      g.uv.push_back(v.uv);
      g.tangent.push_back(t);
      g.color.push_back(glm::min(occlusion * b.color, glm::vec3(1.0f)));   // glTF's COLOR_0 lies in 0..1
      g.node.push_back(l.node);
    }
    auto local = [&](uint16_t i) { return side > 0 || count < 2 || i > 1 ? uint32_t(i) : uint32_t(1 - i); };
    // Counter-clockwise seen from the side the face looks to: the back face reverses each triangle.
    for (size_t t = 0; t + 2 < shape.index.size(); t += 3) {
      const uint32_t a = local(shape.index[t]), b1 = local(shape.index[t + 1]), c = local(shape.index[t + 2]);
      if (side > 0) g.index.insert(g.index.end(), {base + a, base + b1, base + c});
      else g.index.insert(g.index.end(), {base + a, base + c, base + b1});
    }
  };
  if (shape.closed) {   // a needle shoot's spikes are closed: one face, every side already outward
    face(1.0f);
    return;
  }
  face(outer);
  if (b.two_sided) face(-outer);
}

bool has_shed(const tree_skeleton& t, int s) {
  for (size_t i = 0; i < t.size(); ++i)
    if (t.born[i] <= s && !t.alive(i, s)) return true;
  return false;
}

std::vector<int32_t> plant_of_nodes(const tree_skeleton& t) {
  // Roots closer than stool_reach are joined (union-find, so a chain of close stems is one stool);
  // the plants are then numbered in the order of their first root.
  std::vector<size_t> roots;
  for (size_t i = 0; i < t.size(); ++i)
    if (t.parent[i] < 0) roots.push_back(i);
  std::vector<size_t> link(roots.size());
  for (size_t r = 0; r < roots.size(); ++r) link[r] = r;
  auto find = [&](size_t r) {
    while (link[r] != r) r = link[r] = link[link[r]];
    return r;
  };
  for (size_t a = 0; a < roots.size(); ++a)
    for (size_t b = 0; b < a; ++b) {
      const glm::vec3 d = t.position[roots[a]] - t.position[roots[b]];
      if (d.x * d.x + d.z * d.z <= stool_reach * stool_reach && std::abs(d.y) <= stool_reach) link[find(a)] = find(b);
    }
  std::vector<int32_t> label(roots.size(), -1);
  int32_t plants = 0;
  std::vector<int32_t> out(t.size(), 0);
  for (size_t i = 0, r = 0; i < t.size(); ++i) {
    assert(t.parent[i] < int32_t(i) && "plant_of_nodes: parent[i] < i");
    if (t.parent[i] >= 0) {
      out[i] = out[size_t(t.parent[i])];
      continue;
    }
    int32_t& l = label[find(r++)];
    if (l < 0) l = plants++;
    out[i] = l;
  }
  return out;
}

// Splits a mesh into one part per plant (render/io/export_internal.h); leaves alive at `step` are
// baked into quads (one geometry per leaf slot) unless `bake` is false, in which case they are
// left to the caller.
std::vector<tree_part> split_parts(const tree_skeleton& t, const tree_mesh& m, int step, bool bake, bool one_leaf_material,
                                   const leaf_look& leaf_style, const bark_tint& tint) {
  const std::vector<int32_t> tree_of = plant_of_nodes(t);
  int trees = 0;
  for (int32_t k : tree_of) trees = std::max(trees, k + 1);
  std::vector<tree_part> parts(size_t(std::max(trees, 1)));
  const size_t nv = m.position.size();
  if (parts.size() == 1) {  // the common case: reserve exactly, so big trees are not copied while growing
    geometry& g = parts[0].bark;
    g.position.reserve(nv), g.normal.reserve(nv), g.uv.reserve(nv), g.tangent.reserve(nv), g.index.reserve(m.index.size());
    std::array<size_t, leaf_slots> alive{};
    if (bake)
      for (const leaf_instance& l : m.leaves) alive[size_t(leaf_slot(l, one_leaf_material))] += l.born <= step && step < l.died;
    for (int k = 0; k < leaf_slots; ++k) {
      geometry& f = parts[0].leaves[size_t(k)];
      const size_t n = alive[size_t(k)];
      f.position.reserve(8 * n), f.normal.reserve(8 * n), f.uv.reserve(8 * n), f.tangent.reserve(8 * n), f.index.reserve(12 * n);
    }
  }
  std::vector<uint32_t> local(nv, UINT32_MAX);
  const bool occluded = m.occlusion.size() == nv, blend = tint.blends();   // the bark's COLOR_0
  const int seg = std::max(m.radial_segments, 1), stride = seg + 1;
  for (size_t k = 0; k < m.index.size(); ++k) {
    const uint32_t v = m.index[k];
    assert(v < nv && m.node.size() == nv && "export: a bark index past the mesh's vertices");
    const uint32_t node = m.node[v];
    geometry& g = parts[node < tree_of.size() ? tree_of[node] : 0].bark;
    if (local[v] == UINT32_MAX) {
      local[v] = uint32_t(g.position.size());
      g.position.push_back(m.position[v]);
      g.normal.push_back(m.normal[v]);
      g.uv.push_back(m.uv[v]);
      // Tangent along +u (around the ring): the chord between the ring neighbours is tangent to
      // the circle at this vertex; w = +1 since v (the branch) = normal x tangent.
      const uint32_t ring = v / stride * stride, k0 = v - ring;
      const uint32_t prev = ring + (k0 == 0 ? seg - 1 : k0 - 1), next = ring + (k0 == uint32_t(seg) ? 1 : k0 + 1);
      glm::vec3 tan = next < nv ? m.position[next] - m.position[prev] : glm::vec3(1, 0, 0);
      tan -= m.normal[v] * glm::dot(m.normal[v], tan);
      const float len = glm::length(tan);
      tan = len > 1e-12f ? tan / len : glm::vec3(1, 0, 0);
      g.tangent.push_back(glm::vec4(tan, 1.0f));
      if (occluded || blend) g.color.push_back((occluded ? m.occlusion[v] : 1.0f) * (blend ? tint.ratio(m.position[v].y) : glm::vec3(1)));
      g.node.push_back(node);
    }
    g.index.push_back(local[v]);
  }
  if (bake) {
    // Each tree of a forest bends its leaves toward its own crown: the box of its leaves alive now.
    auto part_of = [&](const leaf_instance& l) { return size_t(l.node < tree_of.size() ? tree_of[l.node] : 0); };
    std::vector<crown_box> crowns(parts.size());
    for (const leaf_instance& l : m.leaves)
      if (l.born <= step && step < l.died) crowns[part_of(l)].add(l.position);
    std::vector<leaf_bake> look(parts.size());
    std::vector<crown_ellipsoid> shape(parts.size());
    for (size_t k = 0; k < parts.size(); ++k) shape[k] = crowns[k].ellipsoid(), look[k] = {&shape[k], leaf_style.normal_blend, true};
    leaf_blade_shape baked = m.blade;
    baked.on = baked.on && leaf_style.blades;
    const std::array<blade_mesh, leaf_slots> blades = slot_blades(baked, one_leaf_material, false, leaf_style);
    for (size_t i = 0; i < m.leaves.size(); ++i) {
      const leaf_instance& l = m.leaves[i];
      if (l.born <= step && step < l.died) {
        const size_t slot = size_t(leaf_slot(l, one_leaf_material));
        leaf_bake b = look[part_of(l)];
        b.blade = &blades[slot];
        b.color = leaf_color_of(l, i, int(slot), one_leaf_material, leaf_style);
        bake_leaf(parts[part_of(l)].leaves[slot], l, b);
      }
    }
  }
  for (tree_part& p : parts) {   // vertex-cache and fetch order for every exporter (meshoptimizer)
    optimize_geometry(p.bark);
    for (geometry& g : p.leaves) optimize_geometry(g);
  }
  return parts;
}

void view_at(step_view& v, const tree_skeleton& t, const tree_mesh& m, const mesh_params& p, int step) {
  if (step >= t.steps && !has_shed(t, t.steps)) {
    v.skeleton = &t;
    v.mesh = &m;
  } else {
    v.own_skeleton = skeleton_at_step(t, step);
    v.own_mesh = mesh_tree_at_step(t, m, p, step);
    v.skeleton = &v.own_skeleton;
    v.mesh = &v.own_mesh;
  }
}

bool cancelled(const export_options& o) { return o.cancel && o.cancel->load(std::memory_order_relaxed) != 0; }

std::string lod_tree_name(const std::string& stem) {
  std::string out;
  for (const unsigned char c : stem) out.push_back(std::isalnum(c) || c == '-' || c == '_' ? char(c) : '_');
  return out.empty() ? "tree" : out;
}

std::string file_name(const std::string& path) { return std::filesystem::path(path).filename().string(); }

std::string stem_path(const std::string& path) {
  std::filesystem::path p(path);
  return (p.parent_path() / p.stem()).string();
}

// Writes every (path, bytes) pair all or nothing: each is staged first (preset.h: written and synced
// under a temporary name beside its target, through symlinks, keeping permissions). A failure while
// staging removes only the temporaries. Then each existing target is moved aside and the new file
// renamed in, the main file (which names the others) last; if a rename fails midway, the files
// moved aside are put back, so the previous export stays whole in either case.
std::string write_all(const std::vector<std::pair<std::string, std::string>>& files, export_result& r) {
  std::vector<staged_write> staged(files.size());
  for (size_t k = 0; k < files.size(); ++k) {
    if (std::string err = stage_file(files[k].first, files[k].second, staged[k]); !err.empty()) {
      for (size_t j = 0; j < k; ++j) discard_staged(staged[j]);
      return err;
    }
  }
  std::vector<std::string> aside(files.size());   // the previous file moved aside, or ""
  auto roll_back = [&](size_t done) {
    for (size_t j = 0; j < done; ++j) {
      if (!aside[j].empty()) ::rename(aside[j].c_str(), staged[j].target.c_str());
      else ::unlink(staged[j].target.c_str());
    }
    for (size_t j = done; j < files.size(); ++j) discard_staged(staged[j]);
  };
  for (size_t k = 0; k < files.size(); ++k) {
    struct stat st {};
    if (::lstat(staged[k].target.c_str(), &st) == 0) {
      aside[k] = staged[k].temp + ".previous";
      if (::rename(staged[k].target.c_str(), aside[k].c_str()) != 0) {
        const int err = errno;
        aside[k].clear();
        roll_back(k);
        return "cannot write " + files[k].first + ": cannot move the previous file aside: " + std::strerror(err);
      }
    }
    if (std::string err = commit_staged(staged[k]); !err.empty()) {
      if (!aside[k].empty()) ::rename(aside[k].c_str(), staged[k].target.c_str());
      roll_back(k);
      return err;
    }
  }
  for (size_t k = 0; k < files.size(); ++k) {
    if (!aside[k].empty()) ::unlink(aside[k].c_str());
    r.files.push_back(files[k].first);
  }
  return "";
}

}  // namespace sylva::export_internal
