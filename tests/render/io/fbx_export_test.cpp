// FBX through assimp: read back with assimp's importer (materials and their PNGs beside the file,
// "<tree>_LOD<k>" levels, the wind's bones and animation), every record closed as Blender's
// importer demands, and Blender 3.4's own import when Blender is installed.
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <assimp/Importer.hpp>
#include <assimp/scene.h>

#include "tests/scratch_dir.h"
#include "render/io/export.h"
#include "render/mesh/lod.h"
#include "render/io/preset.h"

using namespace sylva;
namespace fs = std::filesystem;

using sylva_test::slurp;

namespace {

struct scratch : sylva_test::scratch_dir {
  scratch() : scratch_dir("sylva_fbx_test") {}
};

// Walks binary FBX 7.5 records as Blender's parse_fbx.py does: a record with children must end
// with a 25-byte null record. Returns the record count, or 0 when one is not closed.
size_t closed_records(const std::string& d, size_t at, size_t end, size_t& count) {
  while (at < end) {
    if (at + 25 <= d.size() && d.compare(at, 25, std::string(25, '\0')) == 0) return at + 25;
    uint64_t e = 0, props = 0;
    std::memcpy(&e, d.data() + at, 8);
    std::memcpy(&props, d.data() + at + 16, 8);
    const size_t body = at + 25 + uint8_t(d[at + 24]) + props;
    ++count;
    if (body < e) {
      if (e < 25 || d.compare(e - 25, 25, std::string(25, '\0')) != 0) return 0;
      if (closed_records(d, body, e - 25, count) == 0) return 0;
    }
    at = e;
  }
  return at;
}

struct tree_case {
  preset p;
  tree_skeleton t;
  tree_mesh m;
  export_options o;
  explicit tree_case(const char* name) {
    EXPECT_TRUE(load_preset_file(std::string(SYLVA_SOURCE_DIR) + "/presets/" + name + ".json", p).ok);
    t = grow(p.spec, grow_options{});
    m = mesh_tree(t, p.mesh, p.spec.seed);
    o.mesh = p.mesh;
    o.texture_size = 64;
    apply_render_params(o, p.render);
  }
};

}  // namespace

TEST(FbxExport, ReadsBackWithMaterialsTexturesAndClosedRecords) {
  scratch dir;
  tree_case c("lsystem_honda_a");
  const export_result r = export_tree(c.t, c.m, {"lsystem", 1}, dir / "honda.fbx", c.o);
  ASSERT_EQ(r.error, "");
  const std::string bytes = slurp(dir / "honda.fbx");
  ASSERT_EQ(bytes.compare(0, 20, "Kaydara FBX Binary  "), 0);
  size_t records = 0;
  EXPECT_GT(closed_records(bytes, 27, bytes.size(), records), size_t(0));
  EXPECT_GT(records, size_t(50));
  Assimp::Importer imp;
  const aiScene* s = imp.ReadFile(dir / "honda.fbx", 0);
  ASSERT_NE(s, nullptr) << imp.GetErrorString();
  size_t tris = 0;
  std::set<std::string> textures;
  for (unsigned k = 0; k < s->mNumMeshes; ++k) tris += s->mMeshes[k]->mNumFaces;
  EXPECT_EQ(tris, r.triangles);
  for (unsigned k = 0; k < s->mNumMaterials; ++k) {
    aiString tex;
    if (s->mMaterials[k]->GetTexture(aiTextureType_DIFFUSE, 0, &tex) == AI_SUCCESS) textures.insert(tex.C_Str());
  }
  ASSERT_GE(textures.size(), size_t(2));   // bark and leaves
  for (const std::string& t : textures) EXPECT_TRUE(fs::exists(dir / fs::path(t).filename().string())) << t;
  EXPECT_EQ(s->mNumAnimations, 0u);
}

TEST(FbxExport, LodLevelsAreNamedForEnginesAndWindIsBonesAndAnAnimation) {
  scratch dir;
  tree_case c("lsystem_honda_a");
  lod_chain chain = build_lods(c.t, c.m, c.p.mesh, lod_params{});
  export_options lo = c.o;
  for (int k = 1; k < lod_levels; ++k) lo.lods.push_back({&chain.level[size_t(k) - 1], chain.coverage[size_t(k)], chain.target[size_t(k)]});
  ASSERT_EQ(export_tree(c.t, c.m, {"lsystem", 1}, dir / "oak tree.fbx", lo).error, "");
  Assimp::Importer imp;
  const aiScene* s = imp.ReadFile(dir / "oak tree.fbx", 0);
  ASSERT_NE(s, nullptr) << imp.GetErrorString();
  for (int k = 0; k < lod_levels; ++k)
    EXPECT_NE(s->mRootNode->FindNode(("oak_tree_LOD" + std::to_string(k)).c_str()), nullptr) << "LOD" << k;

  export_options wo = c.o;
  wo.wind_seconds = 2;
  ASSERT_EQ(export_tree(c.t, c.m, {"lsystem", 1}, dir / "wind.fbx", wo).error, "");
  Assimp::Importer wimp;
  const aiScene* w = wimp.ReadFile(dir / "wind.fbx", 0);
  ASSERT_NE(w, nullptr) << wimp.GetErrorString();
  size_t bones = 0;
  for (unsigned k = 0; k < w->mNumMeshes; ++k) bones += w->mMeshes[k]->mNumBones;
  EXPECT_GT(bones, size_t(2));
  // assimp's own importer does not bring the stack back; the records are there (Blender plays it).
  const std::string wind = slurp(dir / "wind.fbx");
  EXPECT_NE(wind.find("AnimationStack"), std::string::npos);
  EXPECT_NE(wind.find("AnimationCurveNode"), std::string::npos);
  EXPECT_NE(w->mRootNode->FindNode("wind_root"), nullptr);

  if (std::system("command -v blender >/dev/null 2>&1") != 0) GTEST_SKIP() << "Blender not installed";
  const std::string script = std::string(SYLVA_SOURCE_DIR) + "/tools/blender/check_glb.py";
  const std::string log = dir / "blender.txt";
  const std::string cmd = "blender -b --factory-startup --python '" + script + "' -- '" + (dir / "wind.fbx") + "' '" +
                          (dir / "w.png") + "' 64 --wind > '" + log + "' 2>&1 && blender -b --factory-startup --python '" +
                          script + "' -- '" + (dir / "oak tree.fbx") + "' '" + (dir / "l.png") + "' 64 --lods 4 >> '" + log + "' 2>&1";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << slurp(log);
}
