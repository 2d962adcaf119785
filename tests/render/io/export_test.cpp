// Exporters: GLB/glTF re-imported with tinygltf, OBJ parsed back, skeleton JSON, bad paths, and
// the Khronos validator on every glTF flavour.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "tests/scratch_dir.h"
#include "generators/lsystem.h"
#include "render/io/export.h"
#include "render/assets/textures.h"
#include "render/io/preset.h"

using namespace sylva;
namespace fs = std::filesystem;

using sylva_test::slurp;

namespace {

struct scratch : sylva_test::scratch_dir {
  scratch() : scratch_dir("sylva_export_test") {}
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
    p.leaves.mode = leaf_mode::tips;   // 4 leaves on each lateral tip: counts derived by hand
    p.leaves.min_order = 1;
    m = mesh_tree(t, p);
    o.mesh = p;
    o.texture_size = 64;
  }
};

// Vertices the bark's indices use: what an export keeps (a cap's apex ring has one spare vertex,
// the seam copy of its apex, render/mesh/mesh.h).
size_t used_vertices(const tree_mesh& m) {
  std::vector<bool> used(m.position.size(), false);
  for (uint32_t i : m.index) used[i] = true;
  return size_t(std::count(used.begin(), used.end(), true));
}

// Gives the leaves two archetypes, alternately lobed and palmate.
void two_archetypes(tree_mesh& m) {
  for (size_t i = 0; i < m.leaves.size(); ++i)
    m.leaves[i].texture = uint8_t(i % 2 ? leaf_archetype::palmate : leaf_archetype::lobed);
}

const tinygltf::Material* find_material(const tinygltf::Model& model, const std::string& name) {
  for (const auto& m : model.materials)
    if (m.name == name) return &m;
  return nullptr;
}

// The bytes of an image embedded in a GLB.
std::string image_bytes(const tinygltf::Model& model, int image) {
  const tinygltf::BufferView& v = model.bufferViews[size_t(model.images[size_t(image)].bufferView)];
  const auto& data = model.buffers[size_t(v.buffer)].data;
  return std::string(data.begin() + std::ptrdiff_t(v.byteOffset), data.begin() + std::ptrdiff_t(v.byteOffset + v.byteLength));
}

// The image a material's base colour texture shows.
int base_color_image(const tinygltf::Model& model, const tinygltf::Material& m) {
  return model.textures[size_t(m.pbrMetallicRoughness.baseColorTexture.index)].source;
}

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

}  // namespace

// A user's textures in the test's folder: an 8x4 bark, a 16x16 leaf whose own alpha is all 255
// and a 16x16 grey opacity map (left half white, right half black).
namespace {

struct user_pngs {
  std::string bark, leaf, opacity;
  std::string bark_bytes, leaf_bytes;
  explicit user_pngs(const scratch& dir) {
    bark = dir / "mybark.png", leaf = dir / "myleaf.png", opacity = dir / "myopacity.png";
    image b{8, 4, 3, std::vector<uint8_t>(8 * 4 * 3)};
    for (size_t k = 0; k < b.pixels.size(); ++k) b.pixels[k] = uint8_t(k * 7);
    image l{16, 16, 4, std::vector<uint8_t>(16 * 16 * 4, 255)};
    for (size_t k = 0; k < 16 * 16; ++k) l.pixels[k * 4 + 1] = uint8_t(k);
    image o{16, 16, 3, std::vector<uint8_t>(16 * 16 * 3)};
    for (int y = 0; y < 16; ++y)
      for (int x = 0; x < 16; ++x)
        for (int c = 0; c < 3; ++c) o.pixels[size_t(y * 16 + x) * 3 + size_t(c)] = x < 8 ? 255 : 0;
    EXPECT_EQ(save_png(b, bark), "");
    EXPECT_EQ(save_png(l, leaf), "");
    EXPECT_EQ(save_png(o, opacity), "");
    bark_bytes = slurp(bark), leaf_bytes = slurp(leaf);
  }
};

}  // namespace

