// Cluster cards baked from the tree's own leaves (render/mesh/lod_cards.h): the raster keeps a
// leaf's cut-out, the LOD levels share one set of baked textures, and the exports carry them.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "tests/scratch_dir.h"
#include "generators/tree_spec.h"
#include "render/io/export.h"
#include "render/io/export_internal.h"
#include "render/mesh/lod.h"
#include "render/mesh/lod_cards.h"
#include "render/io/preset.h"

using namespace sylva;
namespace fs = std::filesystem;

using sylva_test::slurp;

namespace {

leaf_instance flat_leaf(glm::vec3 at, float size, glm::vec4 q = {0, 0, 0, 1}) {
  leaf_instance l{};
  l.position = at;
  l.orientation = q;
  l.size = size;
  l.born = 0;
  l.died = 0xffff;
  l.texture = uint8_t(leaf_archetype::lobed);
  return l;
}

}  // namespace

TEST(LodCards, OneLeafFacingTheCardBakesToItsOwnCutOut) {
  const leaf_instance l = flat_leaf({1, 2, 3}, 0.5f);
  const card_fit f = fit_card(&l, 1, l.orientation);
  EXPECT_NEAR(f.size, 0.5f, 1e-5f);                        // the leaf's square
  EXPECT_NEAR(glm::length(f.position - l.position), 0.0f, 1e-5f);
  const leaf_texture_set s = bake_card(&l, 1, f, 128);
  ASSERT_EQ(s.color.width, 128);
  ASSERT_EQ(s.color.channels, 4);
  // The card is the leaf: its opaque share is the archetype's (texels sampled at 128 of 512).
  const float own = opaque_share(leaf_archetype_textures(leaf_archetype::lobed, 512).color);
  EXPECT_NEAR(opaque_share(s.color), own, 0.02f);
  // Normals of a leaf facing the card point out of its front (+Z in the card's frame), tilted only
  // by the leaf's own normal map (veins).
  size_t front = 0, straight = 0, opaque = 0;
  for (size_t i = 0; i < size_t(128 * 128); ++i) {
    if (s.color.pixels[i * 4 + 3] < 128) continue;
    ++opaque;
    front += s.normal.pixels[i * 3 + 2] > 128;
    straight += s.normal.pixels[i * 3 + 2] > 200;
  }
  EXPECT_EQ(front, opaque);
  EXPECT_GT(straight, opaque * 9 / 10);
}

TEST(LodCards, EdgeOnLeavesLeaveTheCardEmptyAndTwoLeavesFillTheirExtent) {
  // Turned 90 degrees about +Y: seen edge-on along the card's normal.
  const float h = 0.70710678f;
  const leaf_instance edge = flat_leaf({0, 0, 0}, 1.0f, {0, h, 0, h});
  const card_fit f = fit_card(&edge, 1, glm::vec4(0, 0, 0, 1));
  const leaf_texture_set s = bake_card(&edge, 1, f, 64);
  EXPECT_EQ(opaque_share(s.color), 0.01f);   // the floor: nothing opaque
  // Two leaves side by side: the card spans both (2 m across), each fills its half.
  const leaf_instance two[2] = {flat_leaf({-0.5f, 0, 0}, 1.0f), flat_leaf({0.5f, 0, 0}, 1.0f)};
  const card_fit g = fit_card(two, 2, glm::vec4(0, 0, 0, 1));
  EXPECT_NEAR(g.size, 2.0f, 1e-5f);
  EXPECT_GT(g.coverage, 0.0f);
  EXPECT_LT(g.coverage, 1.0f);
  const leaf_texture_set t = bake_card(two, 2, g, 128);
  size_t left = 0, right = 0;
  for (int y = 0; y < 128; ++y)
    for (int x = 0; x < 128; ++x)
      if (t.color.pixels[(size_t(y) * 128 + size_t(x)) * 4 + 3] >= 128) (x < 64 ? left : right) += 1;
  EXPECT_GT(left, size_t(500));
  EXPECT_NEAR(double(left) / double(right), 1.0, 0.05);
}

