// Bark colour by height (render/mesh/bark_tint.h): the blend itself, and the glTF export that carries
// it as the bark's COLOR_0 on a texture tinted with the brighter end.
#include <gtest/gtest.h>

#include <filesystem>

#include <tiny_gltf.h>

#include "render/io/export.h"
#include "render/mesh/bark_tint.h"
#include "tests/fixtures.h"
#include "tests/scratch_dir.h"

using namespace sylva;

namespace {

struct scratch : sylva_test::scratch_dir {
  scratch() : scratch_dir("sylva_bark_tint_test") {}
};

// The bark's POSITION and COLOR_0 (float VEC3) of a GLB.
struct bark_vertices {
  std::vector<glm::vec3> position, color;
};
bark_vertices read_bark(const std::filesystem::path& file) {
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string err, warn;
  bark_vertices out;
  EXPECT_TRUE(loader.LoadBinaryFromFile(&model, &err, &warn, file.string())) << err;
  for (const auto& mesh : model.meshes) {
    if (mesh.name != "bark") continue;
    const auto& p = mesh.primitives[0];
    auto read = [&](const char* name, std::vector<glm::vec3>& to) {
      if (!p.attributes.count(name)) return;
      const tinygltf::Accessor& a = model.accessors[size_t(p.attributes.at(name))];
      EXPECT_EQ(a.componentType, TINYGLTF_COMPONENT_TYPE_FLOAT);
      const tinygltf::BufferView& v = model.bufferViews[size_t(a.bufferView)];
      const auto* f = reinterpret_cast<const float*>(model.buffers[0].data.data() + v.byteOffset + a.byteOffset);
      for (size_t k = 0; k < a.count; ++k) to.emplace_back(f[3 * k], f[3 * k + 1], f[3 * k + 2]);
    };
    read("POSITION", out.position);
    read("COLOR_0", out.color);
  }
  return out;
}

}  // namespace

TEST(BarkTint, BlendsFromTheBaseColourAtTheGroundToTheBarkColourAtItsHeight) {
  const bark_tint pine{{0.55f, 0.3f, 0.17f}, {0.3f, 0.28f, 0.26f}, 6.0f};
  EXPECT_EQ(pine.at(-0.1f), pine.base);
  EXPECT_EQ(pine.at(0.0f), pine.base);
  EXPECT_EQ(pine.at(6.0f), pine.color);
  EXPECT_EQ(pine.at(20.0f), pine.color);
  const glm::vec3 mid = pine.at(3.0f);   // smoothstep's middle: the plain average
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(mid[k], 0.5f * (pine.base[k] + pine.color[k]), 1e-6f);
  // The texture's tint is the brighter of the two per channel, so every ratio is at most 1 and the
  // ratio times the peak is the tint again.
  EXPECT_EQ(pine.peak(), glm::vec3(0.55f, 0.3f, 0.26f));
  for (float y : {0.0f, 1.5f, 3.0f, 4.5f, 6.0f}) {
    const glm::vec3 r = pine.ratio(y), back = r * pine.peak(), want = pine.at(y);
    for (int k = 0; k < 3; ++k) {
      EXPECT_GE(r[k], 0.0f);
      EXPECT_LE(r[k], 1.0f);
      EXPECT_NEAR(back[k], want[k], 1e-6f) << y;
    }
  }
  // Height 0 (or NaN): one colour, ratio 1.
  for (float h : {0.0f, std::nanf("")}) {
    const bark_tint one{{0.4f, 0.3f, 0.2f}, {0.1f, 0.1f, 0.1f}, h};
    EXPECT_FALSE(one.blends());
    EXPECT_EQ(one.at(0.0f), one.color);
    EXPECT_EQ(one.ratio(0.0f), glm::vec3(1.0f));
  }
}

// The bark's COLOR_0 with a blend is the crown occlusion (the COLOR_0 without one) times the ratio at
// each vertex's height: darker and greyer at the trunk's foot; above the blend, the bark colour over
// the texture's brighter tint.
TEST(BarkTint, GlbBarkColourIsTheOcclusionTimesTheBlendAtEachVertexHeight) {
  scratch dir;
  sylva_test::honda_export h = sylva_test::honda_for_export(7, 32);
  const tree_skeleton& t = h.t;
  const tree_mesh& m = h.m;
  export_options& o = h.o;
  o.bark_color = {0.55f, 0.3f, 0.17f};
  o.bark_base_color = {0.3f, 0.28f, 0.26f};
  ASSERT_EQ(export_tree(t, m, {"lsystem", 1}, dir / "one.glb", o).error, "");
  o.bark_base_height = 2.0f;
  ASSERT_EQ(export_tree(t, m, {"lsystem", 1}, dir / "blend.glb", o).error, "");
  const bark_vertices one = read_bark(dir / "one.glb"), blend = read_bark(dir / "blend.glb");
  ASSERT_FALSE(one.position.empty());
  ASSERT_EQ(one.position.size(), blend.position.size());
  ASSERT_EQ(one.color.size(), one.position.size());
  ASSERT_EQ(blend.color.size(), blend.position.size());
  const bark_tint tint{o.bark_color, o.bark_base_color, o.bark_base_height};
  size_t low = 0, high = 0;
  for (size_t i = 0; i < one.position.size(); ++i) {
    ASSERT_EQ(one.position[i], blend.position[i]);
    const glm::vec3 want = one.color[i] * tint.ratio(blend.position[i].y);
    for (int k = 0; k < 3; ++k) ASSERT_NEAR(blend.color[i][k], want[k], 1e-5f) << i;
    if (blend.position[i].y < 0.2f) {
      ++low;
      EXPECT_LT(blend.color[i].x, 0.6f * one.color[i].x);   // red falls most: 0.3 of 0.55
    }
    if (blend.position[i].y > 2.0f) {   // the bark colour over a texture tinted with the peak
      ++high;
      EXPECT_FLOAT_EQ(blend.color[i].x, one.color[i].x);
      EXPECT_FLOAT_EQ(blend.color[i].y, one.color[i].y);
      EXPECT_NEAR(blend.color[i].z, one.color[i].z * 0.17f / 0.26f, 1e-5f);
    }
  }
  EXPECT_GT(low, size_t(0));
  EXPECT_GT(high, size_t(0));
}
