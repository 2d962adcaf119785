// Leaves shaded as a volume (render/mesh/leaf_shading.h): the crown's outward direction, the
// bent normals, and the two-sided cards every export writes.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>

#include <glm/geometric.hpp>
#include <tiny_gltf.h>

#include "generators/lsystem.h"
#include "render/io/export.h"
#include "render/mesh/leaf_blade.h"
#include "render/mesh/leaf_shading.h"

using namespace sylva;
namespace fs = std::filesystem;

namespace {

const float* floats(const tinygltf::Model& model, int accessor) {
  const tinygltf::Accessor& a = model.accessors[size_t(accessor)];
  const tinygltf::BufferView& v = model.bufferViews[size_t(a.bufferView)];
  return reinterpret_cast<const float*>(model.buffers[0].data.data() + v.byteOffset + a.byteOffset);
}

glm::vec3 vec3_at(const float* f, size_t k) { return {f[3 * k], f[3 * k + 1], f[3 * k + 2]}; }

}  // namespace

TEST(LeafShading, OutwardIsTheEllipsoidsNormal) {
  const crown_ellipsoid c{{0, 5, 0}, {4, 2, 4}};
  const glm::vec3 side = crown_outward(c, {4, 5, 0});
  EXPECT_NEAR(side.x, 1.0f, 1e-6f);
  const glm::vec3 top = crown_outward(c, {0, 7, 0});
  EXPECT_NEAR(top.y, 1.0f, 1e-6f);
  // Off the axes the gradient leans toward the short axis: at (2, 6) on a 4 x 2 ellipse the
  // normal is (2/16, 1/4) normalised, not the direction from the centre (2, 1).
  const glm::vec3 g = crown_outward(c, {2, 6, 0});
  EXPECT_NEAR(g.y / g.x, 2.0f, 1e-5f);
  EXPECT_EQ(crown_outward(c, c.centre), glm::vec3(0, 1, 0));
  EXPECT_NEAR(glm::length(crown_outward(c, {1, 2, 3})), 1.0f, 1e-6f);
}

TEST(LeafShading, BlendRunsFromTheCardToTheCrown) {
  const glm::vec3 n(0, 0, 1), out(1, 0, 0);
  EXPECT_EQ(blend_leaf_normal(n, out, 0), n);
  const glm::vec3 diag = glm::normalize(glm::vec3(1, 0, 1));
  EXPECT_NEAR(blend_leaf_normal(n, diag, 1).x, diag.x, 1e-6f);   // 45 degrees: the crown's own
  // 90 degrees away: capped at the cosine limit, bent toward the crown.
  EXPECT_NEAR(glm::dot(blend_leaf_normal(n, out, 1), n), min_leaf_normal_cos, 1e-5f);
  EXPECT_GT(blend_leaf_normal(n, out, 1).x, 0.96f);
  const glm::vec3 half = blend_leaf_normal(n, out, 0.5f);
  EXPECT_NEAR(half.x, std::sqrt(0.5f), 1e-6f);
  EXPECT_NEAR(half.z, std::sqrt(0.5f), 1e-6f);
  EXPECT_EQ(blend_leaf_normal(n, -n, 0.5f), n);                  // cancelled: the card's own
  EXPECT_EQ(blend_leaf_normal(n, out, std::nanf("")), n);        // a NaN slider is no bend
  // Bent almost against itself, a side stays on its own side (cosine 0.25).
  const glm::vec3 far = blend_leaf_normal(n, glm::normalize(glm::vec3(0.2f, 0, -1)), 0.9f);
  EXPECT_NEAR(glm::dot(far, n), min_leaf_normal_cos, 1e-5f);
  EXPECT_GT(far.x, 0.9f);
}

