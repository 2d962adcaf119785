// glTF 2.0 export (.glb / .gltf + .bin + PNGs): the document, materials, nodes, LODs, animation.
#include "render/io/export_internal.h"

#include "render/io/export.h"
#include "render/mesh/lod_cards.h"
#include "render/mesh/season.h"
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

// ---------------------------------------------------------------- glTF 2.0
constexpr int gl_float = 5126, gl_ushort = 5123, gl_uint = 5125, gl_byte = 5120, gl_ubyte = 5121;
constexpr int array_buffer = 34962, element_array_buffer = 34963;

struct position_grid {
  bool on = false;
  glm::vec3 origin{0};
  float step = 1;
};

struct gltf_doc {
  json j = json::object();
  std::string bin;
  const wind_bake* wind = nullptr;   // set: primitives get JOINTS_0 / WEIGHTS_0 of its skin

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
      extra["min"] = std::move(jl);   // set key by key: assigning an initializer list here leaked
      extra["max"] = std::move(jh);   // the object it replaced (LeakSanitizer, fuzz_export)
    }
    return add_accessor(view, gl_float, v.size(), type, extra);
  }
  int add_indices(const std::vector<uint32_t>& idx, size_t vertices) {
    assert(std::all_of(idx.begin(), idx.end(), [&](uint32_t i) { return i < vertices; }) &&
           "glTF export: an index past its primitive's vertices");
    if (vertices < 65536) {  // 16-bit when every index fits
      std::vector<uint16_t> small(idx.begin(), idx.end());
      return add_accessor(add_view(small.data(), small.size() * 2, element_array_buffer), gl_ushort, idx.size(), "SCALAR");
    }
    return add_accessor(add_view(idx.data(), idx.size() * 4, element_array_buffer), gl_uint, idx.size(), "SCALAR");
  }
  // Compact files (KHR_mesh_quantization): normals, tangents, colours and 0..1 texture
  // coordinates as normalised integers; positions as 16-bit integers on a grid whose origin and
  // (uniform, so normals stay true) step are the translation and scale of the mesh's node.
  bool compact = false;
  using grid = position_grid;
  // Compact files: the bark's texture coordinates (tiles well past 0..1) as 16-bit fractions of
  // this box, which KHR_texture_transform on the bark's textures maps back.
  bool bark_uv = false;
  glm::vec2 bark_uv_origin{0}, bark_uv_span{1};
  void set_bark_uv_box(const std::vector<const tree_mesh*>& meshes) {
    glm::vec2 lo(1e30f), hi(-1e30f);
    for (const tree_mesh* m : meshes)
      for (const glm::vec2& t : m->uv) lo = glm::min(lo, t), hi = glm::max(hi, t);
    if (lo.x > hi.x) return;
    bark_uv = true;
    bark_uv_origin = glm::floor(lo) - 1.0f;   // whole tiles, a tile of margin each side
    bark_uv_span = glm::ceil(hi) + 1.0f - bark_uv_origin;
  }
  template <class T, int N>
  int add_packed(const std::vector<T>& values, size_t n, int component, bool normalized, const char* type, int target = array_buffer) {
    const size_t stride = (sizeof(T) * N + 3) / 4 * 4;   // vertex elements are 4-byte aligned
    std::vector<unsigned char> bytes(n * stride, 0);
    for (size_t i = 0; i < n; ++i) std::memcpy(&bytes[i * stride], &values[i * N], sizeof(T) * N);
    const int view = add_view(bytes.data(), bytes.size(), target);
    if (target) j["bufferViews"].back()["byteStride"] = stride;
    json extra = json::object();
    if (normalized) extra["normalized"] = true;
    return add_accessor(view, component, n, type, extra);
  }
  template <int N, class V>
  int add_snorm8(const std::vector<V>& v, const char* type) {
    std::vector<int8_t> q(v.size() * N);
    for (size_t i = 0; i < v.size(); ++i)
      for (int c = 0; c < N; ++c) q[i * N + c] = int8_t(std::clamp(std::lround(v[i][c] * 127.0f), -127l, 127l));
    return add_packed<int8_t, N>(q, v.size(), gl_byte, true, type);
  }
  // `levels`: grid steps across the longest side (65535: 16 bits; leaf cards take 16383, 0.8 mm on
  // a 13 m crown, a quarter less data).
  static grid grid_of(const std::vector<const geometry*>& gs, float levels = 65535.0f) {
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const geometry* g : gs)
      for (const glm::vec3& p : g->position) lo = glm::min(lo, p), hi = glm::max(hi, p);
    grid q;
    if (lo.x > hi.x) return q;
    const float extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
    q.on = true;
    q.origin = lo;
    q.step = extent > 0 ? extent / levels : 1.0f;
    return q;
  }
  static void place(json& node, const grid& q) {
    if (!q.on) return;
    node["translation"] = {q.origin.x, q.origin.y, q.origin.z};
    node["scale"] = {q.step, q.step, q.step};
  }
  json compact_attributes(const geometry& g, bool tangents, const grid& q, bool bark) {
    json attr;
    if (q.on) {
      std::vector<uint16_t> p(g.position.size() * 3);
      std::array<uint16_t, 3> lo{65535, 65535, 65535}, hi{0, 0, 0};
      for (size_t i = 0; i < g.position.size(); ++i)
        for (int c = 0; c < 3; ++c) {
          const uint16_t v = uint16_t(std::clamp(std::lround((g.position[i][c] - q.origin[c]) / q.step), 0l, 65535l));
          p[i * 3 + c] = v;
          lo[size_t(c)] = std::min(lo[size_t(c)], v), hi[size_t(c)] = std::max(hi[size_t(c)], v);
        }
      attr["POSITION"] = add_packed<uint16_t, 3>(p, g.position.size(), gl_ushort, false, "VEC3");
      j["accessors"].back()["min"] = {lo[0], lo[1], lo[2]};
      j["accessors"].back()["max"] = {hi[0], hi[1], hi[2]};
    } else {
      attr["POSITION"] = add_vectors(g.position, "VEC3", array_buffer, true);
    }
    attr["NORMAL"] = add_snorm8<3>(g.normal, "VEC3");
    const bool unit_uv = std::all_of(g.uv.begin(), g.uv.end(), [](const glm::vec2& t) {
      return t.x >= 0 && t.x <= 1 && t.y >= 0 && t.y <= 1;
    });
    // Leaf cards' corners (0 or 1) fit in bytes exactly, which compress to half of 16-bit ones.
    const bool byte_uv = unit_uv && std::all_of(g.uv.begin(), g.uv.end(), [](const glm::vec2& t) {
      return std::abs(t.x * 255.0f - std::round(t.x * 255.0f)) < 1e-3f && std::abs(t.y * 255.0f - std::round(t.y * 255.0f)) < 1e-3f;
    });
    if (byte_uv) {
      std::vector<uint8_t> t(g.uv.size() * 2);
      for (size_t i = 0; i < g.uv.size(); ++i)
        for (int c = 0; c < 2; ++c) t[i * 2 + c] = uint8_t(std::lround(g.uv[i][c] * 255.0f));
      attr["TEXCOORD_0"] = add_packed<uint8_t, 2>(t, g.uv.size(), gl_ubyte, true, "VEC2");
    } else if (bark && bark_uv) {
      std::vector<uint16_t> t(g.uv.size() * 2);
      for (size_t i = 0; i < g.uv.size(); ++i)
        for (int c = 0; c < 2; ++c)
          t[i * 2 + c] = uint16_t(std::clamp(std::lround((g.uv[i][c] - bark_uv_origin[c]) / bark_uv_span[c] * 65535.0f), 0l, 65535l));
      attr["TEXCOORD_0"] = add_packed<uint16_t, 2>(t, g.uv.size(), gl_ushort, true, "VEC2");
    } else if (unit_uv) {
      std::vector<uint16_t> t(g.uv.size() * 2);
      for (size_t i = 0; i < g.uv.size(); ++i)
        for (int c = 0; c < 2; ++c) t[i * 2 + c] = uint16_t(std::lround(g.uv[i][c] * 65535.0f));
      attr["TEXCOORD_0"] = add_packed<uint16_t, 2>(t, g.uv.size(), gl_ushort, true, "VEC2");
    } else {
      attr["TEXCOORD_0"] = add_vectors(g.uv, "VEC2", array_buffer);   // bark: tiles beyond 0..1
    }
    if (tangents && !g.tangent.empty()) attr["TANGENT"] = add_snorm8<4>(g.tangent, "VEC4");
    if (g.color.size() == g.position.size()) {
      std::vector<uint8_t> c(g.color.size() * 3);
      for (size_t i = 0; i < g.color.size(); ++i)
        for (int k = 0; k < 3; ++k) c[i * 3 + k] = uint8_t(std::clamp(std::lround(g.color[i][k] * 255.0f), 0l, 255l));
      attr["COLOR_0"] = add_packed<uint8_t, 3>(c, g.color.size(), gl_ubyte, true, "VEC3");
    }
    return attr;
  }

  // One primitive; TANGENT only when its material has a normal map. `q`: the mesh's position grid
  // (compact files; its node carries the grid through place()).
  json add_primitive(const geometry& g, int material, bool tangents, const grid& q = {}, bool bark = false) {
    json attr;
    if (compact) {
      attr = compact_attributes(g, tangents, q, bark);
    } else {
      attr = {{"POSITION", add_vectors(g.position, "VEC3", array_buffer, true)},
              {"NORMAL", add_vectors(g.normal, "VEC3", array_buffer)},
              {"TEXCOORD_0", add_vectors(g.uv, "VEC2", array_buffer)}};
      if (tangents && !g.tangent.empty()) attr["TANGENT"] = add_vectors(g.tangent, "VEC4", array_buffer);
      // Crown occlusion, so the tree's inside is darker in other tools too.
      if (g.color.size() == g.position.size()) attr["COLOR_0"] = add_vectors(g.color, "VEC3", array_buffer);
    }
    if (wind && g.node.size() == g.position.size()) attr.update(wind_skin_attributes(j, bin, *wind, g.node));
    const int idx = add_indices(g.index, g.position.size());
    return {{"attributes", attr}, {"indices", idx}, {"material", material}};
  }
  int add_mesh(const std::string& name, json primitives) {
    j["meshes"].push_back({{"name", name}, {"primitives", std::move(primitives)}});
    return int(j["meshes"].size()) - 1;
  }
  // Lists an extension once in extensionsUsed (and extensionsRequired when a viewer without it
  // would show the file wrong).
  void use(const char* name, bool required) { use_extension(j, name, required); }
  int add_node(json node) {
    j["nodes"].push_back(std::move(node));
    return int(j["nodes"].size()) - 1;
  }
};

