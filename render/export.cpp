// Exporters: glTF 2.0 (.glb / .gltf + .bin + PNGs), OBJ + MTL + PNGs, and the skeleton JSON.
#include "render/export.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>

#include "render/files.h"
#include "render/textures.h"

namespace sylva {
namespace {

using json = nlohmann::json;

// One primitive's worth of triangles, ready to write.
struct geometry {
  std::vector<glm::vec3> position, normal;
  std::vector<glm::vec2> uv;
  std::vector<glm::vec4> tangent;  // bark only (it carries a normal map)
  std::vector<uint32_t> index;
  bool empty() const { return index.empty(); }
};

struct tree_part {
  geometry bark, leaves;
};

// A leaf instance as a quad of one blade length square, base at the petiole (leaf frame of
// skeleton.h: blade in local XY, normal +Z, petiole along -Y); UVs pick its atlas cell.
void bake_leaf(geometry& g, const leaf_instance& l) {
  const glm::quat q(l.orientation.w, l.orientation.x, l.orientation.y, l.orientation.z);
  const float h = l.size, w = l.size * 0.5f;
  const glm::vec3 corner[4] = {{-w, 0, 0}, {w, 0, 0}, {w, h, 0}, {-w, h, 0}};
  const auto cell = leaf_atlas_cell(l.texture);
  const glm::vec2 uv[4] = {{cell[0], cell[3]}, {cell[2], cell[3]}, {cell[2], cell[1]}, {cell[0], cell[1]}};
  glm::vec3 n = q * glm::vec3(0, 0, 1);
  const float len = glm::length(n);
  n = len > 1e-6f ? n / len : glm::vec3(0, 0, 1);
  const uint32_t base = uint32_t(g.position.size());
  for (int k = 0; k < 4; ++k) {
    g.position.push_back(l.position + q * corner[k]);
    g.normal.push_back(n);
    g.uv.push_back(uv[k]);
  }
  for (uint32_t k : {0u, 1u, 2u, 0u, 2u, 3u}) g.index.push_back(base + k);
}

// The mesh to export for step `s` and the skeleton its node ids refer to: the caller's own when
// the final tree is asked for and nothing was shed, else a re-meshed copy of the step.
struct step_view {
  tree_skeleton own_skeleton;
  tree_mesh own_mesh;
  const tree_skeleton* skeleton = nullptr;
  const tree_mesh* mesh = nullptr;
};

bool has_shed(const tree_skeleton& t, int s) {
  for (size_t i = 0; i < t.size(); ++i)
    if (t.born[i] <= s && !t.alive(i, s)) return true;
  return false;
}

// Splits a mesh into one part per tree (a forest is one glTF node per tree); leaves alive at
// `step` are baked into quads unless `instanced`, in which case they are left to the caller.
std::vector<tree_part> split_parts(const tree_skeleton& t, const tree_mesh& m, int step, bool bake) {
  std::vector<int32_t> tree_of(t.size(), 0);
  int trees = 0;
  for (size_t i = 0; i < t.size(); ++i) tree_of[i] = t.parent[i] < 0 ? trees++ : tree_of[t.parent[i]];
  std::vector<tree_part> parts(size_t(std::max(trees, 1)));
  const size_t nv = m.position.size();
  if (parts.size() == 1) {  // the common case: reserve exactly, so big trees are not copied while growing
    geometry& g = parts[0].bark;
    g.position.reserve(nv), g.normal.reserve(nv), g.uv.reserve(nv), g.tangent.reserve(nv), g.index.reserve(m.index.size());
    size_t alive = 0;
    for (const leaf_instance& l : m.leaves) alive += l.born <= step && step < l.died;
    geometry& f = parts[0].leaves;
    f.position.reserve(4 * alive), f.normal.reserve(4 * alive), f.uv.reserve(4 * alive), f.index.reserve(6 * alive);
  }
  std::vector<uint32_t> local(nv, UINT32_MAX);
  const int seg = std::max(m.radial_segments, 1), stride = seg + 1;
  for (size_t k = 0; k < m.index.size(); ++k) {
    const uint32_t v = m.index[k];
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
    }
    g.index.push_back(local[v]);
  }
  if (bake)
    for (const leaf_instance& l : m.leaves)
      if (l.born <= step && step < l.died)
        bake_leaf(parts[l.node < tree_of.size() ? tree_of[l.node] : 0].leaves, l);
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

std::string file_name(const std::string& path) { return std::filesystem::path(path).filename().string(); }
std::string stem_path(const std::string& path) {
  std::filesystem::path p(path);
  return (p.parent_path() / p.stem()).string();
}

// Writes every (path, bytes) pair all or nothing: each goes to a temporary file beside its target
// first (write_file_atomic: written, synced), and only when all of them are complete are they
// renamed into place, the last pair (the main file, which names the others) last. On any failure
// the temporary files and the files already renamed are removed.
std::string write_all(const std::vector<std::pair<std::string, std::string>>& files, export_result& r) {
  namespace fs = std::filesystem;
  static std::atomic<unsigned> counter{0};
  std::vector<std::string> temps;
  std::error_code ec;
  auto undo = [&] {
    for (const std::string& t : temps) fs::remove(t, ec);
    for (const std::string& done : r.files) fs::remove(done, ec);
    r.files.clear();
  };
  for (const auto& [path, bytes] : files) {
    const fs::path target(path);
    std::string name = ".";
    name += target.filename().string();
    name += ".part-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
    const std::string temp = (target.parent_path() / name).string();
    if (std::string err = write_file_atomic(temp, bytes); !err.empty()) {
      undo();
      return "cannot write " + path + " (" + err + ")";
    }
    temps.push_back(temp);
  }
  for (size_t k = 0; k < files.size(); ++k) {
    fs::rename(temps[k], files[k].first, ec);
    if (ec) {
      const std::string err = "cannot write " + files[k].first + ": " + ec.message();
      temps.erase(temps.begin(), temps.begin() + std::ptrdiff_t(k));
      undo();
      return err;
    }
    r.files.push_back(files[k].first);
  }
  return "";
}

// ---------------------------------------------------------------- glTF 2.0
constexpr int gl_float = 5126, gl_ushort = 5123, gl_uint = 5125;
constexpr int array_buffer = 34962, element_array_buffer = 34963;

struct gltf_doc {
  json j = json::object();
  std::string bin;

