// Exporters: glTF 2.0 (.glb / .gltf + .bin + PNGs), OBJ + MTL + PNGs, and the skeleton JSON.
#include "render/export.h"
#include "render/lod_cards.h"
#include "render/export_wind.h"

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

#include "render/preset.h"
#include "render/textures.h"

namespace sylva {
namespace {

using json = nlohmann::json;

// One primitive's worth of triangles, ready to write.
struct geometry {
  std::vector<glm::vec3> position, normal;
  std::vector<glm::vec2> uv;
  std::vector<glm::vec4> tangent;  // +u direction, w = handedness (written when a normal map is)
  std::vector<glm::vec3> color;    // crown occlusion as a grey vertex colour (COLOR_0), when the mesh has it
  std::vector<uint32_t> index;
  std::vector<uint32_t> node;      // skeleton node per vertex (the wind skin's weights)
  bool empty() const { return index.empty(); }
};

// Leaves go into one geometry per material slot: the archetype index, or slot 0 for everything
// when the user's leaf texture replaces the archetypes; a LOD level's baked cluster cards
// (render/lod_cards.h) take the slots after the archetypes'.
constexpr int leaf_slots = leaf_archetype_count + max_baked_cards;

struct tree_part {
  geometry bark;
  std::array<geometry, leaf_slots> leaves;
};

int leaf_slot(const leaf_instance& l, bool one_leaf_material) {
  return one_leaf_material ? 0 : std::clamp(int(l.texture), 0, leaf_slots - 1);
}

// A leaf instance as a card of one blade length square, base at the petiole (leaf frame of
// skeleton.h: blade in local XY, normal +Z, petiole along -Y) with the whole texture on it: the
// petiole at the bottom edge of the image (v = 1, glTF's origin is the top-left corner).
void bake_leaf(geometry& g, const leaf_instance& l) {
  const glm::quat q(l.orientation.w, l.orientation.x, l.orientation.y, l.orientation.z);
  const float h = l.size, w = l.size * 0.5f;
  const glm::vec3 corner[4] = {{-w, 0, 0}, {w, 0, 0}, {w, h, 0}, {-w, h, 0}};
  const glm::vec2 uv[4] = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
  auto unit = [](glm::vec3 v, glm::vec3 fallback) {
    const float len = glm::length(v);
    return len > 1e-6f ? v / len : fallback;
  };
  const glm::vec3 n = unit(q * glm::vec3(0, 0, 1), glm::vec3(0, 0, 1));
  // Tangent along +u (local +X); the bitangent n x t = local +Y runs up the image, so w = +1.
  const glm::vec4 t(unit(q * glm::vec3(1, 0, 0), glm::vec3(1, 0, 0)), 1.0f);
  const uint32_t base = uint32_t(g.position.size());
  for (int k = 0; k < 4; ++k) {
    g.position.push_back(l.position + q * corner[k]);
    g.normal.push_back(n);
    g.uv.push_back(uv[k]);
    g.tangent.push_back(t);
    g.color.push_back(glm::vec3(float(l.occlusion) / 255.0f));
    g.node.push_back(l.node);
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
// `step` are baked into quads (one geometry per leaf slot) unless `bake` is false, in which case
// they are left to the caller.
std::vector<tree_part> split_parts(const tree_skeleton& t, const tree_mesh& m, int step, bool bake, bool one_leaf_material) {
  std::vector<int32_t> tree_of(t.size(), 0);
  int trees = 0;
  for (size_t i = 0; i < t.size(); ++i) {
    assert(t.parent[i] < int32_t(i) && "split_parts: parent[i] < i");
    tree_of[i] = t.parent[i] < 0 ? trees++ : tree_of[t.parent[i]];
  }
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
      f.position.reserve(4 * n), f.normal.reserve(4 * n), f.uv.reserve(4 * n), f.tangent.reserve(4 * n), f.index.reserve(6 * n);
    }
  }
  std::vector<uint32_t> local(nv, UINT32_MAX);
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
      if (m.occlusion.size() == nv) g.color.push_back(glm::vec3(m.occlusion[v]));
      g.node.push_back(node);
    }
    g.index.push_back(local[v]);
  }
  if (bake)
    for (const leaf_instance& l : m.leaves)
      if (l.born <= step && step < l.died)
        bake_leaf(parts[l.node < tree_of.size() ? tree_of[l.node] : 0].leaves[size_t(leaf_slot(l, one_leaf_material))], l);
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

// ---------------------------------------------------------------- glTF 2.0
constexpr int gl_float = 5126, gl_ushort = 5123, gl_uint = 5125;
constexpr int array_buffer = 34962, element_array_buffer = 34963;

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
      extra = {{"min", jl}, {"max", jh}};
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
  // One primitive; TANGENT only when its material has a normal map.
  json add_primitive(const geometry& g, int material, bool tangents) {
    json attr = {{"POSITION", add_vectors(g.position, "VEC3", array_buffer, true)},
                 {"NORMAL", add_vectors(g.normal, "VEC3", array_buffer)},
                 {"TEXCOORD_0", add_vectors(g.uv, "VEC2", array_buffer)}};
    if (tangents && !g.tangent.empty()) attr["TANGENT"] = add_vectors(g.tangent, "VEC4", array_buffer);
    // Crown occlusion (issue 13), so the tree's inside is darker in other tools too.
    if (g.color.size() == g.position.size()) attr["COLOR_0"] = add_vectors(g.color, "VEC3", array_buffer);
    if (wind && g.node.size() == g.position.size()) attr.update(wind_skin_attributes(j, bin, *wind, g.node));
    const int idx = add_indices(g.index, g.position.size());
    return {{"attributes", attr}, {"indices", idx}, {"material", material}};
  }
  int add_mesh(const std::string& name, json primitives) {
    j["meshes"].push_back({{"name", name}, {"primitives", std::move(primitives)}});
    return int(j["meshes"].size()) - 1;
  }
  int add_node(json node) {
    j["nodes"].push_back(std::move(node));
    return int(j["nodes"].size()) - 1;
  }
};