// Percent-encodes a file name for a glTF uri (RFC 3986: unreserved characters stay).
std::string uri_of(const std::string& name) {
  static const char hex[] = "0123456789ABCDEF";
  std::string out;
  for (const unsigned char c : name) {
    if (std::isalnum(c) || c == '-' || c == '_' || c == '.' || c == '~') out.push_back(char(c));
    else out += {'%', hex[c >> 4], hex[c & 15]};
  }
  return out;
}

// glTF materials, textures and images, added when a primitive first needs them. Images are
// embedded (GLB) or listed in `files` to be written beside the .gltf.
struct gltf_materials {
  gltf_doc& d;
  material_source& src;
  bool embed;
  std::string stem_name;
  std::vector<std::pair<std::string, std::string>> files;  // (file name, PNG bytes)
  int bark = -1;
  bool bark_normal = false;
  std::array<int, leaf_slots> leaf = make_filled(-1);
  std::array<bool, leaf_slots> leaf_normal{};
  std::array<int, leaf_slots> quad_mesh = make_filled(-1);  // EXT_mesh_gpu_instancing: one card per slot
  std::array<size_t, leaf_slots> quad_triangles{};           // ... and its triangles a side

  static std::array<int, leaf_slots> make_filled(int v) {
    std::array<int, leaf_slots> a;
    a.fill(v);
    return a;
  }
  // Sampler 0 repeats (bark tiles), sampler 1 clamps (leaf cards).
  int texture(const std::string& png, bool repeat, const std::string& name) {
    if (!d.j.contains("samplers"))
      d.j["samplers"] = json::array({{{"magFilter", 9729}, {"minFilter", 9987}, {"wrapS", 10497}, {"wrapT", 10497}},
                                     {{"magFilter", 9729}, {"minFilter", 9987}, {"wrapS", 33071}, {"wrapT", 33071}}});
    std::string jpeg;
    const bool as_jpeg = d.compact && jpeg_if_opaque(png, jpeg);   // compact: opaque maps as JPEG
    const std::string& bytes = as_jpeg ? jpeg : png;
    if (embed) {
      d.j["images"].push_back({{"name", name}, {"bufferView", d.add_view(bytes.data(), bytes.size(), 0)},
                               {"mimeType", as_jpeg ? "image/jpeg" : "image/png"}});
    } else {
      const std::string file = stem_name + "_" + name + (as_jpeg ? ".jpg" : ".png");
      d.j["images"].push_back({{"name", name}, {"uri", uri_of(file)}});
      files.emplace_back(file, bytes);
    }
    d.j["textures"].push_back({{"sampler", repeat ? 0 : 1}, {"source", int(d.j["images"].size()) - 1}});
    return int(d.j["textures"].size()) - 1;
  }
  int add_material(json m) {
    d.j["materials"].push_back(std::move(m));
    return int(d.j["materials"].size()) - 1;
  }
  // -1 when a PNG could not be encoded (src.error says why).
  int bark_material() {
    if (bark >= 0) return bark;
    const material_pngs* p = src.bark();
    if (!p) return -1;
    const std::string name = src.bark_name();
    json pbr = {{"baseColorTexture", {{"index", texture(p->color, true, name)}}}, {"metallicFactor", 0.0}};
    if (!p->roughness.empty()) pbr["metallicRoughnessTexture"] = {{"index", texture(p->roughness, true, name + "_roughness")}};
    else pbr["roughnessFactor"] = 0.9;
    json m = {{"name", name}, {"pbrMetallicRoughness", pbr}};
    if (!p->normal.empty()) m["normalTexture"] = {{"index", texture(p->normal, true, name + "_normal")}};
    bark_normal = !p->normal.empty();
    if (d.compact && d.bark_uv) {   // the 16-bit coordinates' box (gltf_doc::set_bark_uv_box)
      const json transform = {{"KHR_texture_transform", {{"offset", {d.bark_uv_origin.x, d.bark_uv_origin.y}},
                                                         {"scale", {d.bark_uv_span.x, d.bark_uv_span.y}}}}};
      for (json* info : {&m["pbrMetallicRoughness"]["baseColorTexture"], &m["pbrMetallicRoughness"]["metallicRoughnessTexture"],
                         &m["normalTexture"]})
        if (info->is_object()) (*info)["extensions"] = transform;
      d.use("KHR_texture_transform", true);
    }
    return bark = add_material(std::move(m));
  }
  int leaf_material(int slot) {
    if (leaf[size_t(slot)] >= 0) return leaf[size_t(slot)];
    const material_pngs* p = src.leaf(slot);
    if (!p) return -1;
    const std::string name = src.leaf_name(slot);
    json m = {{"name", name},
              {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", texture(p->color, false, name)}}},
                                        {"metallicFactor", 0.0}, {"roughnessFactor", 0.6}}},
              {"alphaMode", "MASK"},
              {"alphaCutoff", src.alpha_cutoff()}};   // single-sided: every card has a face per side
    if (!p->normal.empty()) m["normalTexture"] = {{"index", texture(p->normal, false, name + "_normal")}};
    leaf_normal[size_t(slot)] = !p->normal.empty();
    return leaf[size_t(slot)] = add_material(std::move(m));
  }
};

