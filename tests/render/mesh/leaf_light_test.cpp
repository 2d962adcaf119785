// Sun and shade leaves (issue 52): sizes from the crown occlusion (leaf_shade_size) and the colour
// factor shared by the viewport and the exports (leaf_color_factor, render/mesh/leaf_shading.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include <glm/geometric.hpp>

#include "generators/lsystem.h"
#include "render/mesh/leaf_shading.h"
#include "render/mesh/mesh.h"

using namespace sylva;

// Each leaf is 1 + s (0.5 - sky) times its size without the rule, sky running 0..1 over the
// occlusion's 0.35..1; fruit keep theirs; the placement and the occlusion are the same.
TEST(LeafLight, ShadeLeavesGrowLargerAndSunLeavesSmaller) {
  lsystem_params lp;
  lp.derivations = 7;
  const tree_skeleton t = grow_honda(lp, {});
  mesh_params p;
  p.leaves.min_order = 1;
  p.leaves.spacing = 0.05f;
  p.fruits.count = 4;
  p.leaves.shade_size = 0;
  const tree_mesh plain = mesh_tree(t, p);
  p.leaves.shade_size = 0.8f;
  const tree_mesh shaded = mesh_tree(t, p);
  ASSERT_EQ(plain.leaves.size(), shaded.leaves.size());
  ASSERT_GT(plain.leaves.size(), size_t(100));
  size_t larger = 0, smaller = 0, fruit = 0;
  for (size_t k = 0; k < plain.leaves.size(); ++k) {
    const leaf_instance &a = plain.leaves[k], &b = shaded.leaves[k];
    ASSERT_EQ(a.occlusion, b.occlusion);
    ASSERT_EQ(glm::length(a.position - b.position), 0.0f);
    if (leaf_archetype_fruit[a.texture]) {
      EXPECT_EQ(a.size, b.size);
      ++fruit;
      continue;
    }
    const float open = std::clamp((float(a.occlusion) / 255.0f - 0.35f) / 0.65f, 0.0f, 1.0f);
    EXPECT_NEAR(b.size / a.size, 1.0f + 0.8f * (0.5f - open), 1e-5f);
    larger += b.size > a.size * 1.01f, smaller += b.size < a.size * 0.99f;
  }
  EXPECT_GT(fruit, size_t(0));
  EXPECT_GT(larger, plain.leaves.size() / 20);    // the crown has both: shade inside, sun outside
  EXPECT_GT(smaller, plain.leaves.size() / 20);
  EXPECT_EQ(validate_mesh(shaded), "");
  // The bounds hold every leaf at its new size.
  for (const leaf_instance& l : shaded.leaves) {
    EXPECT_TRUE(glm::all(glm::lessThanEqual(shaded.bounds_min, l.position - glm::vec3(l.size) + 1e-4f)));
    EXPECT_TRUE(glm::all(glm::greaterThanEqual(shaded.bounds_max, l.position + glm::vec3(l.size) - 1e-4f)));
  }
}

// Open-sky leaves are lighter and yellower than those deep in the crown; the twig's offset is
// shared by its leaves more than it varies between them; zero settings leave the colour alone.
TEST(LeafLight, ColourFactorFromSkyAndTwig) {
  const glm::vec3 sun = leaf_color_factor(7, 3, 1.0f, 0, 1), shade = leaf_color_factor(7, 3, 0.35f, 0, 1);
  EXPECT_GT(sun.x + sun.y + sun.z, shade.x + shade.y + shade.z);
  EXPECT_GT(sun.x / sun.z, shade.x / shade.z);   // warmer in the sun
  EXPECT_EQ(leaf_color_factor(7, 3, 0.5f, 0, 0), glm::vec3(1));
  EXPECT_EQ(leaf_color_factor(7, 3, NAN, NAN, NAN), glm::vec3(1));
  // Variation: leaves of one node differ less from each other than leaves of different nodes.
  double within = 0, between = 0;
  const int n = 200;
  for (int k = 0; k < n; ++k) {
    const glm::vec3 a = leaf_color_factor(11, uint32_t(2 * k), 1, 0.5f, 0), b = leaf_color_factor(11, uint32_t(2 * k + 1), 1, 0.5f, 0);
    const glm::vec3 c = leaf_color_factor(uint32_t(1000 + k), uint32_t(2 * k), 1, 0.5f, 0);
    within += glm::length(a - b), between += glm::length(a - c);
  }
  EXPECT_LT(within, 0.6 * between);
  std::set<float> greens;
  for (uint32_t node = 0; node < 50; ++node) greens.insert(leaf_color_factor(node, 0, 1, 0.3f, 0).y);
  EXPECT_GT(greens.size(), size_t(40));
  for (float g : greens) EXPECT_TRUE(g > 0.6f && g < 1.4f);
}