// Every baked card is two single-sided faces, each wound toward the side its normal lights; a face
// that looks out of the crown is lit from outside (render/mesh/leaf_shading.h).
// Blades (render/mesh/leaf_blade.h) bake the same way, with 12 triangles a face instead of 2.
TEST(LeafShading, ExportedCardsHaveAFacePerSideLitFromTheirSide) {
  for (const bool blades : {false, true}) {
  SCOPED_TRACE(blades ? "blades" : "cards");
  lsystem_params lp;
  lp.derivations = 6;
  const tree_skeleton t = grow_honda(lp, {});
  mesh_params p;
  p.leaves.mode = leaf_mode::tips;
  p.leaves.min_order = 1;
  p.leaves.blades = blades;
  const tree_mesh m = mesh_tree(t, p);
  ASSERT_FALSE(m.leaves.empty());
  // The export bends toward the crown of the leaves alive at the exported (final) step.
  crown_box box;
  size_t alive = 0;
  for (const leaf_instance& l : m.leaves)
    if (l.born <= m.steps && m.steps < l.died) box.add(l.position), ++alive;
  const crown_ellipsoid crown = box.ellipsoid();
  // How many cards the mesher placed facing into the crown: the export turns those over.
  size_t inward = 0;
  for (const leaf_instance& l : m.leaves) {
    const glm::quat q(l.orientation.w, l.orientation.x, l.orientation.y, l.orientation.z);
    if (l.born <= m.steps && m.steps < l.died && glm::dot(q * glm::vec3(0, 0, 1), crown_outward(crown, l.position)) < 0) ++inward;
  }
  EXPECT_GT(inward, alive / 10);   // the test sees cards whose outer side is their back
  for (float blend : {0.0f, 0.6f}) {
    export_options o;
    o.mesh = p;
    o.texture_size = 32;
    o.leaf_normal_blend = blend;
    o.baked_blades = blades;   // the hero profile bakes blades; plain bakes cards
    const fs::path file = fs::temp_directory_path() / ("sylva_leaf_shading_" + std::to_string(::getpid()) + ".glb");
    ASSERT_EQ(export_tree(t, m, {"lsystem", 1}, file.string(), o).error, "");
    tinygltf::TinyGLTF loader;
    tinygltf::Model model;
    std::string err, warn;
    ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &err, &warn, file.string())) << err;
    fs::remove(file);
    size_t faces = 0, bent = 0, outer = 0;
    for (const auto& mesh : model.meshes) {
      if (mesh.name != "leaves") continue;
      for (const auto& prim : mesh.primitives) {
        EXPECT_FALSE(model.materials[size_t(prim.material)].doubleSided);
        const float* pos = floats(model, prim.attributes.at("POSITION"));
        const float* nrm = floats(model, prim.attributes.at("NORMAL"));
        const tinygltf::Accessor& ia = model.accessors[size_t(prim.indices)];
        const tinygltf::BufferView& iv = model.bufferViews[size_t(ia.bufferView)];
        const unsigned char* ib = model.buffers[0].data.data() + iv.byteOffset + ia.byteOffset;
        auto index = [&](size_t k) -> size_t {
          if (ia.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) return reinterpret_cast<const uint16_t*>(ib)[k];
          return reinterpret_cast<const uint32_t*>(ib)[k];
        };
        for (size_t k = 0; k + 2 < ia.count; k += 3) {
          const glm::vec3 a = vec3_at(pos, index(k)), b = vec3_at(pos, index(k + 1)), c = vec3_at(pos, index(k + 2));
          const glm::vec3 facing = glm::normalize(glm::cross(b - a, c - a));
          const glm::vec3 n = vec3_at(nrm, index(k));
          // The leaf's petiole: the middle of the first two of its four corners (bake_leaf); a
          // blade's triangle is judged from its own centre.
          const size_t corner0 = index(k) / 4 * 4;
          const glm::vec3 out = crown_outward(crown, blades ? (a + b + c) / 3.0f : 0.5f * (vec3_at(pos, corner0) + vec3_at(pos, corner0 + 1)));
          ++faces;
          EXPECT_GT(glm::dot(n, facing), 0.0f) << "a face lit from its back";
          if (glm::dot(facing, out) >= 0) {
            ++outer;
            // A blade's vertex normal is smooth across its fold (up to 60 degrees off a triangle's).
            if (!blades || glm::dot(facing, out) >= 0.9f)
              EXPECT_GE(glm::dot(n, out), -1e-4f) << "a face looking out of the crown lit from inside";
          }
          if (glm::dot(n, facing) < 0.999f) ++bent;
        }
      }
    }
    // Two faces of 2 triangles per card, of coarse_blade_triangles per blade.
    EXPECT_EQ(faces, (blades ? 2 * size_t(coarse_blade_triangles) : 4) * alive);
    // One side of every card looks out (a folded, curled blade's triangles nearly so).
    EXPECT_NEAR(double(outer), double(faces) / 2, double(faces) / (blades ? 20 : 100));
    if (blend == 0 && !blades) EXPECT_EQ(bent, size_t(0));   // a blade's normals are smooth across its fold
    if (blend > 0) EXPECT_GT(bent, faces / 2);
  }
  }
}
