// Exporters: GLB/glTF re-imported with tinygltf, OBJ parsed back, skeleton JSON, bad paths, and
// the Khronos validator on every glTF flavour.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "generators/lsystem.h"
#include "render/export.h"
#include "render/textures.h"

using namespace sylva;
namespace fs = std::filesystem;

namespace {

struct scratch {
  fs::path dir;
  scratch() {
    dir = fs::temp_directory_path() / ("sylva_export_test_" + std::to_string(::getpid()));
    fs::create_directories(dir);
  }
  ~scratch() {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
  std::string operator/(const std::string& name) const { return (dir / name).string(); }
};

struct honda_tree {
  tree_skeleton t;
  tree_mesh m;
  mesh_params p;
  export_options o;
  explicit honda_tree(int n) {
    lsystem_params lp;  // tree a: min = 0, so every derivation doubles the apices
    lp.derivations = n;
    t = grow_honda(lp, {});
    p.radial_segments = 6;
    m = mesh_tree(t, p);
    o.mesh = p;
    o.texture_size = 64;
  }
};

size_t leaves_alive(const tree_mesh& m, int step) {
  size_t n = 0;
  for (const leaf_instance& l : m.leaves) n += l.born <= step && step < l.died;
  return n;
}

const tinygltf::Mesh* find_mesh(const tinygltf::Model& model, const std::string& name) {
  for (const auto& mesh : model.meshes)
    if (mesh.name == name) return &mesh;
  return nullptr;
}

std::string slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

}  // namespace

TEST(Export, GlbReimportsWithMeshCounts) {
  scratch dir;
  honda_tree h(6);
  const export_result r = export_tree(h.t, h.m, {"lsystem", 1}, dir / "tree.glb", h.o);
  ASSERT_EQ(r.error, "");
  EXPECT_EQ(r.bytes, fs::file_size(dir / "tree.glb"));
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &err, &warn, dir / "tree.glb")) << err;
  EXPECT_EQ(model.materials.size(), size_t(2));
  EXPECT_EQ(model.images.size(), size_t(3));
  for (const auto& img : model.images) EXPECT_GE(img.bufferView, 0);  // embedded
  const tinygltf::Mesh* bark = find_mesh(model, "bark");
  const tinygltf::Mesh* leaves = find_mesh(model, "leaves");
  ASSERT_TRUE(bark && leaves);
  const auto& bp = bark->primitives[0];
  // One tree, nothing shed: every ring is used, so the bark keeps every vertex and index.
  EXPECT_EQ(model.accessors[bp.attributes.at("POSITION")].count, h.m.position.size());
  EXPECT_EQ(model.accessors[bp.indices].count, h.m.index.size());
  EXPECT_EQ(model.accessors[bp.indices].componentType, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
  EXPECT_TRUE(bp.attributes.count("TANGENT") && bp.attributes.count("NORMAL") && bp.attributes.count("TEXCOORD_0"));
  EXPECT_GE(model.materials[bp.material].normalTexture.index, 0);
  // Leaves: the 2^5 tips of step 6 less the one on the trunk's axis (order 0), 4 leaves each,
  // baked as quads of 4 vertices and 2 triangles.
  EXPECT_EQ(leaves_alive(h.m, 6), size_t(31 * 4));
  const auto& lp = leaves->primitives[0];
  EXPECT_EQ(model.accessors[lp.attributes.at("POSITION")].count, 4 * leaves_alive(h.m, 6));
  EXPECT_EQ(model.accessors[lp.indices].count, 6 * leaves_alive(h.m, 6));
  EXPECT_EQ(model.materials[lp.material].alphaMode, "MASK");
  EXPECT_TRUE(model.materials[lp.material].doubleSided);
}