  int add_view(const void* data, size_t bytes, int target) {
    while (bin.size() % 4) bin.push_back('\0');  // accessors need aligned offsets
    json v = {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", bytes}};
    if (target) v["target"] = target;
    bin.append(static_cast<const char*>(data), bytes);
    j["bufferViews"].push_back(v);
    return int(j["bufferViews"].size()) - 1;
  }
  int add_accessor(int view, int component, size_t count, const char* type, json extra = json::object()) {
    json a = {{"bufferView", view}, {"componentType", component}, {"count", count}, {"type", type}};
    a.update(extra);
    j["accessors"].push_back(a);
    return int(j["accessors"].size()) - 1;
  }
  template <class V>
  int add_vectors(const std::vector<V>& v, const char* type, int target, bool bounds = false) {
    const int view = add_view(v.data(), v.size() * sizeof(V), target);
    json extra = json::object();
    if (bounds) {  // POSITION accessors must carry min and max
      V lo = v[0], hi = v[0];
      for (const V& x : v) lo = glm::min(lo, x), hi = glm::max(hi, x);
      json jl = json::array(), jh = json::array();
      for (int k = 0; k < V::length(); ++k) jl.push_back(lo[k]), jh.push_back(hi[k]);
      extra = {{"min", jl}, {"max", jh}};
    }
    return add_accessor(view, gl_float, v.size(), type, extra);
  }
  int add_indices(const std::vector<uint32_t>& idx, size_t vertices) {
    if (vertices < 65536) {  // 16-bit when every index fits
      std::vector<uint16_t> small(idx.begin(), idx.end());
      return add_accessor(add_view(small.data(), small.size() * 2, element_array_buffer), gl_ushort, idx.size(), "SCALAR");
    }
    return add_accessor(add_view(idx.data(), idx.size() * 4, element_array_buffer), gl_uint, idx.size(), "SCALAR");
  }
  // A mesh with one primitive; -1 when the geometry is empty (glTF forbids empty accessors).
  int add_mesh(const geometry& g, int material, const char* name) {
    if (g.empty()) return -1;
    json attr = {{"POSITION", add_vectors(g.position, "VEC3", array_buffer, true)},
                 {"NORMAL", add_vectors(g.normal, "VEC3", array_buffer)},
                 {"TEXCOORD_0", add_vectors(g.uv, "VEC2", array_buffer)}};
    if (!g.tangent.empty()) attr["TANGENT"] = add_vectors(g.tangent, "VEC4", array_buffer);
    const int idx = add_indices(g.index, g.position.size());
    j["meshes"].push_back({{"name", name}, {"primitives", {{{"attributes", attr}, {"indices", idx}, {"material", material}}}}});
    return int(j["meshes"].size()) - 1;
  }
  int add_node(json node) {
    j["nodes"].push_back(std::move(node));
    return int(j["nodes"].size()) - 1;
  }
};

struct gltf_textures {
  std::string bark_png, normal_png, leaves_png;
};

// Materials 0 (bark) and 1 (leaves) with textures 0..2; images embedded (GLB) or as files.
void add_materials(gltf_doc& d, const gltf_textures& tex, bool embed, const std::string& stem_name) {
  d.j["samplers"] = json::array({{{"magFilter", 9729}, {"minFilter", 9987}, {"wrapS", 10497}, {"wrapT", 10497}},
                                 {{"magFilter", 9729}, {"minFilter", 9987}, {"wrapS", 33071}, {"wrapT", 33071}}});
  const std::pair<const std::string*, const char*> images[3] = {
      {&tex.bark_png, "_bark.png"}, {&tex.normal_png, "_bark_normal.png"}, {&tex.leaves_png, "_leaves.png"}};
  for (const auto& [png, suffix] : images) {
    if (embed)
      d.j["images"].push_back({{"bufferView", d.add_view(png->data(), png->size(), 0)}, {"mimeType", "image/png"}});
    else
      d.j["images"].push_back({{"uri", stem_name + suffix}});
  }
  d.j["textures"] = json::array({{{"sampler", 0}, {"source", 0}}, {{"sampler", 0}, {"source", 1}}, {{"sampler", 1}, {"source", 2}}});
  d.j["materials"] = json::array(
      {{{"name", "bark"},
        {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.9}}},
        {"normalTexture", {{"index", 1}}}},
       {{"name", "leaves"},
        {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 2}}}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.6}}},
        {"alphaMode", "MASK"},
        {"alphaCutoff", 0.5},
        {"doubleSided", true}}});
}