TEST(Export, GlbReimportsWithMeshCounts) {
  scratch dir;
  honda_tree h(6);
  two_archetypes(h.m);
  h.o.alpha_cutoff = 0.3f;
  const export_result r = export_tree(h.t, h.m, {"lsystem", 1}, dir / "tree.glb", h.o);
  ASSERT_EQ(r.error, "");
  EXPECT_EQ(r.warning, "");
  EXPECT_EQ(r.bytes, fs::file_size(dir / "tree.glb"));
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &err, &warn, dir / "tree.glb")) << err;
  // Bark (colour, roughness, normal) and one material per leaf archetype present (colour, normal).
  EXPECT_EQ(model.materials.size(), size_t(3));
  EXPECT_EQ(model.images.size(), size_t(3 + 2 * 2));
  for (const auto& img : model.images) EXPECT_GE(img.bufferView, 0);  // embedded
  const tinygltf::Mesh* bark = find_mesh(model, "bark");
  const tinygltf::Mesh* leaves = find_mesh(model, "leaves");
  ASSERT_TRUE(bark && leaves);
  const auto& bp = bark->primitives[0];
  // One tree, nothing shed: every ring is used, so the bark keeps every used vertex and index.
  EXPECT_EQ(model.accessors[bp.attributes.at("POSITION")].count, used_vertices(h.m));
  EXPECT_EQ(model.accessors[bp.indices].count, h.m.index.size());
  EXPECT_EQ(model.accessors[bp.indices].componentType, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
  EXPECT_TRUE(bp.attributes.count("TANGENT") && bp.attributes.count("NORMAL") && bp.attributes.count("TEXCOORD_0"));
  // Crown occlusion as a grey vertex colour: open sky (1) on the trunk's base, darker inside the crown.
  ASSERT_TRUE(bp.attributes.count("COLOR_0"));
  {
    const tinygltf::Accessor& c = model.accessors[bp.attributes.at("COLOR_0")];
    EXPECT_EQ(c.count, used_vertices(h.m));
    const tinygltf::BufferView& view = model.bufferViews[size_t(c.bufferView)];
    const auto* f = reinterpret_cast<const float*>(model.buffers[0].data.data() + view.byteOffset + c.byteOffset);
    float lo = 1;
    for (size_t k = 0; k < 3 * c.count; ++k) {
      ASSERT_TRUE(f[k] >= 0.0f && f[k] <= 1.0f) << f[k];
      lo = std::min(lo, f[k]);
    }
    EXPECT_FLOAT_EQ(f[0], 1.0f);
    EXPECT_LT(lo, 1.0f);
  }
  const tinygltf::Material& bm = model.materials[size_t(bp.material)];
  EXPECT_EQ(bm.name, "bark_furrowed");
  EXPECT_GE(bm.normalTexture.index, 0);
  EXPECT_GE(bm.pbrMetallicRoughness.metallicRoughnessTexture.index, 0);
  EXPECT_EQ(bm.pbrMetallicRoughness.metallicFactor, 0.0);
  // Leaves: the 2^5 tips of step 6 less the one on the trunk's axis (order 0), 4 leaves each,
  // baked as two-sided cards (a quad of 4 vertices and 2 triangles per side), one primitive per archetype.
  EXPECT_EQ(leaves_alive(h.m, 6), size_t(31 * 4));
  ASSERT_EQ(leaves->primitives.size(), size_t(2));
  size_t verts = 0, indices = 0;
  std::set<std::string> names;
  for (const auto& lp : leaves->primitives) {
    verts += model.accessors[lp.attributes.at("POSITION")].count;
    indices += model.accessors[lp.indices].count;
    EXPECT_TRUE(lp.attributes.count("TANGENT"));  // leaves carry a normal map
    const tinygltf::Material& lm = model.materials[size_t(lp.material)];
    names.insert(lm.name);
    EXPECT_EQ(lm.alphaMode, "MASK");
    EXPECT_FLOAT_EQ(float(lm.alphaCutoff), 0.3f);
    EXPECT_FALSE(lm.doubleSided);   // each side is a face of its own (render/mesh/leaf_shading.h)
    EXPECT_GE(lm.normalTexture.index, 0);
    // Each card shows the whole texture: UVs are the corners of the unit square.
    const tinygltf::Accessor& uv = model.accessors[lp.attributes.at("TEXCOORD_0")];
    const tinygltf::BufferView& view = model.bufferViews[size_t(uv.bufferView)];
    const auto* f = reinterpret_cast<const float*>(model.buffers[0].data.data() + view.byteOffset + uv.byteOffset);
    for (size_t k = 0; k < 2 * uv.count; ++k) ASSERT_TRUE(f[k] == 0.0f || f[k] == 1.0f) << f[k];
  }
  EXPECT_EQ(names, (std::set<std::string>{"leaves_lobed", "leaves_palmate"}));
  EXPECT_EQ(verts, 8 * leaves_alive(h.m, 6));
  EXPECT_EQ(indices, 12 * leaves_alive(h.m, 6));
  // Procedural textures are tinted: the leaf colour is the tinted archetype texture, byte for byte.
  const tinygltf::Material& lobed = *find_material(model, "leaves_lobed");
  image leaf;
  ASSERT_EQ(decode_png(image_bytes(model, base_color_image(model, lobed)), leaf), "");
  const image expect = tinted_texture(leaf_archetype_textures(leaf_archetype::lobed, 64, 1).color, h.o.leaf_color);
  EXPECT_EQ(leaf.width, 64);
  EXPECT_EQ(leaf.pixels, expect.pixels);
}