TEST(Export, GltfWritesBinAndTexturesNextToIt) {
  scratch dir;
  honda_tree h(5);
  const export_result r = export_tree(h.t, h.m, {"lsystem", 1}, dir / "tree.gltf", h.o);
  ASSERT_EQ(r.error, "");
  EXPECT_EQ(r.files.size(), size_t(5));
  for (const char* f : {"tree.gltf", "tree.bin", "tree_bark.png", "tree_bark_normal.png", "tree_leaves.png"})
    EXPECT_TRUE(fs::exists(dir / f)) << f;
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadASCIIFromFile(&model, &err, &warn, dir / "tree.gltf")) << err;
  const tinygltf::Mesh* bark = find_mesh(model, "bark");
  ASSERT_TRUE(bark);
  EXPECT_EQ(model.accessors[bark->primitives[0].indices].count, h.m.index.size());
  for (const auto& e : fs::directory_iterator(dir.dir))  // no temporary files left behind
    EXPECT_EQ(e.path().filename().string().find(".part-"), std::string::npos) << e.path();
  EXPECT_EQ(model.images[0].width, 64);  // the PNG decodes
  image leaves;
  ASSERT_EQ(load_png(dir / "tree_leaves.png", leaves), "");
  EXPECT_EQ(leaves.width, 64);  // 2x2 atlas of 32-pixel leaves
}

TEST(Export, StepExportHasTheStepsTree) {
  scratch dir;
  honda_tree h(6);
  h.o.step = 3;
  ASSERT_EQ(export_tree(h.t, h.m, {"lsystem", 1}, dir / "s3.glb", h.o).error, "");
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &err, &warn, dir / "s3.glb")) << err;
  EXPECT_EQ(model.accessors[find_mesh(model, "bark")->primitives[0].indices].count, size_t(h.m.index_end[3]));
  // Step 3: 4 tips, 3 of them lateral, 4 leaves each.
  EXPECT_EQ(model.accessors[find_mesh(model, "leaves")->primitives[0].indices].count, size_t(6 * 3 * 4));
  h.o.dry_run = true;
  const export_result dry = export_tree(h.t, h.m, {"lsystem", 1}, dir / "dry.glb", h.o);
  EXPECT_GT(dry.bytes, size_t(0));
  EXPECT_FALSE(fs::exists(dir / "dry.glb"));
}

TEST(Export, ForestIsOneNodePerTreeAndBigMeshesUse32BitIndices) {
  scratch dir;
  tree_skeleton t;
  for (int tree = 0; tree < 2; ++tree) {
    int32_t prev = t.add_node({float(tree) * 5, 0, 0}, -1, 0.1f, 0, 0);
    for (int k = 1; k <= 1100; ++k) prev = t.add_node({float(tree) * 5, float(k) * 0.01f, 0}, prev, 0.05f, 1, 0);
  }
  t.steps = 1;
  t.tree_count = 2;
  mesh_params p;
  p.radial_segments = 32;  // 2202 rings * 33 = 72666 vertices; each tree alone has 36333
  export_options o;
  o.mesh = p;
  o.texture_size = 16;
  const tree_mesh m = mesh_tree(t, p);
  ASSERT_EQ(export_tree(t, m, {"test", 1}, dir / "forest.glb", o).error, "");
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &err, &warn, dir / "forest.glb")) << err;
  ASSERT_EQ(model.scenes[0].nodes.size(), size_t(2));
  EXPECT_EQ(model.nodes[model.scenes[0].nodes[1]].name, "tree_2");
  size_t verts = 0;
  for (const auto& mesh : model.meshes) {
    const auto& prim = mesh.primitives[0];
    verts += model.accessors[prim.attributes.at("POSITION")].count;
    EXPECT_EQ(model.accessors[prim.indices].componentType, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
  }
  EXPECT_EQ(verts, m.position.size());
  // One tree of 72666 vertices does not fit 16-bit indices.
  t.tree_count = 1;
  t.parent[1101] = 1100;
  t.order[1101] = 1;
  const tree_mesh one = mesh_tree(t, p);
  ASSERT_EQ(export_tree(t, one, {"test", 1}, dir / "one.glb", o).error, "");
  ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &err, &warn, dir / "one.glb")) << err;
  EXPECT_EQ(model.accessors[find_mesh(model, "bark")->primitives[0].indices].componentType,
            TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT);
}

