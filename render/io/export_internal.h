// Internals shared by the exporters (render/io/export*.cpp): the per-tree parts with leaves baked
// into cards, the step view, the all-or-nothing write, and the materials' textures. Not for use
// outside render/io/export*.cpp; the public interface is render/io/export.h.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <nlohmann/json.hpp>

#include "render/io/export.h"
#include "render/mesh/bark_tint.h"
#include "render/mesh/leaf_blade.h"
#include "render/mesh/leaf_shoot.h"
#include "render/mesh/leaf_shading.h"
#include "render/mesh/lod_cards.h"
#include "render/assets/textures.h"

namespace sylva::export_internal {

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
// (render/mesh/lod_cards.h) take the slots after the archetypes'.
constexpr int leaf_slots = leaf_archetype_count + max_baked_cards;

struct tree_part {
  geometry bark;
  std::array<geometry, leaf_slots> leaves;
};

// The mesh to export for step `s` and the skeleton its node ids refer to: the caller's own when
// the final tree is asked for and nothing was shed, else a re-meshed copy of the step.
struct step_view {
  tree_skeleton own_skeleton;
  tree_mesh own_mesh;
  const tree_skeleton* skeleton = nullptr;
  const tree_mesh* mesh = nullptr;
};

// A texture of the user's: its pixels (RGBA), and the file's own bytes when it is a PNG, which
// is then written unchanged.
struct user_image {
  image pixels;
  std::string png;
};

// PNG bytes of one material's textures; "" = the material has none of that kind.
struct material_pngs {
  std::string color, normal, roughness;
};

int leaf_slot(const leaf_instance& l, bool one_leaf_material);

// A leaf's blade mesh in card units (render/mesh/leaf_blade.h): the exporters' subset of its
// archetype's grid, or the full grid for an instanced prototype. Triangles counter-clockwise from +Z.
// A needle shoot (render/mesh/leaf_shoot.h) is closed (`closed`): baked as one face.
using blade_mesh = leaf_mesh;
struct leaf_look;
blade_mesh export_blade_mesh(leaf_archetype a, const leaf_blade_shape& s, bool full_grid, const leaf_look& look);
// Per leaf slot, the blade to bake (empty: the flat card): the archetypes' own when the mesh's
// blades are on and no user picture replaces them; fruit and baked cards stay cards.
std::array<blade_mesh, leaf_archetype_count + max_baked_cards> slot_blades(const leaf_blade_shape& s, bool one_leaf_material,
                                                                          bool full_grid, const leaf_look& look);

// A leaf instance as a card of one blade length square, base at the petiole (leaf frame of
// skeleton.h: blade in local XY, normal +Z, petiole along -Y) with the whole texture on it: the
// petiole at the bottom edge of the image (v = 1, glTF's origin is the top-left corner); or, with
// a blade, that blade's mesh with the same picture coordinates. A face per side with two_sided
// (render/mesh/leaf_shading.h), the side looking out of the crown first; with a crown, each side's
// normal is bent toward its outward direction by normal_blend.
struct leaf_bake {
  const crown_ellipsoid* crown = nullptr;
  float normal_blend = 0;
  bool two_sided = true;
  const blade_mesh* blade = nullptr;   // null or empty: the flat card
  glm::vec3 color{1.0f};               // times the occlusion in COLOR_0 (leaf_color_factor)
};
void bake_leaf(geometry& g, const leaf_instance& l, const leaf_bake& b);

bool has_shed(const tree_skeleton& t, int s);

// Stems whose bases stand within stool_reach (metres, horizontally and vertically) of another's are
// one plant: a coppice stool or a many-stemmed shrub grown as several trees in one environment is
// one glTF node and one bark mesh, where a forest's trees, metres apart, stay one node each.
inline constexpr float stool_reach = 1.0f;
// The plant (0, 1, ... in the order of their first root) of every node.
std::vector<int32_t> plant_of_nodes(const tree_skeleton& t);

// Splits a mesh into one part per plant (a forest's trees one each; a stool one); leaves alive
// at `step` are baked into quads (one geometry per leaf slot) unless `bake` is false, in which
// case they are left to the caller. Baked leaves are two-sided, bent toward their tree's crown by
// normal_blend (render/mesh/leaf_shading.h).
// The bark's COLOR_0 is its crown occlusion times tint.ratio(y) (render/mesh/bark_tint.h).
// How baked leaves look: normals bent toward the crown by normal_blend; COLOR_0 the crown
// occlusion times leaf_color_factor(variation, sun_tone) (render/mesh/leaf_shading.h); blade
// meshes or flat cards.
struct leaf_look {
  float normal_blend = 0, variation = 0, sun_tone = 0;
  bool blades = false;   // bake the mesh's blades (when on) instead of flat cards
  int texture_size = 512;     // the leaf materials' pictures, whose texels the needle shoots sample
  uint64_t texture_seed = 1;
};
std::vector<tree_part> split_parts(const tree_skeleton& t, const tree_mesh& m, int step, bool bake, bool one_leaf_material,
                                   const leaf_look& look, const bark_tint& tint = {});
// Leaf `index` of its mesh (in leaf slot `slot`): its colour factor (leaf_color_factor), or 1 for
// fruit and a LOD's baked cards, which keep their own colours.
glm::vec3 leaf_color_of(const leaf_instance& l, size_t index, int slot, bool one_leaf_material, const leaf_look& look);

void view_at(step_view& v, const tree_skeleton& t, const tree_mesh& m, const mesh_params& p, int step);

bool cancelled(const export_options& o);

// Engine naming of LOD levels (Unity builds an LODGroup from objects named "<name>_LOD0",
// "<name>_LOD1", ...): the tree's name is the file's stem, with characters other than letters,
// digits, '-' and '_' replaced by '_' ("tree" when nothing is left).
std::string lod_tree_name(const std::string& stem);
struct lod_name {
  std::string tree;
  int level = 0;
  std::string name() const { return tree + "_LOD" + std::to_string(level); }
  std::string of_tree(size_t k) const { return tree + "_tree_" + std::to_string(k) + "_LOD" + std::to_string(level); }
};

std::string file_name(const std::string& path);

std::string stem_path(const std::string& path);

// Writes every (path, bytes) pair all or nothing: each is staged first (preset.h: written and synced
// under a temporary name beside its target, through symlinks, keeping permissions). A failure while
// staging removes only the temporaries. Then each existing target is moved aside and the new file
// renamed in, the main file (which names the others) last; if a rename fails midway, the files
// moved aside are put back, so the previous export stays whole in either case.
std::string write_all(const std::vector<std::pair<std::string, std::string>>& files, export_result& r);

// "" with `out` filled, or why the file cannot be used (missing, too big, not an image).
std::string load_user_image(const std::string& path, user_image& out);

// The PNGs of a procedural material (bark: colour, normal, roughness; leaf: colour, normal), the
// colour tinted as the viewport tints it. PNG compression is most of an export's time, so the
// images are encoded in parallel and the result is kept for the process: the export dialog's size
// estimate and the export after it encode once. nullptr with `error` set when encoding fails.
std::shared_ptr<const material_pngs> procedural_pngs(bool bark, int archetype, int size, uint64_t seed,
                                                     const glm::vec3& tint, std::string& error);

// render/io/export_compact.cpp (meshoptimizer): vertex-cache and fetch order of one primitive (the
// same triangles); a glTF's buffer views under EXT_meshopt_compression (returns the new binary
// buffer, `j` gets the views' extensions and the two buffers); an opaque image as JPEG.
void optimize_geometry(geometry& g);
void use_extension(json& j, const char* name, bool required);   // listed once in extensionsUsed (/Required)
std::string meshopt_compress(json& j, const std::string& bin);
bool jpeg_if_opaque(const std::string& png, std::string& jpeg);

export_result export_gltf(const tree_skeleton& t, const tree_mesh& m, const export_info& info, const std::string& path,
                          const export_options& o, bool binary);

// FBX through assimp (render/io/export_fbx.cpp): PNGs beside the file, --lods as "<tree>_LOD<k>"
// nodes, the wind skin and its loop with wind_seconds > 0.
export_result export_fbx(const tree_skeleton& t, const tree_mesh& m, const export_info& info, const std::string& path,
                         const export_options& o);

// `collect` (--lods): the files are appended there, not written, for one all-or-nothing write of
// every level; `png_stem` then names the PNGs (shared by the levels), and `m` is used as is.
export_result export_obj(const tree_skeleton& t, const tree_mesh& m, const export_info& info, const std::string& path,
                         const export_options& o, std::vector<std::pair<std::string, std::string>>* collect = nullptr,
                         const std::string& png_stem = "");

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
  // Bark colour by height (render/mesh/bark_tint.h): glTF carries the blend in the bark's COLOR_0
  // (split_parts) and tints the texture with its brighter end; OBJ (no vertex colours) and FBX (whose
  // importers do not multiply them in) call without_vertex_colors() first and keep the bark colour.
  bark_tint bark_colors() const {
    return {o_.bark_color, o_.bark_base_color, vertex_colors_ ? o_.bark_base_height : 0.0f};   // NaN: blends() is false
  }
  void without_vertex_colors() { vertex_colors_ = false; }
  leaf_look leaf_looks() const {
    return {o_.leaf_normal_blend, o_.leaf_color_variation, o_.leaf_sun_tone, o_.baked_blades, size_, o_.texture_seed};
  }

  // The PNGs of a material, made on first use; nullptr after an encoding failure (see error).
  const material_pngs* bark() {
    if (bark_) return &*bark_;
    material_pngs m;
    if (user_bark_) {
      m.color = png_of(bark_color_);
    } else if (auto p = procedural_pngs(true, int(o_.bark), size_, o_.texture_seed, bark_colors().peak(), error)) {
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
  // A deciduous archetype's material is tinted with the middle of the season's per-leaf range; a
  // fruit's card keeps its own colours (render/mesh/season.h archetype_is_fruit).
  glm::vec3 season_color(int slot) const {
    const season_look& s = o_.season;
    if (slot < leaf_archetype_count && archetype_is_fruit(leaf_archetype(slot))) return glm::vec3(1.0f);
    if (season_deciduous(s, slot)) return 0.5f * (s.deciduous_color_a + s.deciduous_color_b);
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
  bool vertex_colors_ = true;
  std::optional<material_pngs> bark_;
  std::array<std::optional<material_pngs>, leaf_slots> leaves_;
  std::shared_ptr<const baked_card_textures> cards_;
};

}  // namespace sylva::export_internal