TEST(Export, InstancedLeavesAreOneCardMeshPerArchetype) {
  scratch dir;
  honda_tree h(5);
  two_archetypes(h.m);
  h.o.gltf_instancing = true;
  ASSERT_EQ(export_tree(h.t, h.m, {"lsystem", 1}, dir / "inst.glb", h.o).error, "");
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &err, &warn, dir / "inst.glb")) << err;
  size_t instances = 0;
  for (const char* name : {"leaves_lobed", "leaves_palmate"}) {
    const tinygltf::Mesh* card = find_mesh(model, name);
    ASSERT_TRUE(card) << name;
    ASSERT_EQ(card->primitives.size(), size_t(1));
    EXPECT_EQ(model.materials[size_t(card->primitives[0].material)].name, name);
    // Two sides of the archetype's blade grid (render/mesh/leaf_blade.h); of a flat card with blades off.
    EXPECT_EQ(model.accessors[card->primitives[0].attributes.at("POSITION")].count,
              size_t(2 * (h.m.blade.on ? blade_vertices : 4)));
    for (const auto& node : model.nodes)
      if (node.name == name) {
        const auto& ext = node.extensions.at("EXT_mesh_gpu_instancing");
        const size_t n = model.accessors[size_t(ext.Get("attributes").Get("TRANSLATION").GetNumberAsInt())].count;
        instances += n;
        // The crown occlusion per instance, one grey per instance.
        ASSERT_TRUE(ext.Get("attributes").Has("_COLOR_0"));
        EXPECT_EQ(model.accessors[size_t(ext.Get("attributes").Get("_COLOR_0").GetNumberAsInt())].count, n);
      }
  }
  EXPECT_EQ(instances, leaves_alive(h.m, 5));
}

TEST(Export, GltfWritesBinAndTexturesNextToIt) {
  scratch dir;
  honda_tree h(5);
  const export_result r = export_tree(h.t, h.m, {"lsystem", 1}, dir / "tree.gltf", h.o);
  ASSERT_EQ(r.error, "");
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadASCIIFromFile(&model, &err, &warn, dir / "tree.gltf")) << err;
  ASSERT_EQ(model.materials.size(), size_t(2));
  const std::string leaf = model.materials[1].name;  // leaves_<the archetype of these leaves>
  EXPECT_EQ(leaf.rfind("leaves_", 0), size_t(0)) << leaf;
  EXPECT_EQ(r.files.size(), size_t(7));
  for (const std::string& f : std::vector<std::string>{"tree.gltf", "tree.bin", "tree_bark_furrowed.png", "tree_bark_furrowed_normal.png",
                              "tree_bark_furrowed_roughness.png", "tree_" + leaf + ".png", "tree_" + leaf + "_normal.png"})
    EXPECT_TRUE(fs::exists(dir / f)) << f;
  for (const auto& e : fs::directory_iterator(dir.dir))  // no temporary files left behind
    EXPECT_EQ(e.path().filename().string().find(".part-"), std::string::npos) << e.path();
  const tinygltf::Mesh* bark = find_mesh(model, "bark");
  ASSERT_TRUE(bark);
  EXPECT_EQ(model.accessors[bark->primitives[0].indices].count, h.m.index.size());
  EXPECT_EQ(model.images[0].width, 64);  // the PNG decodes
  image leaves;
  ASSERT_EQ(load_png(dir / ("tree_" + leaf + ".png"), leaves), "");
  EXPECT_EQ(leaves.width, 64);  // texture_size: leaves as big as the bark
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
  // The step's tree re-meshed: its tips then get caps, so compare with that mesh, not a prefix.
  EXPECT_EQ(model.accessors[find_mesh(model, "bark")->primitives[0].indices].count,
            mesh_tree_at_step(h.t, h.m, h.p, 3).index.size());
  // Step 3: 4 tips, 3 of them lateral, 4 leaves each, 12 indices per two-sided card.
  EXPECT_EQ(model.accessors[find_mesh(model, "leaves")->primitives[0].indices].count, size_t(12 * 3 * 4));
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
  p.leaves_enabled = false;
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
  EXPECT_EQ(verts, used_vertices(m));
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
  // A NaN speed (typed into the dialog's field) would be written as null bounds: refused by name.
  h.o.seconds_per_step = std::nanf("");
  const export_result nan = export_tree(h.t, h.m, {"lsystem", 1}, dir / "nan.glb", h.o);
  EXPECT_EQ(nan.error, "seconds per step: nan is not a finite number");
  EXPECT_FALSE(fs::exists(dir / "nan.glb"));
}

