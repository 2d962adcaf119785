// Issue 54: with levels, the FBX carries an FBX LOD group, as Unreal's and Unity's importers read
// it: a "LodGroup" model with a LodGroup NodeAttribute whose thresholds are the screen sizes the
// chain was built for, and <tree>_LOD0..3 as its children in order. Read back from the file's
// records and with assimp's importer (each level's triangles); Blender's check is in
// fbx_export_test.cpp.
#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

#include <assimp/Importer.hpp>
#include <assimp/scene.h>

#include "tests/run_sylva.h"
#include "tests/fixtures.h"
#include "tests/scratch_dir.h"
#include "generators/tree_spec.h"
#include "render/io/export.h"
#include "render/io/fbx_records.h"
#include "render/io/preset.h"
#include "render/mesh/lod.h"

using namespace sylva;
using sylva_test::slurp;

namespace {

// What the file says of its LOD group: the group model's type, its NodeAttribute's type, flags and
// properties, and the names of the models connected under the group, in connection order.
struct lod_group_view {
  std::string model_type, attribute_type, type_flags;
  std::map<std::string, double> props;
  std::vector<std::string> levels;
  int64_t attributes = 0, attributes_declared = -1;
};

lod_group_view read_group(const std::string& bytes, const std::string& group) {
  lod_group_view v;
  fbx::document d;
  EXPECT_EQ(fbx::parse(bytes, d), "");
  const fbx::record* objects = fbx::find(d.top, "Objects");
  const fbx::record* connections = fbx::find(d.top, "Connections");
  if (!objects || !connections) return v;
  std::map<int64_t, const fbx::record*> by_id;
  int64_t group_id = -1;
  for (const fbx::record& r : objects->children) {
    if (r.props.size() < 3) continue;
    by_id[fbx::as_int(r.props[0])] = &r;
    v.attributes += r.name == "NodeAttribute";
    if (r.name == "Model" && fbx::object_name(r) == group) {
      group_id = fbx::as_int(r.props[0]);
      v.model_type = fbx::as_string(r.props[2]);
    }
  }
  for (const fbx::record& c : connections->children) {
    if (c.props.size() < 3 || fbx::as_string(c.props[0]) != "OO" || fbx::as_int(c.props[2]) != group_id) continue;
    const auto it = by_id.find(fbx::as_int(c.props[1]));
    if (it == by_id.end()) continue;
    const fbx::record& r = *it->second;
    if (r.name == "Model") v.levels.push_back(fbx::object_name(r));
    if (r.name != "NodeAttribute") continue;
    v.attribute_type = fbx::as_string(r.props[2]);
    if (const fbx::record* f = fbx::child(r, "TypeFlags"); f && !f->props.empty()) v.type_flags = fbx::as_string(f->props[0]);
    if (const fbx::record* p70 = fbx::child(r, "Properties70"))
      for (const fbx::record& p : p70->children)
        if (p.props.size() >= 5) v.props[fbx::as_string(p.props[0])] = fbx::as_double(p.props[4]);
  }
  if (const fbx::record* defs = fbx::find(d.top, "Definitions"))
    for (const fbx::record& t : defs->children)
      if (t.name == "ObjectType" && !t.props.empty() && fbx::as_string(t.props[0]) == "NodeAttribute")
        if (const fbx::record* n = fbx::child(t, "Count"); n && !n->props.empty()) v.attributes_declared = fbx::as_int(n->props[0]);
  return v;
}

size_t faces_under(const aiScene* s, const aiNode* n) {
  size_t f = 0;
  for (unsigned k = 0; k < n->mNumMeshes; ++k) f += s->mMeshes[n->mMeshes[k]]->mNumFaces;
  for (unsigned k = 0; k < n->mNumChildren; ++k) f += faces_under(s, n->mChildren[k]);
  return f;
}

}  // namespace