// Procedural textures, or the user's PNGs where given; "" or an error naming the file.
std::string make_gltf_textures(const export_options& o, gltf_textures& g) {
  const int n = std::clamp(o.texture_size, 16, 2048);
  texture_set t = make_textures(n, n / 2, o.texture_seed);
  for (auto [path, img] : {std::pair{&o.bark_texture, &t.bark_color}, std::pair{&o.bark_normal_texture, &t.bark_normal}})
    if (!path->empty())
      if (std::string err = load_png(*path, *img); !err.empty()) return "texture " + err;
  image atlas;
  if (!o.leaf_texture.empty()) {
    image leaf;
    if (std::string err = load_png(o.leaf_texture, leaf); !err.empty()) return "texture " + err;
    atlas = make_leaf_atlas({leaf, leaf, leaf, leaf});
  } else {
    atlas = make_leaf_atlas(t.leaf);
  }
  for (auto [img, png] : {std::pair{&t.bark_color, &g.bark_png}, std::pair{&t.bark_normal, &g.normal_png}, std::pair{&atlas, &g.leaves_png}})
    if (std::string err = encode_png(*img, *png); !err.empty()) return err;
  return "";
}

// Nodes for one view of the tree: one node per tree, with a bark and a leaves child.
// Returns the node ids to put under the parent; counts triangles.
std::vector<int> add_tree_nodes(gltf_doc& d, const step_view& v, int step, bool instanced, const std::string& prefix,
                                size_t& triangles) {
  std::vector<tree_part> parts = split_parts(*v.skeleton, *v.mesh, step, !instanced);
  std::vector<int> out;
  int leaf_quad_mesh = -1;
  for (size_t k = 0; k < parts.size(); ++k) {
    const tree_part& part = parts[k];
    json tree = {{"name", prefix + (parts.size() > 1 ? "tree_" + std::to_string(k + 1) : "tree")}};
    json children = json::array();
    if (int mesh = d.add_mesh(part.bark, 0, "bark"); mesh >= 0) {
      children.push_back(d.add_node({{"name", "bark"}, {"mesh", mesh}}));
      triangles += part.bark.index.size() / 3;
    }
    if (!instanced) {
      if (int mesh = d.add_mesh(part.leaves, 1, "leaves"); mesh >= 0) {
        children.push_back(d.add_node({{"name", "leaves"}, {"mesh", mesh}}));
        triangles += part.leaves.index.size() / 3;
      }
    }
    if (!children.empty()) tree["children"] = children;
    out.push_back(d.add_node(tree));
  }
  if (instanced) {
    // EXT_mesh_gpu_instancing: one leaf quad, one instance per leaf alive at `step`.
    std::vector<glm::vec3> tr, sc;
    std::vector<glm::vec4> rot;
    geometry quad;
    for (const leaf_instance& l : v.mesh->leaves) {
      if (!(l.born <= step && step < l.died)) continue;
      if (quad.empty()) bake_leaf(quad, {glm::vec3(0), glm::vec4(0, 0, 0, 1), 1.0f, 0, 0, 0, 0});
      const glm::vec4 q = l.orientation / std::max(glm::length(l.orientation), 1e-12f);
      tr.push_back(l.position);
      rot.push_back(q);
      sc.push_back(glm::vec3(std::max(l.size, 1e-6f)));
    }
    if (!tr.empty()) {
      leaf_quad_mesh = d.add_mesh(quad, 1, "leaf");
      json attrs = {{"TRANSLATION", d.add_vectors(tr, "VEC3", 0)}, {"ROTATION", d.add_vectors(rot, "VEC4", 0)},
                    {"SCALE", d.add_vectors(sc, "VEC3", 0)}};
      out.push_back(d.add_node({{"name", prefix + "leaves"}, {"mesh", leaf_quad_mesh},
                                {"extensions", {{"EXT_mesh_gpu_instancing", {{"attributes", attrs}}}}}}));
      d.j["extensionsUsed"] = json::array({"EXT_mesh_gpu_instancing"});
      triangles += 2 * tr.size();
    }
  }
  return out;
}