TEST(Export, ObjParsesBackWithMatchingCounts) {
  scratch dir;
  honda_tree h(6);
  two_archetypes(h.m);
  const export_result r = export_tree(h.t, h.m, {"lsystem", 1}, dir / "tree.obj", h.o);
  ASSERT_EQ(r.error, "");
  std::istringstream in(slurp(dir / "tree.obj"));
  std::string line, group, material;
  size_t v = 0, vt = 0, vn = 0, bark_faces = 0, leaf_faces = 0;
  std::map<std::string, size_t> faces_by_material;
  bool mtllib = false;
  while (std::getline(in, line)) {
    if (line.rfind("v ", 0) == 0) ++v;
    else if (line.rfind("vt ", 0) == 0) ++vt;
    else if (line.rfind("vn ", 0) == 0) ++vn;
    else if (line.rfind("g ", 0) == 0) group = line.substr(2);
    else if (line.rfind("usemtl ", 0) == 0) material = line.substr(7);
    else if (line.rfind("mtllib tree.mtl", 0) == 0) mtllib = true;
    else if (line.rfind("f ", 0) == 0) {
      int a = 0, b = 0, c = 0;
      ASSERT_EQ(std::sscanf(line.c_str(), "f %d/%*d/%*d %d/%*d/%*d %d/%*d/%*d", &a, &b, &c), 3) << line;
      EXPECT_TRUE(a >= 1 && b >= 1 && c >= 1 && size_t(std::max({a, b, c})) <= v);
      (group == "bark" ? bark_faces : leaf_faces)++;
      faces_by_material[material]++;
    }
  }
  const size_t leaves = leaves_alive(h.m, 6);
  EXPECT_TRUE(mtllib);
  EXPECT_EQ(v, used_vertices(h.m) + 8 * leaves);   // two-sided cards: a quad per side
  EXPECT_EQ(vt, v);
  EXPECT_EQ(vn, v);
  EXPECT_EQ(bark_faces, h.m.triangles());
  EXPECT_EQ(leaf_faces, 4 * leaves);
  // One material per archetype present, plus the bark.
  ASSERT_EQ(faces_by_material.size(), size_t(3));
  EXPECT_EQ(faces_by_material["bark_furrowed"], h.m.triangles());
  EXPECT_EQ(faces_by_material["leaves_lobed"] + faces_by_material["leaves_palmate"], 4 * leaves);
  EXPECT_GT(faces_by_material["leaves_palmate"], size_t(0));
  const std::string mtl = slurp(dir / "tree.mtl");
  for (const char* want : {"newmtl bark_furrowed\n", "map_Kd tree_bark_furrowed.png\n", "map_Bump -bm 1 tree_bark_furrowed_normal.png\n",
                           "newmtl leaves_lobed\n", "map_Kd tree_leaves_lobed.png\n", "map_d -imfchan m tree_leaves_lobed.png\n",
                           "norm tree_leaves_lobed_normal.png\n", "newmtl leaves_palmate\n"})
    EXPECT_NE(mtl.find(want), std::string::npos) << want << mtl;
  for (const char* f : {"tree_bark_furrowed.png", "tree_bark_furrowed_normal.png", "tree_leaves_lobed.png",
                        "tree_leaves_lobed_normal.png", "tree_leaves_palmate.png", "tree_leaves_palmate_normal.png"})
    EXPECT_TRUE(fs::exists(dir / f)) << f;
  EXPECT_EQ(r.files.size(), size_t(2 + 3 + 4));  // obj, mtl, bark colour/normal/roughness, 2 leaves x 2
  image leaf;
  ASSERT_EQ(load_png(dir / "tree_leaves_palmate.png", leaf), "");
  EXPECT_EQ(leaf.channels, 4);  // the alpha map_d reads
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
  // No dead wood: every node's dead is null.
  ASSERT_EQ(doc["nodes"]["dead"].size(), h.t.size());
  EXPECT_TRUE(doc["nodes"]["dead"][15].is_null());
  // A self-pruned limb's stub (generators/history.h) says from which step it is dead wood.
  h.t.dead.assign(h.t.size(), never_died);
  h.t.dead[7] = 3;
  const auto stub = nlohmann::json::parse(skeleton_json(h.t, {"lsystem", 7}));
  EXPECT_EQ(stub["nodes"]["dead"][7], 3);
  EXPECT_TRUE(stub["nodes"]["dead"][6].is_null());
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
    files.append(" '").append(dir / name).append("'");
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
  // Two leaf archetypes: a material and a primitive (or an instanced card) each, in every form.
  two_archetypes(h.m);
  add("two.glb", h.o);
  add("two.gltf", h.o);
  add("two_grow.glb", anim);
  add("two_instanced.glb", inst);
  add("two_instanced_grow.gltf", [&] { export_options o = inst; o.growth_animation = true; return o; }());
  // The user's textures, in a folder whose name needs escaping in a uri.
  user_pngs user(dir);
  export_options own = h.o;
  own.bark_texture = user.bark, own.leaf_texture = user.leaf, own.leaf_opacity = user.opacity;
  add("own textures.gltf", own);
  add("own.glb", own);
  const std::string cmd = "node " + src + "/scripts/validate-gltf.js" + files + " > " + (dir / "report.txt") + " 2>&1";
  const int rc = std::system(cmd.c_str());
  EXPECT_EQ(rc, 0) << slurp(dir / "report.txt");
}