TEST(LodCards, LevelsShareOneSetAndEveryCardNamesABakedTexture) {
  preset p;
  ASSERT_TRUE(load_preset_file(std::string(SYLVA_SOURCE_DIR) + "/presets/species_cedar.json", p).ok);
  const tree_skeleton t = grow(p.spec, grow_options{});
  const tree_mesh m = mesh_tree(t, p.mesh, p.spec.seed);
  const lod_chain c = build_lods(t, m, p.mesh, p.render.lod);
  ASSERT_TRUE(c.reduced);
  EXPECT_EQ(m.cards, nullptr);
  const auto& cards = c.level[0].cards;
  ASSERT_NE(cards, nullptr);
  EXPECT_EQ(c.level[1].cards, cards);
  EXPECT_EQ(c.level[2].cards, cards);
  ASSERT_GT(cards->sets.size(), size_t(0));
  EXPECT_LE(cards->sets.size(), size_t(max_baked_cards));
  EXPECT_EQ(cards->source.size(), cards->sets.size());
  EXPECT_EQ(cards->opaque.size(), cards->sets.size());
  for (const leaf_texture_set& s : cards->sets) EXPECT_EQ(s.color.width, card_texture_size);
  for (int k = 0; k < 3; ++k) {
    size_t baked = 0;
    for (const leaf_instance& l : c.level[size_t(k)].leaves) {
      EXPECT_LT(int(l.texture), leaf_archetype_count + int(cards->sets.size()));
      baked += l.texture >= leaf_archetype_count;
      EXPECT_TRUE(std::isfinite(l.size) && l.size > 0);
    }
    if (k == 2) {
      EXPECT_GT(baked, size_t(0)) << "LOD3 merges leaves";
    }
  }
}

TEST(LodCards, ExportsCarryTheBakedTextures) {
  preset p;
  ASSERT_TRUE(load_preset_file(std::string(SYLVA_SOURCE_DIR) + "/presets/species_palm.json", p).ok);
  const tree_skeleton t = grow(p.spec, grow_options{});
  const tree_mesh m = mesh_tree(t, p.mesh, p.spec.seed);
  const lod_chain c = build_lods(t, m, p.mesh, p.render.lod);
  ASSERT_NE(c.level[2].cards, nullptr);
  export_options o;
  apply_render_params(o, p.render);
  o.mesh = p.mesh;
  o.texture_size = 32;
  o.lod0_coverage = c.coverage[0];
  for (int k = 1; k < lod_levels; ++k) o.lods.push_back({&c.level[size_t(k) - 1], c.coverage[size_t(k)], c.target[size_t(k)]});
  const sylva_test::scratch_dir scratch("sylva-lod-cards");
  const fs::path& dir = scratch.dir;
  ASSERT_EQ(export_tree(t, m, {"palm", 1}, (dir / "tree.gltf").string(), o).error, "");
  const nlohmann::json j = nlohmann::json::parse(slurp((dir / "tree.gltf").string()));
  size_t card_materials = 0;
  for (const auto& mat : j["materials"])
    if (mat["name"].get<std::string>().rfind("leaves_lod_card", 0) == 0) {
      ++card_materials;
      const int tex = mat["pbrMetallicRoughness"]["baseColorTexture"]["index"];
      const int img = j["textures"][size_t(tex)]["source"];
      EXPECT_TRUE(fs::exists(dir / j["images"][size_t(img)]["uri"].get<std::string>()));
      EXPECT_EQ(mat["alphaMode"], "MASK");
    }
  EXPECT_GT(card_materials, size_t(0));
  // OBJ: each level's MTL names the baked card PNGs its faces use, written beside it.
  ASSERT_EQ(export_tree(t, m, {"palm", 1}, (dir / "tree.obj").string(), o).error, "");
  const std::string mtl = slurp((dir / "tree_lod3.mtl").string());
  const size_t at = mtl.find("map_Kd tree_leaves_lod_card");
  ASSERT_NE(at, std::string::npos) << mtl;
  const std::string file = mtl.substr(at + 7, mtl.find('\n', at) - at - 7);
  EXPECT_TRUE(fs::exists(dir / file)) << file;
  EXPECT_NE(slurp((dir / "tree_lod3.obj").string()).find("usemtl leaves_lod_card"), std::string::npos);
}