// ---------------------------------------------------------------- materials and their textures
constexpr uintmax_t max_user_texture_bytes = uintmax_t(64) << 20;
constexpr int max_user_texture_side = 8192;

// A texture of the user's: its pixels (RGBA), and the file's own bytes when it is a PNG, which
// is then written unchanged.
struct user_image {
  image pixels;
  std::string png;
};

// "" with `out` filled, or why the file cannot be used (missing, too big, not an image).
std::string load_user_image(const std::string& path, user_image& out) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(path, ec)) return "file not found";
  if (!fs::is_regular_file(path, ec)) return "not a file";
  const uintmax_t on_disk = fs::file_size(path, ec);
  if (ec) return "cannot read it: " + ec.message();
  if (on_disk > max_user_texture_bytes)
    return "the file is " + std::to_string(on_disk >> 20) + " MB, over the limit of " +
           std::to_string(max_user_texture_bytes >> 20) + " MB";
  std::string bytes;
  if (std::string err = read_file(path, bytes); !err.empty()) return err;
  int w = 0, h = 0, ch = 0;
  if (!stbi_info_from_memory(reinterpret_cast<const stbi_uc*>(bytes.data()), int(bytes.size()), &w, &h, &ch))
    return "not a readable PNG (corrupt, or another format)";
  if (w > max_user_texture_side || h > max_user_texture_side)
    return std::to_string(w) + "x" + std::to_string(h) + " pixels, over the limit of " +
           std::to_string(max_user_texture_side) + " a side";
  if (std::string err = decode_png(bytes, out.pixels); !err.empty()) return err;
  static constexpr std::string_view png_signature("\x89PNG\r\n\x1a\n", 8);
  if (std::string_view(bytes).substr(0, 8) == png_signature) out.png = std::move(bytes);
  return "";
}

// PNG bytes of one material's textures; "" = the material has none of that kind.
struct material_pngs {
  std::string color, normal, roughness;
};