TEST(Textures, PngRoundTripAndErrors) {
  scratch dir;
  const image leaf = leaf_archetype_textures(leaf_archetype::palmate, 16).color;
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

TEST(Export, UserTexturesReachGlbAndObj) {
  scratch dir;
  user_pngs user(dir);
  honda_tree h(4);
  two_archetypes(h.m);  // replaced by the one user leaf material
  render_params rp;
  rp.bark_texture = user.bark;
  rp.leaf_texture = user.leaf;
  rp.leaf_opacity = user.opacity;
  apply_render_params(h.o, rp);
  const export_result r = export_tree(h.t, h.m, {"lsystem", 1}, dir / "user.glb", h.o);
  ASSERT_EQ(r.error, "");
  EXPECT_EQ(r.warning, "");
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &err, &warn, dir / "user.glb")) << err;
  ASSERT_EQ(model.materials.size(), size_t(2));
  const tinygltf::Material* bark = find_material(model, "bark_custom");
  const tinygltf::Material* leaves = find_material(model, "leaves_custom");
  ASSERT_TRUE(bark && leaves);
  // The bark PNG is embedded byte for byte; a foreign colour map gets no procedural relief.
  EXPECT_EQ(image_bytes(model, base_color_image(model, *bark)), user.bark_bytes);
  EXPECT_EQ(bark->normalTexture.index, -1);
  EXPECT_FALSE(find_mesh(model, "bark")->primitives[0].attributes.count("TANGENT"));
  // The leaf: the user's colours, the opacity map's grey as alpha; all leaves in one primitive.
  EXPECT_EQ(find_mesh(model, "leaves")->primitives.size(), size_t(1));
  image leaf;
  ASSERT_EQ(decode_png(image_bytes(model, base_color_image(model, *leaves)), leaf), "");
  ASSERT_EQ(leaf.width, 16);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      const size_t k = size_t(y * 16 + x);
      ASSERT_EQ(leaf.pixels[k * 4 + 1], uint8_t(k));
      ASSERT_EQ(leaf.pixels[k * 4 + 3], x < 8 ? 255 : 0) << x << "," << y;
    }

  // OBJ: the same files beside it.
  ASSERT_EQ(export_tree(h.t, h.m, {"lsystem", 1}, dir / "user.obj", h.o).error, "");
  EXPECT_EQ(slurp(dir / "user_bark_custom.png"), user.bark_bytes);
  image beside;
  ASSERT_EQ(load_png(dir / "user_leaves_custom.png", beside), "");
  EXPECT_EQ(beside.pixels, leaf.pixels);
  const std::string mtl = slurp(dir / "user.mtl");
  EXPECT_NE(mtl.find("map_Kd user_leaves_custom.png"), std::string::npos) << mtl;
  EXPECT_EQ(mtl.find("leaves_lobed"), std::string::npos) << mtl;

  // Without an opacity map the leaf PNG is the user's file, unchanged.
  h.o.leaf_opacity.clear();
  ASSERT_EQ(export_tree(h.t, h.m, {"lsystem", 1}, dir / "plain.obj", h.o).error, "");
  EXPECT_EQ(slurp(dir / "plain_leaves_custom.png"), user.leaf_bytes);
}