std::string glb_container(std::string js, std::string& b) {
  auto u32 = [](std::string& s, uint32_t v) { for (int k = 0; k < 4; ++k) s.push_back(char((v >> (8 * k)) & 0xff)); };
  while (js.size() % 4) js.push_back(' ');  // GLB: JSON chunk padded with spaces
  while (b.size() % 4) b.push_back('\0');
  std::string out;
  out.reserve(28 + js.size() + b.size());
  u32(out, 0x46546C67);  // "glTF"
  u32(out, 2);
  u32(out, uint32_t(12 + 8 + js.size() + (b.empty() ? 0 : 8 + b.size())));
  u32(out, uint32_t(js.size()));
  u32(out, 0x4E4F534A);  // "JSON"
  out += js;
  if (!b.empty()) {
    u32(out, uint32_t(b.size()));
    u32(out, 0x004E4942);  // "BIN\0"
    out += b;
  }
  return out;
}

export_result export_gltf(const tree_skeleton& t, const tree_mesh& m, const export_info& info, const std::string& path,
                          const export_options& o, bool binary) {
  export_result r;
  const std::string stem = stem_path(path), stem_name = file_name(stem);
  gltf_doc d;
  d.j["asset"] = {{"version", "2.0"}, {"generator", "Sylva"},
                  {"extras", {{"generator", info.generator}, {"seed", info.seed}}}};
  gltf_textures tex;
  if (r.error = make_gltf_textures(o, tex); !r.error.empty()) return r;
  // The final tree's buffer size, so that big exports are not copied while the buffer grows.
  d.bin.reserve(m.position.size() * 48 + m.index.size() * 4 + m.leaves.size() * 152 + tex.bark_png.size() +
                tex.normal_png.size() + tex.leaves_png.size() + 64);
  add_materials(d, tex, binary, stem_name);
  if (o.progress) o.progress(0.1f);

  const int final_step = std::max(t.steps, 0);
  std::vector<int> roots;
  if (!o.growth_animation) {
    const int s = o.step < 0 ? final_step : std::min(o.step, final_step);
    step_view v;
    view_at(v, t, m, o.mesh, s);
    roots = add_tree_nodes(d, v, s, o.gltf_instancing, "", r.triangles);
  } else {
    // Growth over time: one node per step, shown in turn by STEP scale keyframes.
    int count = std::clamp(std::min(o.max_animation_steps, final_step + 1), 1, final_step + 1);
    auto sample = [&](int j, int n) { return n <= 1 ? final_step : int(std::lround(double(j) * final_step / (n - 1))); };
    auto estimate = [&](int n) {  // triangles of n sampled steps, from the step tables
      size_t tris = 0;
      for (int j = 0; j < n; ++j) {
        const int s = sample(j, n);
        tris += m.index_end[std::min<size_t>(s, m.index_end.size() - 1)] / 3 + 2 * size_t(m.leaf_end[std::min<size_t>(s, m.leaf_end.size() - 1)]);
      }
      return tris;
    };
    if (m.index_end.empty()) count = 1;
    else while (count > 2 && estimate(count) > o.max_animation_triangles) count = count * 3 / 4;
    r.animation_steps = count;
    const float sps = std::max(o.seconds_per_step, 1e-3f);
    json channels = json::array(), samplers = json::array();
    for (int j = 0; j < count; ++j) {
      if (cancelled(o)) { r.error = "export cancelled"; return r; }
      const int s = sample(j, count);
      step_view v;
      view_at(v, t, m, o.mesh, s);
      json node = {{"name", "step_" + std::to_string(s)}};
      const std::vector<int> kids = add_tree_nodes(d, v, s, o.gltf_instancing, "step_" + std::to_string(s) + "_", r.triangles);
      if (!kids.empty()) node["children"] = kids;
      std::vector<float> times, scales;
      auto key = [&](float time, float scale) { times.push_back(time); for (int k = 0; k < 3; ++k) scales.push_back(scale); };
      if (j > 0) key(0, 0);
      key(float(j) * sps, 1);
      if (j + 1 < count) key(float(j + 1) * sps, 0);
      if (j + 1 < count) node["scale"] = {0.0, 0.0, 0.0};  // a still viewer shows the last step
      const int id = d.add_node(node);
      roots.push_back(id);
      const int in = d.add_accessor(d.add_view(times.data(), times.size() * 4, 0), gl_float, times.size(), "SCALAR",
                                    {{"min", {times.front()}}, {"max", {times.back()}}});
      const int outp = d.add_accessor(d.add_view(scales.data(), scales.size() * 4, 0), gl_float, times.size(), "VEC3");
      samplers.push_back({{"input", in}, {"output", outp}, {"interpolation", "STEP"}});
      channels.push_back({{"sampler", int(samplers.size()) - 1}, {"target", {{"node", id}, {"path", "scale"}}}});
      if (o.progress) o.progress(0.1f + 0.8f * float(j + 1) / float(count));
    }
    if (count > 1) d.j["animations"] = json::array({{{"name", "growth"}, {"channels", channels}, {"samplers", samplers}}});
  }
  if (cancelled(o)) { r.error = "export cancelled"; return r; }
  d.j["scenes"] = json::array({{{"name", "sylva"}, {"nodes", roots}}});
  d.j["scene"] = 0;
  std::vector<std::pair<std::string, std::string>> files;
  if (binary) {
    d.j["buffers"] = json::array({{{"byteLength", d.bin.size()}}});
    files.emplace_back(path, glb_container(d.j.dump(), d.bin));
  } else {
    d.j["buffers"] = json::array({{{"byteLength", d.bin.size()}, {"uri", stem_name + ".bin"}}});
    files.emplace_back(stem + ".bin", std::move(d.bin));
    files.emplace_back(stem + "_bark.png", tex.bark_png);
    files.emplace_back(stem + "_bark_normal.png", tex.normal_png);
    files.emplace_back(stem + "_leaves.png", tex.leaves_png);
    files.emplace_back(path, d.j.dump(1));
  }
  r.bytes = files.back().second.size();
  if (o.dry_run) return r;
  r.error = write_all(files, r);
  if (o.progress) o.progress(1.0f);
  return r;
}