// The PNGs of a procedural material (bark: colour, normal, roughness; leaf: colour, normal), the
// colour tinted as the viewport tints it. PNG compression is most of an export's time, so the
// images are encoded in parallel and the result is kept for the process: the export dialog's size
// estimate and the export after it encode once. nullptr with `error` set when encoding fails.
std::shared_ptr<const material_pngs> procedural_pngs(bool bark, int archetype, int size, uint64_t seed,
                                                     const glm::vec3& tint, std::string& error) {
  using key_type = std::tuple<bool, int, int, uint64_t, float, float, float>;
  static std::mutex mutex;
  static std::map<key_type, std::shared_ptr<const material_pngs>> cache;
  const key_type key{bark, archetype, size, seed, tint.x, tint.y, tint.z};
  {
    std::lock_guard lock(mutex);
    if (auto it = cache.find(key); it != cache.end()) return it->second;
  }
  std::vector<image> images;
  if (bark) {
    const bark_texture_set& set = bark_archetype_textures(bark_archetype(std::clamp(archetype, 0, bark_archetype_count - 1)), size, seed);
    images = {tinted_texture(set.color, tint), set.normal, set.roughness};
  } else {
    const leaf_texture_set& set = leaf_archetype_textures(leaf_archetype(std::clamp(archetype, 0, leaf_slots - 1)), size, seed);
    images = {tinted_texture(set.color, tint), set.normal};
  }
  std::vector<std::string> png(images.size()), err(images.size());
  std::vector<std::thread> helpers;
  for (size_t k = 1; k < images.size(); ++k) helpers.emplace_back([&, k] { err[k] = encode_png(images[k], png[k]); });
  err[0] = encode_png(images[0], png[0]);
  for (std::thread& t : helpers) t.join();
  for (const std::string& e : err)
    if (!e.empty()) {
      error = e;
      return nullptr;
    }
  auto out = std::make_shared<const material_pngs>(material_pngs{std::move(png[0]), std::move(png[1]), bark ? std::move(png[2]) : ""});
  std::lock_guard lock(mutex);
  if (cache.size() >= 32) cache.clear();  // tints being edited: keep the memory bounded
  cache.emplace(key, out);
  return out;
}

// The materials of one export: the bark, and the leaves by slot (leaf_slot()). Loads the user's
// textures once (a file that cannot be used is a warning and the procedural texture stands in)
// and makes each material's PNGs on first use, so only the archetypes present cost anything.
class material_source {
 public:
  material_source(const export_options& o, std::string& warning)
      : o_(o), size_(std::clamp(o.texture_size, 16, 4096)), warning_(warning) {
    for (const export_lod_level& l : o.lods)
      if (l.mesh && l.mesh->cards) cards_ = l.mesh->cards;   // the levels share one set
    const std::string bark_name = bark_archetype_names[std::clamp(int(o.bark), 0, bark_archetype_count - 1)];
    user_bark_ = load("bark texture", o.bark_texture, "using the procedural " + bark_name + " bark", bark_color_);
    user_bark_normal_ = load("bark normal map", o.bark_normal_texture,
                             user_bark_ ? "the bark gets no normal map" : "using the procedural one", bark_normal_);
    user_leaf_ = load("leaf texture", o.leaf_texture, "using the procedural leaves", leaf_);
    if (!o.leaf_opacity.empty() && o.leaf_texture.empty()) {
      warn("leaf opacity map " + o.leaf_opacity + ": there is no leaf texture of your own to cut out; ignored");
    } else if (user_leaf_) {
      user_image opacity;
      if (load("leaf opacity map", o.leaf_opacity, "keeping the leaf texture's own alpha", opacity)) {
        image& leaf = leaf_.pixels;
        if (opacity.pixels.width != leaf.width || opacity.pixels.height != leaf.height) {
          warn("leaf opacity map " + o.leaf_opacity + " is " + std::to_string(opacity.pixels.width) + "x" +
               std::to_string(opacity.pixels.height) + " pixels but the leaf texture is " + std::to_string(leaf.width) +
               "x" + std::to_string(leaf.height) + "; they must be the same size, so the leaf texture keeps its own alpha");
        } else {
          // Grey opacity (its red channel, as the viewport reads it) becomes the alpha.
          for (size_t i = 0; i < size_t(leaf.width) * size_t(leaf.height); ++i) leaf.pixels[i * 4 + 3] = opacity.pixels.pixels[i * 4];
          leaf_.png.clear();  // re-encoded with the new alpha
        }
      }
    }
  }

  // The user's leaf texture replaces every archetype: all leaves share slot 0 and one material.
  bool one_leaf_material() const { return user_leaf_; }
  std::string bark_name() const {
    return user_bark_ ? "bark_custom" : std::string("bark_") + bark_archetype_names[std::clamp(int(o_.bark), 0, bark_archetype_count - 1)];
  }
  std::string leaf_name(int slot) const {
    if (user_leaf_) return "leaves_custom";
    if (slot >= leaf_archetype_count) return "leaves_lod_card" + std::to_string(slot - leaf_archetype_count);
    return std::string("leaves_") + leaf_archetype_names[std::clamp(slot, 0, leaf_archetype_count - 1)];
  }
  float alpha_cutoff() const { return std::clamp(o_.alpha_cutoff, 0.0f, 1.0f); }