TEST(LodCards, BadLeavesBakeNothingAndNeverCrash) {
  leaf_instance bad[3] = {flat_leaf({0, 0, 0}, 1.0f), flat_leaf({0, 0, 0}, 1.0f), flat_leaf({1e30f, 0, 0}, 1e30f)};
  bad[1].orientation = glm::vec4(std::nanf(""), 0, 0, 1);
  const card_fit f = fit_card(bad, 3, glm::vec4(0, 0, 0, 1));
  EXPECT_TRUE(std::isfinite(f.size));
  const leaf_texture_set s = bake_card(bad + 1, 2, fit_card(bad, 1, glm::vec4(0, 0, 0, 1)), 32);
  EXPECT_EQ(s.color.pixels.size(), size_t(32 * 32 * 4));
}

// Cones and fruit (generators/fruits.h) stay on LOD0: a merged card would tint them as leaves,
// and they are too small to show at a LOD's distance. Their exported material keeps their own
// colours: the fir's cone texture is the untinted archetype's, not the leaf colour's green.
TEST(LodCards, ConesStayOnLod0AndExportUntinted) {
  preset p;
  ASSERT_TRUE(load_preset_file(std::string(SYLVA_SOURCE_DIR) + "/presets/species_fir.json", p).ok);
  ASSERT_GT(p.mesh.fruits.count, 0);
  const tree_skeleton t = grow(p.spec, grow_options{});
  const tree_mesh m = mesh_tree(t, p.mesh, p.spec.seed);
  const uint8_t cone = uint8_t(leaf_archetype::cone_upright);
  EXPECT_GT(std::count_if(m.leaves.begin(), m.leaves.end(), [&](const leaf_instance& l) { return l.texture == cone; }), 50);
  const lod_chain c = build_lods(t, m, p.mesh, p.render.lod);
  ASSERT_TRUE(c.reduced);
  for (int k = 0; k < 3; ++k)
    for (const leaf_instance& l : c.level[size_t(k)].leaves) ASSERT_NE(l.texture, cone) << "LOD" << k + 1;
  for (uint8_t s : c.level[0].cards->source) EXPECT_NE(s, cone);

  export_options o;
  apply_render_params(o, p.render);
  o.mesh = p.mesh;
  o.texture_size = 64;
  const sylva_test::scratch_dir scratch("sylva-fruit");
  const fs::path& dir = scratch.dir;
  ASSERT_EQ(export_tree(t, m, {"fir", 1}, (dir / "tree.gltf").string(), o).error, "");
  const nlohmann::json j = nlohmann::json::parse(slurp((dir / "tree.gltf").string()));
  bool found = false;
  for (const auto& mat : j["materials"]) {
    if (mat["name"] != "leaves_cone_upright") continue;
    found = true;
    const int tex = mat["pbrMetallicRoughness"]["baseColorTexture"]["index"];
    const int img = j["textures"][size_t(tex)]["source"];
    export_internal::user_image u;
    ASSERT_EQ(export_internal::load_user_image((dir / j["images"][size_t(img)]["uri"].get<std::string>()).string(), u), "");
    const image& own = leaf_archetype_textures(leaf_archetype::cone_upright, 64).color;
    ASSERT_EQ(u.pixels.pixels.size(), own.pixels.size());
    double diff = 0, opaque = 0;
    for (size_t k = 0; k < own.pixels.size(); k += 4) {
      if (own.pixels[k + 3] < 255) continue;
      ++opaque;
      for (int ch = 0; ch < 3; ++ch) diff += std::abs(int(u.pixels.pixels[k + size_t(ch)]) - int(own.pixels[k + size_t(ch)]));
    }
    ASSERT_GT(opaque, 0);
    EXPECT_LT(diff / (3 * opaque), 1.5) << "the cone's own colours, untinted";
  }
  EXPECT_TRUE(found);
}