TEST(Export, UnusableUserTexturesWarnAndFallBack) {
  scratch dir;
  user_pngs user(dir);
  honda_tree h(3);
  std::ofstream(dir / "corrupt.png", std::ios::binary) << "\x89PNG\r\n\x1a\nnot really";
  const image wide{9000, 1, 3, std::vector<uint8_t>(9000 * 3, 90)};
  ASSERT_EQ(save_png(wide, dir / "huge.png"), "");
  image small{8, 8, 3, std::vector<uint8_t>(8 * 8 * 3, 0)};
  ASSERT_EQ(save_png(small, dir / "small_opacity.png"), "");
  struct unusable {
    std::string export_options::*field;
    std::string path, why;
  };
  const unusable cases[] = {{&export_options::leaf_texture, dir / "nope.png", "file not found"},
                            {&export_options::bark_texture, dir / "corrupt.png", "not a readable image"},
                            {&export_options::bark_texture, dir / "huge.png", "9000x1 pixels, over the limit of 8192"},
                            {&export_options::leaf_texture, dir.dir.string(), "not a file"}};
  for (const unusable& c : cases) {
    SCOPED_TRACE(c.path);
    export_options o = h.o;
    o.*c.field = c.path;
    const std::string out = dir / "fallback.glb";
    fs::remove(out);
    const export_result r = export_tree(h.t, h.m, {"lsystem", 1}, out, o);
    ASSERT_EQ(r.error, "");
    EXPECT_NE(r.warning.find(c.path), std::string::npos) << r.warning;
    EXPECT_NE(r.warning.find(c.why), std::string::npos) << r.warning;
    EXPECT_NE(r.warning.find("procedural"), std::string::npos) << r.warning;
    ASSERT_TRUE(fs::exists(out));  // written all the same, with the procedural materials
    tinygltf::TinyGLTF loader;
    tinygltf::Model model;
    std::string err, warn;
    ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &err, &warn, out)) << err;
    EXPECT_TRUE(find_material(model, "bark_furrowed"));
    EXPECT_FALSE(find_material(model, "leaves_custom"));
  }
  // An opacity map of another size: a warning, and the leaf keeps its own alpha (all 255).
  export_options o = h.o;
  o.leaf_texture = user.leaf;
  o.leaf_opacity = dir / "small_opacity.png";
  const export_result r = export_tree(h.t, h.m, {"lsystem", 1}, dir / "sizes.obj", o);
  ASSERT_EQ(r.error, "");
  EXPECT_NE(r.warning.find("8x8 pixels but the leaf texture is 16x16"), std::string::npos) << r.warning;
  EXPECT_EQ(slurp(dir / "sizes_leaves_custom.png"), user.leaf_bytes);
  // An opacity map without a leaf texture of the user's own is ignored, with a word why.
  o.leaf_texture.clear();
  EXPECT_NE(export_tree(h.t, h.m, {"lsystem", 1}, dir / "sizes.obj", o).warning.find("no leaf texture"), std::string::npos);
}