TEST(FbxLodGroup, LevelsHangUnderALodGroupWithTheChainsScreenSizes) {
  sylva_test::scratch_dir dir("sylva-fbx-lod-group");
  const preset p = sylva_test::shipped_preset("lsystem_honda_a");
  const tree_skeleton t = grow(p.spec, grow_options{});
  const tree_mesh m = mesh_tree(t, p.mesh, p.spec.seed);
  const lod_chain c = build_lods(t, m, p.mesh, lod_params{});
  export_options o;
  o.mesh = p.mesh;
  o.texture_size = 32;
  o.lod0_coverage = c.coverage[0];
  for (int k = 1; k < lod_levels; ++k) o.lods.push_back({&c.level[size_t(k) - 1], c.coverage[size_t(k)], c.target[size_t(k)]});
  const export_result r = export_tree(t, m, {"lsystem", 1}, dir / "tree.fbx", o);
  ASSERT_EQ(r.error, "");
  EXPECT_EQ(r.warning.find("LOD group"), std::string::npos) << r.warning;

  const lod_group_view g = read_group(slurp(dir / "tree.fbx"), "tree");
  EXPECT_EQ(g.model_type, "LodGroup");
  EXPECT_EQ(g.attribute_type, "LodGroup");
  EXPECT_EQ(g.type_flags, "LodGroup");
  EXPECT_EQ(g.levels, (std::vector<std::string>{"tree_LOD0", "tree_LOD1", "tree_LOD2", "tree_LOD3"}));
  // Thresholds: one per level but the last, the screen size (percent of the view's height) down
  // to which that level shows.
  ASSERT_EQ(g.props.count("Thresholds|Level0"), size_t(1));
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(g.props.at("Thresholds|Level" + std::to_string(k)), 100.0 * double(c.coverage[size_t(k)]), 1e-4) << "level " << k;
  EXPECT_EQ(g.props.count("Thresholds|Level3"), size_t(0));
  EXPECT_EQ(g.props.at("ThresholdsUsedAsPercentage"), 1.0);
  for (int k = 0; k < lod_levels; ++k) EXPECT_EQ(g.props.count("DisplayLevels|Level" + std::to_string(k)), size_t(1));
  EXPECT_EQ(g.attributes_declared, g.attributes);

  // assimp reads the file whole: the group node holds the four levels, each with its triangles.
  Assimp::Importer imp;
  const aiScene* s = imp.ReadFile(dir / "tree.fbx", 0);
  ASSERT_NE(s, nullptr) << imp.GetErrorString();
  const aiNode* group = s->mRootNode->FindNode("tree");
  ASSERT_NE(group, nullptr);
  ASSERT_EQ(group->mNumChildren, unsigned(lod_levels));
  for (int k = 0; k < lod_levels; ++k) {
    EXPECT_EQ(std::string(group->mChildren[k]->mName.C_Str()), "tree_LOD" + std::to_string(k));
    EXPECT_EQ(faces_under(s, group->mChildren[k]), c.triangles[size_t(k)]) << "LOD" << k;
  }

  // Without levels the tree is no LOD group.
  const export_result plain = export_tree(t, m, {"lsystem", 1}, dir / "plain.fbx", export_options{});
  ASSERT_EQ(plain.error, "");
  fbx::document d;
  ASSERT_EQ(fbx::parse(slurp(dir / "plain.fbx"), d), "");
  EXPECT_EQ(slurp(dir / "plain.fbx").find("LodGroup"), std::string::npos);
}

TEST(FbxLodGroup, CliLodsWriteTheGroup) {
  sylva_test::scratch_dir dir("sylva-fbx-lod-cli");
  const sylva_run r = run_sylva("env -u DISPLAY -u WAYLAND_DISPLAY", "export '" + std::string(SYLVA_SOURCE_DIR) +
                                                                         "/presets/lsystem_honda_a.json' -o '" + (dir / "honda a.fbx") + "' --lods");
  ASSERT_EQ(r.code, 0) << r.err;
  lod_group_view g = read_group(slurp(dir / "honda a.fbx"), "honda_a");
  EXPECT_EQ(g.attribute_type, "LodGroup");
  EXPECT_EQ(g.levels.size(), size_t(lod_levels));
  EXPECT_GT(g.props["Thresholds|Level0"], g.props["Thresholds|Level1"]);
  EXPECT_GT(g.props["Thresholds|Level1"], g.props["Thresholds|Level2"]);
}

TEST(FbxLodGroup, RecordsRoundTripAndBadBytesAreRefused) {
  sylva_test::scratch_dir dir("sylva-fbx-records");
  const preset p = sylva_test::shipped_preset("lsystem_honda_a");
  const tree_skeleton t = grow(p.spec, grow_options{});
  const tree_mesh m = mesh_tree(t, p.mesh, p.spec.seed);
  ASSERT_EQ(export_tree(t, m, {"lsystem", 1}, dir / "t.fbx", export_options{}).error, "");
  const std::string bytes = slurp(dir / "t.fbx");
  fbx::document d;
  ASSERT_EQ(fbx::parse(bytes, d), "");
  EXPECT_EQ(fbx::write(d), bytes);   // the exporter's own file: every record already closed
  EXPECT_NE(fbx::make_lod_group(d, "no such node", {50}), "");
  EXPECT_NE(fbx::parse("Kaydara FBX Binary  \0\x1a\0", d), "");
  EXPECT_NE(fbx::parse(bytes.substr(0, bytes.size() / 2), d), "");
  std::string broken = bytes;
  broken[27] = '\x7f';   // the first record's end offset points past the file
  broken[33] = '\x7f';
  EXPECT_NE(fbx::parse(broken, d), "");
  // Hostile bytes: flipped bytes and cut files parse or are refused, never crash; whatever parses
  // writes back out and parses again.
  uint32_t seed = 54;
  auto next = [&] { return seed = seed * 1664525u + 1013904223u; };
  size_t refused = 0;
  for (int k = 0; k < 300; ++k) {
    std::string bad = bytes.substr(0, 27 + next() % (bytes.size() - 27));
    for (int f = 0; f < 4; ++f) bad[27 + next() % (bad.size() - 27)] = char(next() >> 24);
    if (!fbx::parse(bad, d).empty()) {
      ++refused;
      continue;
    }
    fbx::document again;
    EXPECT_EQ(fbx::parse(fbx::write(d), again), "");
  }
  EXPECT_GT(refused, size_t(0));
}
