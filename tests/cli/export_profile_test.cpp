// `sylva export --profile` (render/io/export.h export_profile): plain bakes flat cards, hero
// instances the blades in glTF, hero-baked bakes them, and an unknown profile is a usage error.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include <tiny_gltf.h>

#include "render/mesh/leaf_blade.h"
#include "render/mesh/leaf_shoot.h"
#include "tests/run_sylva.h"
#include "tests/scratch_dir.h"

using namespace sylva;
using sylva_test::scratch_dir;

namespace {

struct leaf_counts {
  size_t vertices = 0, instanced_meshes = 0;
};

leaf_counts leaves_of(const std::string& file) {
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string err, warn;
  leaf_counts c;
  if (!loader.LoadBinaryFromFile(&model, &err, &warn, file)) return c;
  for (const auto& node : model.nodes)
    if (node.extensions.count("EXT_mesh_gpu_instancing")) ++c.instanced_meshes;
  for (const auto& mesh : model.meshes)
    for (const auto& prim : mesh.primitives) {
      const std::string& material = model.materials[size_t(prim.material)].name;
      if (material.rfind("leaves_", 0) == 0) c.vertices += model.accessors[size_t(prim.attributes.at("POSITION"))].count;
    }
  return c;
}

// An accessor's floats, tightly packed or strided.
std::vector<float> floats_of(const tinygltf::Model& m, int accessor, int per) {
  const tinygltf::Accessor& a = m.accessors[size_t(accessor)];
  const tinygltf::BufferView& v = m.bufferViews[size_t(a.bufferView)];
  const size_t stride = v.byteStride ? v.byteStride : sizeof(float) * size_t(per);
  const unsigned char* base = m.buffers[size_t(v.buffer)].data.data() + v.byteOffset + a.byteOffset;
  std::vector<float> out;
  for (size_t k = 0; k < a.count; ++k)
    for (int c = 0; c < per; ++c) out.push_back(reinterpret_cast<const float*>(base + k * stride)[c]);
  return out;
}

}  // namespace

// The instances of a hero file, expanded, put each blade where the hero-baked file bakes it: every
// instance's transform (TRANSLATION, ROTATION, SCALE) applied to its prototype's midrib vertex at
// the petiole lands on a vertex of the baked blades (the coarse and fine grids share that vertex).
TEST(ExportProfile, ExpandedInstancesMatchTheBakedBlades) {
  scratch_dir dir("sylva_export_expand");
  const std::string preset = std::string(SYLVA_SOURCE_DIR) + "/presets/lsystem_honda_a.json";
  for (const char* profile : {"hero", "hero-baked"})
    ASSERT_EQ(run_sylva("", "export '" + preset + "' -o '" + (dir / (std::string(profile) + ".glb")) + "' --profile " + profile).code, 0);
  tinygltf::TinyGLTF loader;
  tinygltf::Model hero, baked;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&hero, &err, &warn, dir / "hero.glb")) << err;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&baked, &err, &warn, dir / "hero-baked.glb")) << err;
  std::vector<glm::vec3> baked_points;
  for (const auto& mesh : baked.meshes)
    for (const auto& prim : mesh.primitives)
      if (baked.materials[size_t(prim.material)].name.rfind("leaves_", 0) == 0) {
        const std::vector<float> p = floats_of(baked, prim.attributes.at("POSITION"), 3);
        for (size_t k = 0; k + 2 < p.size(); k += 3) baked_points.emplace_back(p[k], p[k + 1], p[k + 2]);
      }
  ASSERT_FALSE(baked_points.empty());
  // The petiole's midrib vertex of the fine grid: row 0, the middle column (render/mesh/leaf_blade.h).
  const size_t midrib = size_t(blade_columns / 2);
  size_t instances = 0, matched = 0;
  for (const auto& node : hero.nodes) {
    if (!node.extensions.count("EXT_mesh_gpu_instancing")) continue;
    const auto& prim = hero.meshes[size_t(node.mesh)].primitives[0];
    const std::vector<float> proto = floats_of(hero, prim.attributes.at("POSITION"), 3);
    ASSERT_EQ(proto.size(), size_t(3 * 2 * blade_vertices));   // two faces of the fine grid
    const glm::vec3 base(proto[3 * midrib], proto[3 * midrib + 1], proto[3 * midrib + 2]);
    const auto& attrs = node.extensions.at("EXT_mesh_gpu_instancing").Get("attributes");
    const std::vector<float> t = floats_of(hero, attrs.Get("TRANSLATION").GetNumberAsInt(), 3);
    const std::vector<float> r = floats_of(hero, attrs.Get("ROTATION").GetNumberAsInt(), 4);
    const std::vector<float> s = floats_of(hero, attrs.Get("SCALE").GetNumberAsInt(), 3);
    for (size_t i = 0; i < t.size() / 3; ++i, ++instances) {
      const glm::quat q(r[4 * i + 3], r[4 * i], r[4 * i + 1], r[4 * i + 2]);
      const glm::vec3 at = glm::vec3(t[3 * i], t[3 * i + 1], t[3 * i + 2]) + q * (base * glm::vec3(s[3 * i], s[3 * i + 1], s[3 * i + 2]));
      float best = 1e30f;
      for (const glm::vec3& b : baked_points) best = std::min(best, glm::length(b - at));
      matched += best < 1e-4f;
    }
  }
  ASSERT_GT(instances, size_t(50));
  EXPECT_EQ(matched, instances);
  // Every leaf baked has two faces of the coarse grid, so the baked file holds as many leaves.
  EXPECT_EQ(baked_points.size(), instances * size_t(2 * coarse_blade_vertices));
}