TEST(Export, GrowthAnimationHasOneStepNodePerStep) {
  scratch dir;
  honda_tree h(5);
  h.o.growth_animation = true;
  h.o.seconds_per_step = 0.25f;
  const export_result r = export_tree(h.t, h.m, {"lsystem", 1}, dir / "grow.glb", h.o);
  ASSERT_EQ(r.error, "");
  EXPECT_EQ(r.animation_steps, 6);  // steps 0..5
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &err, &warn, dir / "grow.glb")) << err;
  ASSERT_EQ(model.animations.size(), size_t(1));
  EXPECT_EQ(model.animations[0].channels.size(), size_t(6));
  EXPECT_EQ(model.animations[0].samplers[2].interpolation, "STEP");
  // Step 2's node appears at 0.5 s and goes at 0.75 s.
  const auto& times = model.accessors[model.animations[0].samplers[2].input];
  EXPECT_FLOAT_EQ(float(times.maxValues[0]), 0.75f);
  h.o.max_animation_steps = 3;
  const export_result capped = export_tree(h.t, h.m, {"lsystem", 1}, dir / "capped.glb", h.o);
  EXPECT_EQ(capped.animation_steps, 3);
  EXPECT_LT(capped.bytes, r.bytes);
}

TEST(Export, ObjParsesBackWithMatchingCounts) {
  scratch dir;
  honda_tree h(6);
  const export_result r = export_tree(h.t, h.m, {"lsystem", 1}, dir / "tree.obj", h.o);
  ASSERT_EQ(r.error, "");
  std::istringstream in(slurp(dir / "tree.obj"));
  std::string line, group;
  size_t v = 0, vt = 0, vn = 0, bark_faces = 0, leaf_faces = 0;
  bool mtllib = false;
  while (std::getline(in, line)) {
    if (line.rfind("v ", 0) == 0) ++v;
    else if (line.rfind("vt ", 0) == 0) ++vt;
    else if (line.rfind("vn ", 0) == 0) ++vn;
    else if (line.rfind("g ", 0) == 0) group = line.substr(2);
    else if (line.rfind("mtllib tree.mtl", 0) == 0) mtllib = true;
    else if (line.rfind("f ", 0) == 0) {
      int a = 0, b = 0, c = 0;
      ASSERT_EQ(std::sscanf(line.c_str(), "f %d/%*d/%*d %d/%*d/%*d %d/%*d/%*d", &a, &b, &c), 3) << line;
      EXPECT_TRUE(a >= 1 && b >= 1 && c >= 1 && size_t(std::max({a, b, c})) <= v);
      (group == "bark" ? bark_faces : leaf_faces)++;
    }
  }
  const size_t leaves = leaves_alive(h.m, 6);
  EXPECT_TRUE(mtllib);
  EXPECT_EQ(v, h.m.position.size() + 4 * leaves);
  EXPECT_EQ(vt, v);
  EXPECT_EQ(vn, v);
  EXPECT_EQ(bark_faces, h.m.triangles());
  EXPECT_EQ(leaf_faces, 2 * leaves);
  const std::string mtl = slurp(dir / "tree.mtl");
  EXPECT_NE(mtl.find("newmtl bark"), std::string::npos);
  EXPECT_NE(mtl.find("newmtl leaves"), std::string::npos);
  EXPECT_TRUE(fs::exists(dir / "tree_leaves.png"));
}

