// Plants in exports: stems whose bases stand within a metre of each other (a coppice stool, a
// shrub grown as several stems in one environment) are one plant, one glTF node with one bark and
// one leaf mesh; trees metres apart (a forest) stay one node each.
#include <gtest/gtest.h>

#include <algorithm>

#include <tiny_gltf.h>

#include "render/io/export.h"
#include "render/io/export_internal.h"
#include "render/io/preset.h"
#include "tests/scratch_dir.h"

using namespace sylva;

namespace {

// A straight stem of `nodes` internodes standing at (x, 0, z).
void add_stem(tree_skeleton& t, float x, float z, int nodes) {
  int32_t prev = t.add_node({x, 0, z}, -1, 0.05f, 0, 0);
  for (int k = 1; k <= nodes; ++k) prev = t.add_node({x, float(k) * 0.2f, z}, prev, 0.02f, 1, 0);
}

std::vector<std::string> scene_node_names(const std::string& glb) {
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string err, warn;
  EXPECT_TRUE(loader.LoadBinaryFromFile(&model, &err, &warn, glb)) << err;
  std::vector<std::string> names;
  if (model.scenes.empty()) return names;
  for (int n : model.scenes[0].nodes) names.push_back(model.nodes[size_t(n)].name);
  return names;
}

}  // namespace

TEST(ExportPlants, StemsOnOneStoolAreOnePlantAndForestTreesAreNot) {
  tree_skeleton t;
  add_stem(t, 0.0f, 0.0f, 5);
  add_stem(t, 6.0f, 0.0f, 5);    // a tree of its own, 6 m away
  add_stem(t, 0.7f, 0.0f, 5);    // 0.7 m from the first: the same stool
  add_stem(t, 1.5f, 0.3f, 5);    // 0.85 m from the third (1.53 m from the first): still the stool
  t.steps = 1;
  t.tree_count = 4;
  const std::vector<int32_t> plant = export_internal::plant_of_nodes(t);
  ASSERT_EQ(plant.size(), t.size());
  EXPECT_EQ(plant[0], 0);
  EXPECT_EQ(plant[6], 1);
  EXPECT_EQ(plant[12], 0);
  EXPECT_EQ(plant[18], 0);
  EXPECT_EQ(plant.back(), 0);   // every node follows its stem's root

  sylva_test::scratch_dir dir("sylva_export_plants");
  mesh_params p;
  p.leaves_enabled = false;
  export_options o;
  o.mesh = p;
  o.texture_size = 16;
  const tree_mesh m = mesh_tree(t, p);
  ASSERT_EQ(export_tree(t, m, {"test", 1}, dir / "two.glb", o).error, "");
  EXPECT_EQ(scene_node_names(dir / "two.glb"), (std::vector<std::string>{"tree_1", "tree_2"}));
}

// The hazel is eight stems on one stool: one plant, so an artist imports one object with one bark
// and one leaf mesh (two draw calls), not sixteen.
TEST(ExportPlants, TheHazelExportsAsOnePlant) {
  preset hazel;
  ASSERT_TRUE(load_preset_file(SYLVA_SOURCE_DIR "/presets/species_bush.json", hazel).ok);
  const tree_skeleton t = grow(hazel.spec, grow_options{});
  ASSERT_GE(t.tree_count, 2);
  const std::vector<int32_t> plant = export_internal::plant_of_nodes(t);
  EXPECT_EQ(*std::max_element(plant.begin(), plant.end()), 0);
  sylva_test::scratch_dir dir("sylva_export_hazel");
  export_options o;
  apply_render_params(o, hazel.render);
  o.mesh = hazel.mesh;
  o.texture_size = 16;
  const tree_mesh m = mesh_tree(t, hazel.mesh, hazel.spec.seed);
  ASSERT_EQ(export_tree(t, m, {generator_name(hazel.spec), hazel.spec.seed}, dir / "hazel.glb", o).error, "");
  EXPECT_EQ(scene_node_names(dir / "hazel.glb"), (std::vector<std::string>{"tree"}));
}