TEST(ExportProfile, PlainHeroAndHeroBakedCarryTheLeavesAsTheySay) {
  scratch_dir dir("sylva_export_profile");
  const std::string preset = std::string(SYLVA_SOURCE_DIR) + "/presets/lsystem_honda_a.json";
  auto run = [&](const std::string& profile) {
    const std::string out = dir / (profile + ".glb");
    const sylva_run r = run_sylva("", "export '" + preset + "' -o '" + out + "' --profile " + profile);
    EXPECT_EQ(r.code, 0) << r.err;
    return leaves_of(out);
  };
  const leaf_counts plain = run("plain"), hero = run("hero"), baked = run("hero-baked");
  ASSERT_GT(plain.vertices, size_t(0));
  EXPECT_EQ(plain.instanced_meshes, size_t(0));
  EXPECT_EQ(baked.instanced_meshes, size_t(0));
  // Two faces a leaf: 4 corners each as a card, 12 vertices each as a baked blade.
  EXPECT_EQ(baked.vertices * 4, plain.vertices * size_t(coarse_blade_vertices));
  // Hero: one prototype per leaf material, each the fine grid's two faces, and the leaves as instances.
  EXPECT_GT(hero.instanced_meshes, size_t(0));
  EXPECT_EQ(hero.vertices, hero.instanced_meshes * size_t(2 * blade_vertices));
  const sylva_run bad = run_sylva("", "export '" + preset + "' -o '" + (dir / "x.glb") + "' --profile fancy");
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("--profile"), std::string::npos) << bad.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "x.glb"));
}

// A needle archetype (render/mesh/leaf_shoot.h): hero instances the fine shoot once per material,
// hero-baked bakes each leaf as the coarse shoot's closed spikes, one face only, and the plain
// profile keeps the flat card.
TEST(ExportProfile, NeedleShootsAreInstancedFineAndBakedCoarse) {
  scratch_dir dir("sylva_export_shoots");
  const std::string preset = std::string(SYLVA_SOURCE_DIR) + "/presets/lsystem_honda_a.json";
  auto run = [&](const std::string& profile) {
    const std::string out = dir / (profile + ".glb");
    const sylva_run r = run_sylva("", "export '" + preset + "' -o '" + out + "' --profile " + profile + " --set leaf_archetype=needles");
    EXPECT_EQ(r.code, 0) << r.err;
    return leaves_of(out);
  };
  const leaf_counts plain = run("plain"), hero = run("hero"), baked = run("hero-baked");
  ASSERT_GT(plain.vertices, size_t(0));
  const size_t leaves = plain.vertices / 8;   // two faces of four corners
  EXPECT_EQ(hero.instanced_meshes, size_t(1));
  EXPECT_EQ(hero.vertices, size_t(shoot_pieces_fine * shoot_piece_vertices));
  EXPECT_EQ(baked.vertices, leaves * size_t(shoot_vertices_coarse));
}