TEST(Export, SkeletonJsonRoundTripsCounts) {
  honda_tree h(4);
  h.t.died[15] = 4;  // a shed tip: died is a number, the others null
  h.t.steps = 5;
  const auto doc = nlohmann::json::parse(skeleton_json(h.t, {"lsystem", 7}));
  EXPECT_EQ(doc["sylva_skeleton"], 1);
  EXPECT_EQ(doc["seed"], 7);
  EXPECT_EQ(doc["steps"], 5);
  EXPECT_EQ(doc["nodes"]["position"].size(), h.t.size());
  EXPECT_EQ(doc["nodes"]["parent"][3], h.t.parent[3]);
  EXPECT_TRUE(doc["nodes"]["died"][0].is_null());
  EXPECT_EQ(doc["nodes"]["died"][15], 4);
  // At step 2: the root and 1 + 2 internodes.
  EXPECT_EQ(nlohmann::json::parse(skeleton_json(h.t, {"lsystem", 7}, 2))["nodes"]["radius"].size(), size_t(4));
}

TEST(Export, UnwritablePathGivesErrorAndNoFile) {
  scratch dir;
  honda_tree h(3);
  const std::string bad = (dir.dir / "missing" / "tree.glb").string();
  const export_result r = export_tree(h.t, h.m, {"lsystem", 1}, bad, h.o);
  EXPECT_NE(r.error.find(bad), std::string::npos) << r.error;
  EXPECT_FALSE(fs::exists(bad));
  // The .gltf itself cannot be written (a folder has its name): the .bin and PNGs go too.
  fs::create_directories(dir / "blocked.gltf");
  fs::create_directories(dir.dir / "blocked.gltf" / "x");
  const export_result g = export_tree(h.t, h.m, {"lsystem", 1}, dir / "blocked.gltf", h.o);
  EXPECT_NE(g.error, "");
  EXPECT_FALSE(fs::exists(dir / "blocked.bin"));
  EXPECT_FALSE(fs::exists(dir / "blocked_bark.png"));
  EXPECT_NE(export_tree(h.t, h.m, {"lsystem", 1}, dir / "tree.xyz", h.o).error, "");
}

