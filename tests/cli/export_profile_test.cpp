// `sylva export --profile` (render/io/export.h export_profile): plain bakes flat cards, hero
// instances the blades in glTF, hero-baked bakes them, and an unknown profile is a usage error.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include <tiny_gltf.h>

#include "render/mesh/leaf_blade.h"
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

}  // namespace

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