  // The PNGs of a material, made on first use; nullptr after an encoding failure (see error).
  const material_pngs* bark() {
    if (bark_) return &*bark_;
    material_pngs m;
    if (user_bark_) {
      m.color = png_of(bark_color_);
    } else if (auto p = procedural_pngs(true, int(o_.bark), size_, o_.texture_seed, o_.bark_color, error)) {
      m = *p;
    }
    if (user_bark_normal_) m.normal = png_of(bark_normal_);
    if (!error.empty()) return nullptr;
    bark_ = std::move(m);
    return &*bark_;
  }
  const material_pngs* leaf(int slot) {
    auto& cached = leaves_[size_t(slot)];
    if (cached) return &*cached;
    material_pngs m;
    const size_t card = size_t(std::max(slot - leaf_archetype_count, 0));
    if (user_leaf_) {
      m.color = png_of(leaf_);
    } else if (slot >= leaf_archetype_count) {
      // A baked cluster card, tinted as the leaves it was baked from.
      if (cards_ && card < cards_->sets.size()) {
        m.color = encode(tinted_texture(cards_->sets[card].color, season_color(cards_->source[card])));
        m.normal = encode(cards_->sets[card].normal);
      } else {
        m.color = encode(image{1, 1, 4, {128, 128, 128, 255}});   // a card index no set names: plain grey
      }
    } else if (auto p = procedural_pngs(false, slot, size_, o_.texture_seed, season_color(slot), error)) {
      m = *p;
    }
    if (!error.empty()) return nullptr;
    cached = std::move(m);
    return &*cached;
  }

  std::string error;  // a PNG that could not be encoded

 private:
  // A deciduous archetype's material is tinted with the middle of the season's per-leaf range.
  glm::vec3 season_color(int slot) const {
    const season_look& s = o_.season;
    if (slot < 32 && (s.deciduous_mask >> slot) & 1u) return 0.5f * (s.deciduous_color_a + s.deciduous_color_b);
    return o_.leaf_color;
  }
  void warn(const std::string& line) { warning_ += (warning_.empty() ? "" : "\n") + line; }
  bool load(const std::string& what, const std::string& path, const std::string& fallback, user_image& out) {
    if (path.empty()) return false;
    const std::string why = load_user_image(path, out);
    if (why.empty()) return true;
    warn(what + " " + path + ": " + why + "; " + fallback);
    return false;
  }
  std::string encode(const image& img) {
    std::string png;
    if (std::string err = encode_png(img, png); !err.empty() && error.empty()) error = err;
    return png;
  }
  std::string png_of(const user_image& u) { return u.png.empty() ? encode(u.pixels) : u.png; }

  const export_options& o_;
  int size_;
  std::string& warning_;
  bool user_bark_ = false, user_bark_normal_ = false, user_leaf_ = false;
  user_image bark_color_, bark_normal_, leaf_;
  std::optional<material_pngs> bark_;
  std::array<std::optional<material_pngs>, leaf_slots> leaves_;
  std::shared_ptr<const baked_card_textures> cards_;
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
    if (embed) {
      d.j["images"].push_back({{"name", name}, {"bufferView", d.add_view(png.data(), png.size(), 0)}, {"mimeType", "image/png"}});
    } else {
      const std::string file = stem_name + "_" + name + ".png";
      d.j["images"].push_back({{"name", name}, {"uri", uri_of(file)}});
      files.emplace_back(file, png);
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
              {"alphaCutoff", src.alpha_cutoff()},
              {"doubleSided", true}};
    if (!p->normal.empty()) m["normalTexture"] = {{"index", texture(p->normal, false, name + "_normal")}};
    leaf_normal[size_t(slot)] = !p->normal.empty();
    return leaf[size_t(slot)] = add_material(std::move(m));
  }
};