TEST(Export, KhronosValidatorReportsNoErrorsOrWarnings) {
  if (std::system("command -v node >/dev/null 2>&1 && command -v npm >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "node/npm not installed (scripts/install-deps.sh installs them)";
  const std::string src = SYLVA_SOURCE_DIR;
  ASSERT_EQ(std::system(("bash " + src + "/scripts/install-gltf-validator.sh").c_str()), 0)
      << "could not install the npm package gltf-validator";
  scratch dir;
  honda_tree h(7);
  std::string files;
  auto add = [&](const std::string& name, export_options o) {
    const export_result r = export_tree(h.t, h.m, {"lsystem", 1}, dir / name, o);
    ASSERT_EQ(r.error, "") << name;
    files.append(1, ' ').append(dir / name);
  };
  add("tree.glb", h.o);
  add("tree.gltf", h.o);
  export_options anim = h.o;
  anim.growth_animation = true;
  add("grow.glb", anim);
  add("grow.gltf", anim);
  export_options inst = h.o;
  inst.gltf_instancing = true;
  add("instanced.glb", inst);
  export_options step = h.o;
  step.step = 3;
  add("step3.gltf", step);
  // A forest of two trees: one node per tree.
  tree_skeleton forest = h.t;
  const size_t n = forest.size();
  for (size_t i = 0; i < n; ++i)
    forest.add_node(forest.position[i] + glm::vec3(3, 0, 0), forest.parent[i] < 0 ? -1 : forest.parent[i] + int32_t(n),
                    forest.radius[i], forest.born[i], forest.order[i]);
  forest.tree_count = 2;
  const tree_mesh fm = mesh_tree(forest, h.p);
  ASSERT_EQ(export_tree(forest, fm, {"lsystem", 1}, dir / "forest.glb", h.o).error, "");
  files.append(1, ' ').append(dir / "forest.glb");
  const std::string cmd = "node " + src + "/scripts/validate-gltf.js" + files + " > " + (dir / "report.txt") + " 2>&1";
  const int rc = std::system(cmd.c_str());
  EXPECT_EQ(rc, 0) << slurp(dir / "report.txt");
}

TEST(Textures, DeterministicTilingAndLeafOutlines) {
  const texture_set a = make_textures(32, 32, 5), b = make_textures(32, 32, 5);
  EXPECT_EQ(a.bark_color.pixels, b.bark_color.pixels);
  EXPECT_EQ(a.bark_normal.pixels, b.bark_normal.pixels);
  EXPECT_NE(make_bark_color(32, 6).pixels, a.bark_color.pixels);
  ASSERT_EQ(a.bark_color.pixels.size(), size_t(32 * 32 * 3));
  // Normals point out of the surface: blue (z) above the 0.5 midpoint everywhere.
  for (size_t k = 2; k < a.bark_normal.pixels.size(); k += 3) ASSERT_GT(a.bark_normal.pixels[k], 128);
  for (int v = 0; v < 4; ++v) {
    const image& l = a.leaf[v];
    ASSERT_EQ(l.channels, 4);
    auto alpha = [&](int x, int y) { return l.pixels[(size_t(y) * l.width + x) * 4 + 3]; };
    EXPECT_EQ(alpha(16, 12), 255) << "blade centre, variant " << v;  // midrib, mid-blade
    EXPECT_EQ(alpha(0, 0), 0) << "corner, variant " << v;
    EXPECT_EQ(alpha(31, 31), 0);
  }
  // The atlas keeps cell k at (k % 2, k / 2).
  const image atlas = make_leaf_atlas(a.leaf);
  ASSERT_EQ(atlas.width, 64);
  EXPECT_EQ(atlas.pixels[(size_t(32 + 12) * 64 + 32 + 16) * 4 + 1], a.leaf[3].pixels[(size_t(12) * 32 + 16) * 4 + 1]);
  EXPECT_EQ(leaf_atlas_cell(3), (std::array<float, 4>{0.5f, 0.5f, 1.0f, 1.0f}));
}

TEST(Textures, PngRoundTripAndErrors) {
  scratch dir;
  const image leaf = make_leaf_texture(16, 2, 1);
  ASSERT_EQ(save_png(leaf, dir / "leaf.png"), "");
  image back;
  ASSERT_EQ(load_png(dir / "leaf.png", back), "");
  EXPECT_EQ(back.width, 16);
  EXPECT_EQ(back.pixels, leaf.pixels);  // PNG is lossless
  EXPECT_NE(load_png(dir / "missing.png", back), "");
  EXPECT_NE(decode_png("not a png", back), "");
  std::string bytes;
  EXPECT_NE(encode_png(image{}, bytes), "");
  EXPECT_NE(save_png(leaf, (dir.dir / "no" / "leaf.png").string()), "");
}

TEST(Export, UserTexturesAreEmbedded) {
  scratch dir;
  honda_tree h(3);
  image bark{8, 4, 4, std::vector<uint8_t>(8 * 4 * 4, 200)};
  ASSERT_EQ(save_png(bark, dir / "mybark.png"), "");
  h.o.bark_texture = dir / "mybark.png";
  ASSERT_EQ(export_tree(h.t, h.m, {"lsystem", 1}, dir / "user.glb", h.o).error, "");
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &err, &warn, dir / "user.glb")) << err;
  EXPECT_EQ(model.images[0].width, 8);
  EXPECT_EQ(model.images[0].height, 4);
  h.o.leaf_texture = dir / "nope.png";
  const export_result r = export_tree(h.t, h.m, {"lsystem", 1}, dir / "user2.glb", h.o);
  EXPECT_NE(r.error.find("nope.png"), std::string::npos) << r.error;
  EXPECT_FALSE(fs::exists(dir / "user2.glb"));
}