TEST(Export, ApplyRenderParamsCopiesEveryMaterialSetting) {
  render_params rp;
  rp.bark = bark_archetype::peeling;
  rp.bark_color = {0.1f, 0.2f, 0.3f};
  rp.leaf_color = {0.4f, 0.5f, 0.6f};
  rp.alpha_cutoff = 0.7f;
  rp.leaf_normal_blend = 0.25f;
  rp.bark_texture = "b.png", rp.leaf_texture = "l.png", rp.leaf_opacity = "o.png";
  export_options o;
  apply_render_params(o, rp);
  EXPECT_EQ(o.bark, bark_archetype::peeling);
  EXPECT_EQ(o.bark_color, rp.bark_color);
  EXPECT_EQ(o.leaf_color, rp.leaf_color);
  EXPECT_EQ(o.alpha_cutoff, 0.7f);
  EXPECT_EQ(o.leaf_normal_blend, 0.25f);
  EXPECT_EQ(o.bark_texture, "b.png");
  EXPECT_EQ(o.leaf_texture, "l.png");
  EXPECT_EQ(o.leaf_opacity, "o.png");
  EXPECT_EQ(export_options{}.texture_size, 512);
}

// Issue 15, item 1: a multi-file export that fails at any one of its files leaves the previous
// export byte-identical and no temporary behind.
TEST(Export, FailedMultiFileExportLeavesThePreviousOneWhole) {
  scratch dir;
  honda_tree older(4), newer(6);
  newer.o.mesh.leaves.archetype = leaf_archetype::lobed;   // other bytes in every file
  for (const std::string name : {"tree.obj", "tree.gltf"}) {
    const export_result first = export_tree(older.t, older.m, {"lsystem", 1}, dir / name, older.o);
    ASSERT_EQ(first.error, "");
    ASSERT_GE(first.files.size(), size_t(4)) << name;
    std::map<std::string, std::string> before;
    for (const std::string& f : first.files) before[f] = slurp(f);
    for (size_t k = 0; k < first.files.size(); ++k) {
      inject_write_failure_for_tests(int(k));
      const export_result failed = export_tree(newer.t, newer.m, {"lsystem", 1}, dir / name, newer.o);
      inject_write_failure_for_tests(-1);
      EXPECT_NE(failed.error, "") << name << ", failure at file " << k;
      EXPECT_NE(failed.error.find("No space left"), std::string::npos) << failed.error;
      for (const auto& [f, bytes] : before) EXPECT_EQ(slurp(f), bytes) << f << " after a failure at file " << k;
      size_t entries = 0;
      for (const auto& e : fs::directory_iterator(dir.dir)) entries += e.path().filename().string()[0] == '.';
      EXPECT_EQ(entries, size_t(0)) << "a temporary was left behind";
    }
    // Without a failure the new export replaces every file.
    const export_result second = export_tree(newer.t, newer.m, {"lsystem", 1}, dir / name, newer.o);
    ASSERT_EQ(second.error, "");
    EXPECT_NE(slurp(dir / name), before[dir / name]);
  }
}

// The same on a real full disk: a small tmpfs (needs the right to mount; skipped otherwise).
TEST(Export, FullDiskLeavesThePreviousExportWhole) {
  scratch dir;
  const fs::path mnt = dir.dir / "small";
  fs::create_directories(mnt);
  const std::string mount = "mount -t tmpfs -o size=12m tmpfs '" + mnt.string() + "' 2>/dev/null";
  if (std::system(mount.c_str()) != 0) GTEST_SKIP() << "cannot mount a tmpfs here (needs CAP_SYS_ADMIN)";
  struct unmount {
    std::string cmd;
    ~unmount() { if (std::system(cmd.c_str()) != 0) {} }
  } guard{"umount '" + mnt.string() + "'"};
  honda_tree older(4), newer(9);
  const std::string obj = (mnt / "tree.obj").string();
  const export_result first = export_tree(older.t, older.m, {"lsystem", 1}, obj, older.o);
  ASSERT_EQ(first.error, "");
  std::map<std::string, std::string> before;
  for (const std::string& f : first.files) before[f] = slurp(f);
  // Fill the disk, leaving less room than the new export needs.
  const std::string filler = (mnt / "filler").string();
  ASSERT_EQ(std::system(("dd if=/dev/zero of='" + filler + "' bs=64k 2>/dev/null; true").c_str()), 0);
  fs::resize_file(filler, fs::file_size(filler) - 200 * 1024);
  const export_result failed = export_tree(newer.t, newer.m, {"lsystem", 1}, obj, newer.o);
  EXPECT_NE(failed.error, "");
  for (const auto& [f, bytes] : before) EXPECT_EQ(slurp(f), bytes) << f;
  size_t temps = 0;
  for (const auto& e : fs::directory_iterator(mnt)) temps += e.path().filename().string()[0] == '.';
  EXPECT_EQ(temps, size_t(0));
}