// Nodes for one view of the tree: one node per tree, with a bark child and a leaves child (one
// primitive per leaf material). Returns the node ids to put under the parent; counts triangles.
// "" or the error.
std::string add_tree_nodes(gltf_doc& d, gltf_materials& mats, const step_view& v, int step, bool instanced,
                           const std::string& prefix, size_t& triangles, std::vector<int>& out, int skin = -1) {
  const bool one = mats.src.one_leaf_material();
  std::vector<tree_part> parts = split_parts(*v.skeleton, *v.mesh, step, !instanced, one);
  for (size_t k = 0; k < parts.size(); ++k) {
    const tree_part& part = parts[k];
    json tree = {{"name", prefix + (parts.size() > 1 ? "tree_" + std::to_string(k + 1) : "tree")}};
    json children = json::array();
    if (!part.bark.empty()) {
      const int mat = mats.bark_material();
      if (mat < 0) return mats.src.error;
      const int mesh = d.add_mesh("bark", json::array({d.add_primitive(part.bark, mat, mats.bark_normal)}));
      children.push_back(d.add_node({{"name", "bark"}, {"mesh", mesh}}));
      triangles += part.bark.index.size() / 3;
    }
    json prims = json::array();
    for (int slot = 0; slot < leaf_slots; ++slot) {
      const geometry& g = part.leaves[size_t(slot)];
      if (g.empty()) continue;
      const int mat = mats.leaf_material(slot);
      if (mat < 0) return mats.src.error;
      prims.push_back(d.add_primitive(g, mat, mats.leaf_normal[size_t(slot)]));
      triangles += g.index.size() / 3;
    }
    if (!prims.empty()) children.push_back(d.add_node({{"name", "leaves"}, {"mesh", d.add_mesh("leaves", std::move(prims))}}));
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
    std::array<std::vector<glm::vec3>, leaf_slots> tr, sc;
    std::array<std::vector<glm::vec4>, leaf_slots> rot;
    for (const leaf_instance& l : v.mesh->leaves) {
      if (!(l.born <= step && step < l.died)) continue;
      const size_t slot = size_t(leaf_slot(l, one));
      tr[slot].push_back(l.position);
      rot[slot].push_back(l.orientation / std::max(glm::length(l.orientation), 1e-12f));
      sc[slot].push_back(glm::vec3(std::max(l.size, 1e-6f)));
    }
    for (int slot = 0; slot < leaf_slots; ++slot) {
      const size_t s = size_t(slot);
      if (tr[s].empty()) continue;
      if (mats.quad_mesh[s] < 0) {
        const int mat = mats.leaf_material(slot);
        if (mat < 0) return mats.src.error;
        geometry quad;
        bake_leaf(quad, {glm::vec3(0), glm::vec4(0, 0, 0, 1), 1.0f, 0, 0, 0, 0});
        mats.quad_mesh[s] = d.add_mesh(mats.src.leaf_name(slot), json::array({d.add_primitive(quad, mat, mats.leaf_normal[s])}));
      }
      json attrs = {{"TRANSLATION", d.add_vectors(tr[s], "VEC3", 0)}, {"ROTATION", d.add_vectors(rot[s], "VEC4", 0)},
                    {"SCALE", d.add_vectors(sc[s], "VEC3", 0)}};
      out.push_back(d.add_node({{"name", prefix + mats.src.leaf_name(slot)}, {"mesh", mats.quad_mesh[s]},
                                {"extensions", {{"EXT_mesh_gpu_instancing", {{"attributes", attrs}}}}}}));
      d.j["extensionsUsed"] = json::array({"EXT_mesh_gpu_instancing"});
      triangles += 2 * tr[s].size();
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

// --lods (issue 17): one root node per level, LOD0 carrying MSFT_lod with the lower levels' ids and
// MSFT_screencoverage in its extras; the impostor a textured quad after them. Scene 0 shows LOD0
// (the levels hang off it through the extension), scene 1 lists every level as its own root, so a
// viewer without the extension still finds each one. "" or the error.
std::string add_lod_nodes(gltf_doc& d, gltf_materials& mats, const tree_skeleton& t, const tree_mesh& m,
                          const export_options& o, size_t& triangles, std::vector<int>& roots, std::vector<int>& all) {
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
    const std::string name = "LOD" + std::to_string(k);
    if (std::string e = add_tree_nodes(d, mats, v, last, false, name + "_", tris, kids); !e.empty()) return e;
    json node = {{"name", name}, {"extras", {{"sylva_lod", k}, {"triangles", tris}}}};
    if (k > 0 && k - 1 < o.lods.size()) node["extras"]["budget_triangles"] = o.lods[k - 1].budget;
    if (!kids.empty()) node["children"] = kids;
    ids.push_back(d.add_node(node));
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
    ids.push_back(d.add_node({{"name", "impostor"}, {"mesh", mesh}, {"extras", {{"sylva_impostor", layout}}}}));
    coverage.push_back(im.coverage);
  }
  if (ids.size() > 1) {
    json lower = json::array();
    for (size_t k = 1; k < ids.size(); ++k) lower.push_back(ids[k]);
    json& lod0 = d.j["nodes"][size_t(ids[0])];
    lod0["extensions"] = {{"MSFT_lod", {{"ids", lower}}}};
    lod0["extras"]["MSFT_screencoverage"] = coverage;
    json& used = d.j["extensionsUsed"];
    if (!used.is_array()) used = json::array();
    used.push_back("MSFT_lod");
  }
  roots.push_back(ids[0]);
  all = ids;
  return "";
}

export_result export_gltf(const tree_skeleton& t, const tree_mesh& m, const export_info& info, const std::string& path,
                          const export_options& o, bool binary) {
  export_result r;
  const std::string stem = stem_path(path), stem_name = file_name(stem);
  gltf_doc d;
  d.j["asset"] = {{"version", "2.0"}, {"generator", "Sylva"},
                  {"extras", {{"generator", info.generator}, {"seed", info.seed}}}};
  material_source src(o, r.warning);
  gltf_materials mats{d, src, binary, stem_name};
  // The final tree's buffer size, so that big exports are not copied while the buffer grows.
  d.bin.reserve(m.position.size() * 48 + m.index.size() * 4 + m.leaves.size() * 200 + (size_t(1) << 20));
  if (o.progress) o.progress(0.1f);

  const int final_step = std::max(t.steps, 0);
  std::vector<int> roots;
  std::vector<int> lod_roots;
  if (!o.lods.empty() || o.impostor) {
    if (r.error = add_lod_nodes(d, mats, t, m, o, r.triangles, roots, lod_roots); !r.error.empty()) return r;
  } else if (!o.growth_animation) {
    const int s = o.step < 0 ? final_step : std::min(o.step, final_step);
    step_view v;
    view_at(v, t, m, o.mesh, s);
    wind_bake wind;
    int skin = -1;
    json wind_channels = json::array(), wind_samplers = json::array();
    if (o.wind_seconds > 0) {   // issue 17: the wind as a skin and a seamless loop
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
  if (binary) {
    d.j["buffers"] = json::array({{{"byteLength", d.bin.size()}}});
    files.emplace_back(path, glb_container(d.j.dump(-1, ' ', false, json::error_handler_t::replace), d.bin));
  } else {
    d.j["buffers"] = json::array({{{"byteLength", d.bin.size()}, {"uri", uri_of(stem_name + ".bin")}}});
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

// ---------------------------------------------------------------- OBJ + MTL
void put_float(std::string& s, float v) {
  char buf[32];
  const auto res = std::to_chars(buf, buf + sizeof buf, std::isfinite(v) ? v : 0.0f);
  s.append(buf, res.ptr);
}

// `collect` (--lods): the files are appended there, not written, for one all-or-nothing write of
// every level; `png_stem` then names the PNGs (shared by the levels), and `m` is used as is.
export_result export_obj(const tree_skeleton& t, const tree_mesh& m, const export_info& info, const std::string& path,
                         const export_options& o, std::vector<std::pair<std::string, std::string>>* collect = nullptr,
                         const std::string& png_stem = "") {
  export_result r;
  const std::string stem = stem_path(path), stem_name = png_stem.empty() ? file_name(stem) : png_stem;
  const int s = collect ? std::max(t.steps, 0) : o.step < 0 ? std::max(t.steps, 0) : std::min(o.step, std::max(t.steps, 0));
  material_source src(o, r.warning);
  step_view v;
  if (collect) v.skeleton = &t, v.mesh = &m;
  else view_at(v, t, m, o.mesh, s);
  std::vector<tree_part> parts = split_parts(*v.skeleton, *v.mesh, s, true, src.one_leaf_material());
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
  return doc.dump(-1, ' ', false, json::error_handler_t::replace);
}

void apply_render_params(export_options& o, const render_params& rp) {
  o.bark = rp.bark;
  o.bark_color = rp.bark_color;
  o.season = season_leaf_look(rp);
  o.leaf_color = o.season.evergreen_color;
  o.alpha_cutoff = rp.alpha_cutoff;
  o.bark_texture = rp.bark_texture;
  o.leaf_texture = rp.leaf_texture;
  o.leaf_opacity = rp.leaf_opacity;
  o.wind = rp.wind;
}

export_result export_tree(const tree_skeleton& t, const tree_mesh& m, const export_info& info, const std::string& path,
                          const export_options& o) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  export_result r;
  if ((ext == ".glb" || ext == ".gltf" || ext == ".obj") && season_changes_leaves(o.season)) {
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
  if (ext == ".glb" || ext == ".gltf") return export_gltf(t, m, info, path, o, ext == ".glb");
  if (ext == ".obj" && !o.lods.empty()) {
    // One OBJ (and MTL) per level, PNGs shared: tree.obj is LOD0, tree_lod1.obj ... All or nothing.
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