// Nodes for one view of the tree: one node per tree, with a bark child and a leaves child (one
// primitive per leaf material). Returns the node ids to put under the parent; counts triangles.
// "" or the error.
// With `level` (a LOD level's name, "<tree>_LOD<k>"), each tree is one node and one mesh of that
// name holding the bark and every leaf primitive, as engines' LOD conventions want (a forest's
// trees are "<tree>_tree_<n>_LOD<k>").
std::string add_tree_nodes(gltf_doc& d, gltf_materials& mats, const step_view& v, int step, bool instanced,
                           const std::string& prefix, size_t& triangles, std::vector<int>& out, int skin = -1,
                           const lod_name* level = nullptr) {
  const bool one = mats.src.one_leaf_material();
  std::vector<tree_part> parts = split_parts(*v.skeleton, *v.mesh, step, !instanced, one, mats.src.leaf_looks(), mats.src.bark_colors());
  for (size_t k = 0; k < parts.size(); ++k) {
    const tree_part& part = parts[k];
    json tree = {{"name", prefix + (parts.size() > 1 ? "tree_" + std::to_string(k + 1) : "tree")}};
    json children = json::array();
    // Compact files: one position grid per mesh; a skinned mesh ignores its node's transform, so
    // its positions stay floats.
    gltf_doc::grid bark_grid, leaf_grid;
    if (d.compact && !d.wind) {
      std::vector<const geometry*> leaves;
      for (const geometry& g : part.leaves) leaves.push_back(&g);
      leaf_grid = gltf_doc::grid_of(leaves, 16383.0f);
      if (level) leaves.push_back(&part.bark);
      bark_grid = level ? gltf_doc::grid_of(leaves) : gltf_doc::grid_of({&part.bark});
      if (level) leaf_grid = bark_grid;   // one mesh, one node
    }
    json bark_prims = json::array();
    if (!part.bark.empty()) {
      const int mat = mats.bark_material();
      if (mat < 0) return mats.src.error;
      bark_prims.push_back(d.add_primitive(part.bark, mat, mats.bark_normal, bark_grid, true));
      triangles += part.bark.index.size() / 3;
    }
    json prims = json::array();
    for (int slot = 0; slot < leaf_slots; ++slot) {
      const geometry& g = part.leaves[size_t(slot)];
      if (g.empty()) continue;
      const int mat = mats.leaf_material(slot);
      if (mat < 0) return mats.src.error;
      prims.push_back(d.add_primitive(g, mat, mats.leaf_normal[size_t(slot)], leaf_grid));
      triangles += g.index.size() / 3;
    }
    if (level) {
      for (json& p : prims) bark_prims.push_back(std::move(p));
      const std::string name = parts.size() > 1 ? level->of_tree(k + 1) : level->name();
      if (bark_prims.empty()) continue;
      json node = {{"name", name}, {"mesh", d.add_mesh(name, std::move(bark_prims))}};
      gltf_doc::place(node, bark_grid);
      out.push_back(d.add_node(node));
      continue;
    }
    if (!bark_prims.empty()) {
      json node = {{"name", "bark"}, {"mesh", d.add_mesh("bark", std::move(bark_prims))}};
      gltf_doc::place(node, bark_grid);
      children.push_back(d.add_node(node));
    }
    if (!prims.empty()) {
      json node = {{"name", "leaves"}, {"mesh", d.add_mesh("leaves", std::move(prims))}};
      gltf_doc::place(node, leaf_grid);
      children.push_back(d.add_node(node));
    }
    if (skin >= 0) {   // skinned meshes must be scene roots without transforms (glTF 2.0 §3.7.3)
      for (const json& c : children) {
        d.j["nodes"][c.get<size_t>()]["skin"] = skin;
        d.j["nodes"][c.get<size_t>()]["name"] = prefix + d.j["nodes"][c.get<size_t>()]["name"].get<std::string>();
        out.push_back(c.get<int>());
      }
      continue;
    }
    if (!children.empty()) tree["children"] = children;
    out.push_back(d.add_node(tree));
  }
  if (instanced) {
    // EXT_mesh_gpu_instancing: one leaf card per material, one instance per leaf alive at `step`.
    std::array<std::vector<glm::vec3>, leaf_slots> tr, sc, grey;
    std::array<std::vector<glm::vec4>, leaf_slots> rot;
    const leaf_look look = mats.src.leaf_looks();
    const std::array<blade_mesh, leaf_slots> blades = slot_blades(v.mesh->blade, one, true, look);   // the prototypes' fine grids
    for (size_t i = 0; i < v.mesh->leaves.size(); ++i) {
      const leaf_instance& l = v.mesh->leaves[i];
      if (!(l.born <= step && step < l.died)) continue;
      const size_t slot = size_t(leaf_slot(l, one));
      tr[slot].push_back(l.position);
      rot[slot].push_back(l.orientation / std::max(glm::length(l.orientation), 1e-12f));
      sc[slot].push_back(glm::vec3(std::max(l.size, 1e-6f)));
      // Crown occlusion per instance, times the leaf's colour factor (leaf_color_factor) but for fruit
      // and baked cards, which keep their own colours.
      const glm::vec3 factor = leaf_color_of(l, i, int(slot), one, look);
      grey[slot].push_back(glm::min(glm::vec3(float(l.occlusion) / 255.0f) * factor, glm::vec3(1.0f)));
    }
    for (int slot = 0; slot < leaf_slots; ++slot) {
      const size_t s = size_t(slot);
      if (tr[s].empty()) continue;
      if (mats.quad_mesh[s] < 0) {
        const int mat = mats.leaf_material(slot);
        if (mat < 0) return mats.src.error;
        geometry quad;
        // Two sides, unbent: an instance's crown direction would need a normal per instance. The
        // prototype is the blade's full grid (render/mesh/leaf_blade.h), or the flat card.
        leaf_bake prototype;
        prototype.blade = &blades[s];
        bake_leaf(quad, {glm::vec3(0), glm::vec4(0, 0, 0, 1), 1.0f, 0, 0, 0, 0}, prototype);
        mats.quad_triangles[s] = quad.index.size() / (blades[s].closed ? 3 : 6);
        mats.quad_mesh[s] = d.add_mesh(mats.src.leaf_name(slot), json::array({d.add_primitive(quad, mat, mats.leaf_normal[s])}));
      }
      json attrs = {{"TRANSLATION", d.add_vectors(tr[s], "VEC3", 0)}, {"ROTATION", d.add_vectors(rot[s], "VEC4", 0)},
                    {"SCALE", d.add_vectors(sc[s], "VEC3", 0)},
                    // Application-specific (EXT_mesh_gpu_instancing allows "_" names); three.js
                    // reads _COLOR_0 as the instance colour, which multiplies the card's colour.
                    {"_COLOR_0", d.add_vectors(grey[s], "VEC3", 0)}};
      out.push_back(d.add_node({{"name", prefix + mats.src.leaf_name(slot)}, {"mesh", mats.quad_mesh[s]},
                                {"extensions", {{"EXT_mesh_gpu_instancing", {{"attributes", attrs}}}}}}));
      d.use("EXT_mesh_gpu_instancing", false);
      triangles += tr[s].size() * mats.quad_triangles[s];
    }
  }
  return "";
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

// --lods: one root node per level, LOD0 carrying MSFT_lod with the lower levels' ids and
// MSFT_screencoverage in its extras; the impostor a textured quad after them. Scene 0 shows LOD0
// (the levels hang off it through the extension), scene 1 lists every level as its own root, so a
// viewer without the extension still finds each one. "" or the error.
std::string add_lod_nodes(gltf_doc& d, gltf_materials& mats, const tree_skeleton& t, const tree_mesh& m,
                          const export_options& o, const std::string& tree_name, size_t& triangles, std::vector<int>& roots,
                          std::vector<int>& all) {
  const int last = std::max(t.steps, 0);
  std::vector<const tree_mesh*> levels{&m};
  std::vector<float> coverage{o.lod0_coverage};
  for (const export_lod_level& l : o.lods)
    if (l.mesh) levels.push_back(l.mesh), coverage.push_back(l.coverage);
  std::vector<int> ids;
  for (size_t k = 0; k < levels.size(); ++k) {
    step_view v;
    v.skeleton = &t;
    v.mesh = levels[k];
    std::vector<int> kids;
    size_t tris = 0;
    const lod_name level{tree_name, int(k)};
    if (std::string e = add_tree_nodes(d, mats, v, last, false, "", tris, kids, -1, &level); !e.empty()) return e;
    json extras = {{"sylva_lod", k}, {"triangles", tris}};
    if (k > 0 && k - 1 < o.lods.size()) extras["budget_triangles"] = o.lods[k - 1].budget;
    if (kids.size() == 1) {   // one tree: the level's node is its mesh's node
      ids.push_back(kids[0]);
      d.j["nodes"][size_t(kids[0])]["extras"] = extras;
    } else {
      json node = {{"name", level.name()}, {"extras", extras}};
      if (!kids.empty()) node["children"] = kids;
      ids.push_back(d.add_node(node));
    }
    triangles += k == 0 ? tris : 0;   // the export's count is LOD0's; the levels are in extras
  }
  if (o.impostor && !o.impostor->color_png.empty()) {
    const export_impostor& im = *o.impostor;
    // Cell 0 (view from +Z) on a quad facing +Z, centred on the tree; the whole atlas is the texture
    // so an engine can pick the cell for the view direction (extras: the layout).
    geometry q;
    const float hw = 0.5f * im.width, hh = 0.5f * im.height;
    const float cu = 1.0f / float(std::max(im.columns, 1)), cv = 1.0f / float(std::max(im.rows, 1));
    const glm::vec3 c = im.centre;
    q.position = {c + glm::vec3(-hw, -hh, 0), c + glm::vec3(hw, -hh, 0), c + glm::vec3(hw, hh, 0), c + glm::vec3(-hw, hh, 0)};
    q.normal.assign(4, glm::vec3(0, 0, 1));
    q.uv = {{0, cv}, {cu, cv}, {cu, 0}, {0, 0}};   // glTF uv origin: the image's top-left corner
    q.tangent.assign(4, glm::vec4(1, 0, 0, 1));
    q.index = {0, 1, 2, 0, 2, 3};
    json pbr = {{"baseColorTexture", {{"index", mats.texture(im.color_png, false, "impostor")}}},
                {"metallicFactor", 0.0}, {"roughnessFactor", 0.8}};
    json mat = {{"name", "impostor"}, {"pbrMetallicRoughness", pbr}, {"alphaMode", "MASK"}, {"alphaCutoff", 0.5}, {"doubleSided", true}};
    const bool normals = !im.normal_png.empty();
    if (normals) mat["normalTexture"] = {{"index", mats.texture(im.normal_png, false, "impostor_normal")}};
    const int mesh = d.add_mesh("impostor", json::array({d.add_primitive(q, mats.add_material(mat), normals)}));
    json layout = {{"views", im.views}, {"columns", im.columns}, {"rows", im.rows}, {"cell_width_m", im.width},
                   {"cell_height_m", im.height}, {"first_view", "+Z"}, {"turn", "view k at 360*k/views degrees from +Z toward +X"}};
    ids.push_back(d.add_node({{"name", tree_name + "_impostor"}, {"mesh", mesh}, {"extras", {{"sylva_impostor", layout}}}}));
    coverage.push_back(im.coverage);
  }
  if (ids.size() > 1) {
    json lower = json::array();
    for (size_t k = 1; k < ids.size(); ++k) lower.push_back(ids[k]);
    json& lod0 = d.j["nodes"][size_t(ids[0])];
    lod0["extensions"] = {{"MSFT_lod", {{"ids", lower}}}};
    lod0["extras"]["MSFT_screencoverage"] = coverage;
    d.use("MSFT_lod", false);
  }
  roots.push_back(ids[0]);
  all = ids;
  return "";
}

}  // namespace