// ---------------------------------------------------------------- OBJ + MTL
void put_float(std::string& s, float v) {
  char buf[32];
  const auto res = std::to_chars(buf, buf + sizeof buf, std::isfinite(v) ? v : 0.0f);
  s.append(buf, res.ptr);
}

export_result export_obj(const tree_skeleton& t, const tree_mesh& m, const export_info& info, const std::string& path,
                         const export_options& o) {
  export_result r;
  const std::string stem = stem_path(path), stem_name = file_name(stem);
  const int s = o.step < 0 ? std::max(t.steps, 0) : std::min(o.step, std::max(t.steps, 0));
  step_view v;
  view_at(v, t, m, o.mesh, s);
  std::vector<tree_part> parts = split_parts(*v.skeleton, *v.mesh, s, true);
  std::string text = "# Sylva tree: generator " + info.generator + ", seed " + std::to_string(info.seed) +
                     ", step " + std::to_string(s) + "\nmtllib " + stem_name + ".mtl\n";
  size_t verts = 0;
  for (const tree_part& p : parts) verts += p.bark.position.size() + p.leaves.position.size();
  text.reserve(verts * 110);
  auto vertices = [&](const geometry& g) {
    for (size_t k = 0; k < g.position.size(); ++k) {
      text += "v "; put_float(text, g.position[k].x); text += ' '; put_float(text, g.position[k].y); text += ' '; put_float(text, g.position[k].z);
      text += "\nvt "; put_float(text, g.uv[k].x); text += ' '; put_float(text, 1 - g.uv[k].y);  // OBJ's v runs up
      text += "\nvn "; put_float(text, g.normal[k].x); text += ' '; put_float(text, g.normal[k].y); text += ' '; put_float(text, g.normal[k].z);
      text += '\n';
    }
  };
  // All vertices first, then faces by group, so that `bark` and `leaves` are single groups.
  std::vector<size_t> bark_base, leaf_base;
  size_t next = 1;  // OBJ indices start at 1
  for (const tree_part& p : parts) {
    bark_base.push_back(next);
    vertices(p.bark);
    next += p.bark.position.size();
    leaf_base.push_back(next);
    vertices(p.leaves);
    next += p.leaves.position.size();
  }
  if (cancelled(o)) { r.error = "export cancelled"; return r; }
  auto faces = [&](const geometry& g, size_t base) {
    char buf[24];
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
  text += "g bark\nusemtl bark\n";
  for (size_t k = 0; k < parts.size(); ++k) faces(parts[k].bark, bark_base[k]);
  text += "g leaves\nusemtl leaves\n";
  for (size_t k = 0; k < parts.size(); ++k) faces(parts[k].leaves, leaf_base[k]);

  const std::string mtl = "# Sylva materials\nnewmtl bark\nKa 0 0 0\nKd 1 1 1\nKs 0 0 0\nillum 1\nmap_Kd " + stem_name +
                          "_bark.png\nnorm " + stem_name + "_bark_normal.png\n\nnewmtl leaves\nKa 0 0 0\nKd 1 1 1\nKs 0 0 0\nillum 1\nmap_Kd " +
                          stem_name + "_leaves.png\nmap_d -imfchan m " + stem_name + "_leaves.png\n";
  gltf_textures tex;
  if (r.error = make_gltf_textures(o, tex); !r.error.empty()) return r;
  std::vector<std::pair<std::string, std::string>> files = {{stem + ".mtl", mtl},
                                                            {stem + "_bark.png", tex.bark_png},
                                                            {stem + "_bark_normal.png", tex.normal_png},
                                                            {stem + "_leaves.png", tex.leaves_png},
                                                            {path, std::move(text)}};
  r.bytes = files.back().second.size();
  if (o.dry_run) return r;
  r.error = write_all(files, r);
  return r;
}

}  // namespace