export_result export_gltf(const tree_skeleton& t, const tree_mesh& m, const export_info& info, const std::string& path,
                          const export_options& o, bool binary) {
  export_result r;
  const std::string stem = stem_path(path), stem_name = file_name(stem);
  gltf_doc d;
  d.j["asset"] = {{"version", "2.0"}, {"generator", "Sylva"},
                  {"extras", {{"generator", info.generator}, {"seed", info.seed}}}};
  material_source src(o, r.warning);
  gltf_materials mats{d, src, binary, stem_name};
  d.compact = o.compact;
  if (o.compact && !o.growth_animation) {   // growth steps are re-meshed: their bark keeps floats
    std::vector<const tree_mesh*> meshes{&m};
    for (const export_lod_level& l : o.lods)
      if (l.mesh) meshes.push_back(l.mesh);
    d.set_bark_uv_box(meshes);
  }
  // The final tree's buffer size, so that big exports are not copied while the buffer grows.
  d.bin.reserve(m.position.size() * 48 + m.index.size() * 4 + m.leaves.size() * 200 + (size_t(1) << 20));
  if (o.progress) o.progress(0.1f);

  const int final_step = std::max(t.steps, 0);
  std::vector<int> roots;
  std::vector<int> lod_roots;
  if (!o.lods.empty() || o.impostor) {
    if (r.error = add_lod_nodes(d, mats, t, m, o, lod_tree_name(stem_name), r.triangles, roots, lod_roots); !r.error.empty()) return r;
  } else if (!o.growth_animation) {
    const int s = o.step < 0 ? final_step : std::min(o.step, final_step);
    step_view v;
    view_at(v, t, m, o.mesh, s);
    wind_bake wind;
    int skin = -1;
    json wind_channels = json::array(), wind_samplers = json::array();
    if (o.wind_seconds > 0) {   // the wind as a skin and a seamless loop
      wind = bake_wind(*v.skeleton, o.wind, o.wind_seconds);
      d.wind = &wind;
      skin = wind_add_skin(d.j, d.bin, wind, "", roots, wind_channels, wind_samplers);
      r.warning += (r.warning.empty() ? "" : "\n") + wind.note;
      if (o.gltf_instancing) r.warning += "\nwind: instanced leaves cannot be skinned and stay still; export without --instancing to sway them";
    }
    if (r.error = add_tree_nodes(d, mats, v, s, o.gltf_instancing, "", r.triangles, roots, skin); !r.error.empty()) return r;
    d.wind = nullptr;
    if (!wind_channels.empty())
      d.j["animations"] = json::array({{{"name", "wind"}, {"channels", wind_channels}, {"samplers", wind_samplers}}});
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
    json wind_channels = json::array(), wind_samplers = json::array();
    if (o.wind_seconds > 0 && o.gltf_instancing) {
      r.error = "--wind with --animation needs baked leaves: drop --instancing";
      return r;
    }
    for (int j = 0; j < count; ++j) {
      if (cancelled(o)) { r.error = "export cancelled"; return r; }
      const int s = sample(j, count);
      step_view v;
      view_at(v, t, m, o.mesh, s);
      json node = {{"name", "step_" + std::to_string(s)}};
      std::vector<int> kids;
      // With the wind each step gets its own small skin (16 joints); the growth's scale keys then
      // go on the step's root joint, since a skinned mesh ignores its parents' transforms.
      wind_bake wind;
      int skin = -1;
      std::vector<int> joint_roots;
      if (o.wind_seconds > 0) {
        wind = bake_wind(*v.skeleton, o.wind, o.wind_seconds, 16);
        d.wind = &wind;
        skin = wind_add_skin(d.j, d.bin, wind, "step_" + std::to_string(s) + "_", joint_roots, wind_channels, wind_samplers);
        if (j + 1 == count) r.warning += (r.warning.empty() ? "" : "\n") + wind.note;
      }
      r.error = add_tree_nodes(d, mats, v, s, o.gltf_instancing, "step_" + std::to_string(s) + "_", r.triangles, kids, skin);
      d.wind = nullptr;
      if (!r.error.empty()) return r;
      if (skin >= 0) {
        roots.insert(roots.end(), kids.begin(), kids.end());
        kids.clear();
        node = d.j["nodes"][size_t(joint_roots[0])];
      }
      if (!kids.empty()) node["children"] = kids;
      std::vector<float> times, scales;
      auto key = [&](float time, float scale) { times.push_back(time); for (int k = 0; k < 3; ++k) scales.push_back(scale); };
      if (j > 0) key(0, 0);
      key(float(j) * sps, 1);
      if (j + 1 < count) key(float(j + 1) * sps, 0);
      if (j + 1 < count) node["scale"] = {0.0, 0.0, 0.0};  // a still viewer shows the last step
      int id = 0;
      if (skin >= 0) d.j["nodes"][size_t(id = joint_roots[0])] = node;
      else id = d.add_node(node);
      roots.push_back(id);
      const int in = d.add_accessor(d.add_view(times.data(), times.size() * 4, 0), gl_float, times.size(), "SCALAR",
                                    {{"min", {times.front()}}, {"max", {times.back()}}});
      const int outp = d.add_accessor(d.add_view(scales.data(), scales.size() * 4, 0), gl_float, times.size(), "VEC3");
      samplers.push_back({{"input", in}, {"output", outp}, {"interpolation", "STEP"}});
      channels.push_back({{"sampler", int(samplers.size()) - 1}, {"target", {{"node", id}, {"path", "scale"}}}});
      if (o.progress) o.progress(0.1f + 0.8f * float(j + 1) / float(count));
    }
    if (count > 1) d.j["animations"] = json::array({{{"name", "growth"}, {"channels", channels}, {"samplers", samplers}}});
    if (!wind_channels.empty())
      d.j["animations"].push_back({{"name", "wind"}, {"channels", wind_channels}, {"samplers", wind_samplers}});
  }
  if (cancelled(o)) { r.error = "export cancelled"; return r; }
  d.j["scenes"] = json::array({{{"name", "sylva"}, {"nodes", roots}}});
  if (lod_roots.size() > 1) d.j["scenes"].push_back({{"name", "sylva_all_lods"}, {"nodes", lod_roots}});
  d.j["scene"] = 0;
  std::vector<std::pair<std::string, std::string>> files;
  if (o.compact) {
    d.use("KHR_mesh_quantization", true);
    d.bin = meshopt_compress(d.j, d.bin);   // sets both buffers: 0 the data, 1 the fallback
  } else {
    d.j["buffers"] = json::array({{{"byteLength", d.bin.size()}}});
  }
  if (binary) {
    files.emplace_back(path, glb_container(d.j.dump(-1, ' ', false, json::error_handler_t::replace), d.bin));
  } else {
    d.j["buffers"][0]["uri"] = uri_of(stem_name + ".bin");
    files.emplace_back(stem + ".bin", std::move(d.bin));
    const std::string dir = std::filesystem::path(path).parent_path().string();
    for (auto& [name, png] : mats.files) files.emplace_back((std::filesystem::path(dir) / name).string(), std::move(png));
    files.emplace_back(path, d.j.dump(1, ' ', false, json::error_handler_t::replace));
  }
  r.bytes = files.back().second.size();
  if (o.dry_run) return r;
  r.error = write_all(files, r);
  if (o.progress) o.progress(1.0f);
  return r;
}

}  // namespace sylva::export_internal