// ---------------------------------------------------------------- skeleton JSON (DESIGN §6)
std::string skeleton_json(const tree_skeleton& full, const export_info& info, int step) {
  const tree_skeleton t = step >= 0 && step < full.steps ? skeleton_at_step(full, step) : full;
  json nodes;
  json pos = json::array(), par = json::array(), rad = json::array(), born = json::array(), died = json::array(), ord = json::array();
  for (size_t i = 0; i < t.size(); ++i) {
    pos.push_back({t.position[i].x, t.position[i].y, t.position[i].z});
    par.push_back(t.parent[i]);
    rad.push_back(t.radius[i]);
    born.push_back(t.born[i]);
    if (t.died[i] == never_died) died.push_back(nullptr); else died.push_back(t.died[i]);
    ord.push_back(t.order[i]);
  }
  nodes = {{"position", pos}, {"parent", par}, {"radius", rad}, {"born", born}, {"died", died}, {"order", ord}};
  json leaves = json::array();
  for (const leaf& l : t.leaves)
    leaves.push_back({{"position", {l.position.x, l.position.y, l.position.z}},
                      {"orientation", {l.orientation.x, l.orientation.y, l.orientation.z, l.orientation.w}},
                      {"size", l.size}, {"born", l.born},
                      {"died", l.died == never_died ? json(nullptr) : json(l.died)}, {"node", l.node}});
  json doc = {{"sylva_skeleton", 1}, {"generator", info.generator}, {"seed", info.seed}, {"steps", t.steps},
              {"tree_count", t.tree_count}, {"nodes", nodes}, {"leaves", leaves}};
  return doc.dump();
}

export_result export_tree(const tree_skeleton& t, const tree_mesh& m, const export_info& info, const std::string& path,
                          const export_options& o) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  export_result r;
  if (ext == ".glb" || ext == ".gltf") return export_gltf(t, m, info, path, o, ext == ".glb");
  if (ext == ".obj") return export_obj(t, m, info, path, o);
  if (ext == ".json") {
    const std::string text = skeleton_json(t, info, o.step);
    r.bytes = text.size();
    if (o.dry_run) return r;
    r.error = write_all({{path, text}}, r);
    return r;
  }
  r.error = "cannot export " + path + ": unknown extension \"" + ext + "\" (use .glb, .gltf, .obj or .json)";
  return r;
}

}  // namespace sylva
