// FBX export through assimp (Debian's libassimp): the bark and leaf materials with their PNGs
// beside the file, the LOD levels as "<tree>_LOD<k>" nodes (Unity's LODGroup convention) under an
// FBX LOD group (Unreal's and Unity's importers read it; render/io/fbx_records.h), and the
// wind skin's joints with the loop as an animation. One all-or-nothing write of every file.
#include "render/io/export_internal.h"

#include <filesystem>
#include <memory>

#include <assimp/Exporter.hpp>
#include <assimp/scene.h>

#include "render/io/export_wind.h"
#include "render/io/fbx_records.h"

namespace sylva::export_internal {

namespace {

// FBX's unit is the centimetre (assimp writes UnitScaleFactor 1): Sylva's metres are scaled by
// 100 so that Blender, Unity and Unreal import the tree at its size.
constexpr float fbx_units_per_metre = 100.0f;

aiVector3D vec(const glm::vec3& v, float s = 1) { return {v.x * s, v.y * s, v.z * s}; }

template <class T>
T* copy_array(const std::vector<T>& v) {
  T* out = new T[v.size()];
  std::copy(v.begin(), v.end(), out);
  return out;
}

// Children are appended after construction: aiNode owns them.
void add_children(aiNode* parent, const std::vector<aiNode*>& kids) {
  if (kids.empty()) return;
  aiNode** all = new aiNode*[parent->mNumChildren + kids.size()];
  for (unsigned k = 0; k < parent->mNumChildren; ++k) all[k] = parent->mChildren[k];
  for (size_t k = 0; k < kids.size(); ++k) {
    kids[k]->mParent = parent;
    all[parent->mNumChildren + k] = kids[k];
  }
  delete[] parent->mChildren;
  parent->mChildren = all;
  parent->mNumChildren += unsigned(kids.size());
}

struct fbx_builder {
  material_source& src;
  std::string stem_name;
  const wind_bake* wind = nullptr;
  std::vector<std::string> joint_names;
  std::vector<aiMesh*> meshes;
  std::vector<aiMaterial*> materials;
  std::vector<std::pair<std::string, std::string>> files;   // (file name, PNG bytes)
  int bark = -1;
  std::array<int, leaf_slots> leaf = [] { std::array<int, leaf_slots> a; a.fill(-1); return a; }();
  std::string error;

  std::string png(const std::string& name, const std::string& bytes) {
    const std::string file = stem_name + "_" + name + ".png";
    files.emplace_back(file, bytes);
    return file;
  }
  int add_material(const std::string& name, const material_pngs& p, bool cut_out) {
    auto* m = new aiMaterial;
    aiString n(name);
    m->AddProperty(&n, AI_MATKEY_NAME);
    aiColor3D white(1, 1, 1);
    m->AddProperty(&white, 1, AI_MATKEY_COLOR_DIFFUSE);
    aiString color(png(name, p.color));
    m->AddProperty(&color, AI_MATKEY_TEXTURE_DIFFUSE(0));
    if (cut_out) m->AddProperty(&color, AI_MATKEY_TEXTURE_OPACITY(0));   // the colour PNG's alpha
    if (!p.normal.empty()) {
      aiString normal(png(name + "_normal", p.normal));
      m->AddProperty(&normal, AI_MATKEY_TEXTURE_NORMALS(0));
    }
    materials.push_back(m);
    return int(materials.size()) - 1;
  }
  int bark_material() {
    if (bark >= 0) return bark;
    const material_pngs* p = src.bark();
    if (!p) return -1;
    return bark = add_material(src.bark_name(), *p, false);
  }
  int leaf_material(int slot) {
    int& m = leaf[size_t(slot)];
    if (m >= 0) return m;
    const material_pngs* p = src.leaf(slot);
    if (!p) return -1;
    return m = add_material(src.leaf_name(slot), *p, true);
  }

  // One geometry as an aiMesh (its index into `meshes`); -1 on a material failure.
  int add_mesh(const geometry& g, int material, const std::string& name) {
    if (material < 0) return -1;
    auto* m = new aiMesh;
    m->mName = aiString(name);
    m->mMaterialIndex = unsigned(material);
    m->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
    const size_t n = g.position.size();
    m->mNumVertices = unsigned(n);
    m->mVertices = new aiVector3D[n];
    m->mNormals = new aiVector3D[n];
    m->mTextureCoords[0] = new aiVector3D[n];
    m->mNumUVComponents[0] = 2;
    const bool tangents = g.tangent.size() == n;
    if (tangents) m->mTangents = new aiVector3D[n], m->mBitangents = new aiVector3D[n];
    if (g.color.size() == n) m->mColors[0] = new aiColor4D[n];
    for (size_t i = 0; i < n; ++i) {
      m->mVertices[i] = vec(g.position[i], fbx_units_per_metre);
      m->mNormals[i] = vec(g.normal[i]);
      m->mTextureCoords[0][i] = aiVector3D(g.uv[i].x, 1.0f - g.uv[i].y, 0);   // FBX's v runs up
      if (tangents) {
        const glm::vec3 t(g.tangent[i]);
        m->mTangents[i] = vec(t);
        m->mBitangents[i] = vec(glm::cross(g.normal[i], t) * g.tangent[i].w);
      }
      if (m->mColors[0]) m->mColors[0][i] = aiColor4D(g.color[i].x, g.color[i].y, g.color[i].z, 1);
    }
    m->mNumFaces = unsigned(g.index.size() / 3);
    m->mFaces = new aiFace[m->mNumFaces];
    for (unsigned f = 0; f < m->mNumFaces; ++f) {
      m->mFaces[f].mNumIndices = 3;
      m->mFaces[f].mIndices = new unsigned[3]{g.index[3 * f], g.index[3 * f + 1], g.index[3 * f + 2]};
    }
    if (wind && g.node.size() == n) add_bones(m, g);
    meshes.push_back(m);
    return int(meshes.size()) - 1;
  }

  // The wind skin's weights (the glTF skin's, render/io/export_wind.h) as one bone per joint used.
  void add_bones(aiMesh* m, const geometry& g) {
    const wind_skin& skin = wind->skin;
    std::vector<std::vector<aiVertexWeight>> per_joint(skin.joints.size());
    for (size_t v = 0; v < g.node.size(); ++v) {
      const uint32_t node = g.node[v];
      if (node >= skin.node_joints.size()) {
        per_joint[0].emplace_back(unsigned(v), 1.0f);
        continue;
      }
      for (int c = 0; c < 4; ++c)
        if (skin.node_weights[node][c] > 0) per_joint[skin.node_joints[node][c]].emplace_back(unsigned(v), skin.node_weights[node][c]);
    }
    std::vector<aiBone*> bones;
    for (size_t j = 0; j < per_joint.size(); ++j) {
      if (per_joint[j].empty()) continue;
      auto* b = new aiBone;
      b->mName = aiString(joint_names[j]);
      const glm::vec3 p = skin.joints[j].pivot * fbx_units_per_metre;
      b->mOffsetMatrix = aiMatrix4x4(1, 0, 0, -p.x, 0, 1, 0, -p.y, 0, 0, 1, -p.z, 0, 0, 0, 1);   // rest: a translation
      b->mNumWeights = unsigned(per_joint[j].size());
      b->mWeights = copy_array(per_joint[j]);
      bones.push_back(b);
    }
    m->mNumBones = unsigned(bones.size());
    m->mBones = copy_array(bones);
  }

  // One node per tree of `parts` under `parent`, named `name` (a forest's trees get "_tree_<n>"
  // before the level suffix), holding the bark and every leaf material's mesh.
  bool add_trees(aiNode* parent, const std::vector<tree_part>& parts, const std::string& tree, const std::string& suffix,
                 size_t& triangles) {
    std::vector<aiNode*> kids;
    for (size_t k = 0; k < parts.size(); ++k) {
      const std::string name = parts.size() > 1 ? tree + "_tree_" + std::to_string(k + 1) + suffix : tree + suffix;
      std::vector<unsigned> ids;
      auto add = [&](const geometry& g, int material, const std::string& what) {
        if (g.empty()) return true;
        const int id = add_mesh(g, material, name + "_" + what);
        if (id < 0) return false;
        ids.push_back(unsigned(id));
        triangles += g.index.size() / 3;
        return true;
      };
      if (!part_bark(parts[k], add)) return false;
      for (int slot = 0; slot < leaf_slots; ++slot)
        if (!parts[k].leaves[size_t(slot)].empty() && !add(parts[k].leaves[size_t(slot)], leaf_material(slot), src.leaf_name(slot)))
          return false;
      auto* node = new aiNode(name);
      node->mNumMeshes = unsigned(ids.size());
      node->mMeshes = copy_array(ids);
      kids.push_back(node);
    }
    add_children(parent, kids);
    return true;
  }
  template <class F>
  bool part_bark(const tree_part& p, F& add) {
    return p.bark.empty() || add(p.bark, bark_material(), "bark");
  }

  // The joints as a node chain under the root (translations from each parent's pivot), and the
  // loop as one animation of their rotations.
  void add_wind(aiScene& scene) {
    const auto& joints = wind->skin.joints;
    std::vector<aiNode*> nodes(joints.size());
    for (size_t k = 0; k < joints.size(); ++k) {
      nodes[k] = new aiNode(joint_names[k]);
      const glm::vec3 parent = joints[k].parent >= 0 ? joints[size_t(joints[k].parent)].pivot : glm::vec3(0);
      const glm::vec3 t = (joints[k].pivot - parent) * fbx_units_per_metre;
      aiMatrix4x4::Translation(aiVector3D(t.x, t.y, t.z), nodes[k]->mTransformation);
    }
    for (size_t k = 1; k < joints.size(); ++k) add_children(nodes[size_t(joints[k].parent)], {nodes[k]});
    add_children(scene.mRootNode, {nodes[0]});
    auto* anim = new aiAnimation;
    anim->mName = aiString("wind");
    // Key times in seconds: assimp's FBX writer takes mTime as seconds whatever mTicksPerSecond says.
    anim->mTicksPerSecond = 1;
    anim->mDuration = double(wind->seconds);
    std::vector<aiNodeAnim*> channels;
    for (size_t k = 1; k < joints.size(); ++k) {
      auto* c = new aiNodeAnim;
      c->mNodeName = aiString(joint_names[k]);
      const size_t n = wind->times.size();
      c->mNumRotationKeys = unsigned(n);
      c->mRotationKeys = new aiQuatKey[n];
      for (size_t i = 0; i < n; ++i) {
        const glm::quat& q = wind->keys[k][i];
        c->mRotationKeys[i] = aiQuatKey(double(wind->times[i]), aiQuaternion(q.w, q.x, q.y, q.z));
      }
      aiVector3D t, s(1, 1, 1);
      aiQuaternion r;
      nodes[k]->mTransformation.Decompose(s, r, t);
      c->mNumPositionKeys = 1;
      c->mPositionKeys = new aiVectorKey[1]{aiVectorKey(0, t)};
      c->mNumScalingKeys = 1;
      c->mScalingKeys = new aiVectorKey[1]{aiVectorKey(0, aiVector3D(1, 1, 1))};
      channels.push_back(c);
    }
    anim->mNumChannels = unsigned(channels.size());
    anim->mChannels = copy_array(channels);
    scene.mNumAnimations = 1;
    scene.mAnimations = new aiAnimation*[1]{anim};
  }
};

}  // namespace

export_result export_fbx(const tree_skeleton& t, const tree_mesh& m, const export_info& info, const std::string& path,
                         const export_options& o) {
  export_result r;
  const std::string stem = stem_path(path), stem_name = file_name(stem), tree = lod_tree_name(stem_name);
  material_source src(o, r.warning);
  src.without_vertex_colors();   // FBX importers do not multiply vertex colours into materials
  fbx_builder b{src, stem_name};
  auto scene = std::make_unique<aiScene>();
  scene->mRootNode = new aiNode(tree + "_root");
  const int final_step = std::max(t.steps, 0);
  wind_bake wind;
  if (!o.lods.empty()) {
    if (o.wind_seconds > 0) r.warning = "wind: --lods exports carry no wind skin; export without --lods for the animation";
    // LOD0 is the mesh given, LOD1.. the levels: each "<tree>_LOD<k>" under one "<tree>" node.
    auto* group = new aiNode(tree);
    std::vector<const tree_mesh*> levels{&m};
    for (const export_lod_level& l : o.lods)
      if (l.mesh) levels.push_back(l.mesh);
    for (size_t k = 0; k < levels.size(); ++k) {
      size_t tris = 0;
      const auto parts = split_parts(t, *levels[k], final_step, true, src.one_leaf_material(), src.leaf_looks(), src.bark_colors());
      if (!b.add_trees(group, parts, tree, "_LOD" + std::to_string(k), tris)) {
        r.error = src.error;
        return r;
      }
      if (k == 0) r.triangles = tris;
    }
    add_children(scene->mRootNode, {group});
  } else {
    const int s = o.step < 0 ? final_step : std::min(o.step, final_step);
    step_view v;
    view_at(v, t, m, o.mesh, s);
    if (o.wind_seconds > 0) {
      wind = bake_wind(*v.skeleton, o.wind, o.wind_seconds);
      b.wind = &wind;
      for (const wind_joint& j : wind.skin.joints) {
        const size_t k = b.joint_names.size();
        b.joint_names.push_back(j.kind == 0 ? "wind_root" : j.kind == 1 ? "trunk_" + std::to_string(k) : "branch_" + std::to_string(j.branch));
      }
      r.warning += (r.warning.empty() ? "" : "\n") + wind.note;
    }
    const auto parts = split_parts(*v.skeleton, *v.mesh, s, true, src.one_leaf_material(), src.leaf_looks(), src.bark_colors());
    if (!b.add_trees(scene->mRootNode, parts, tree, "", r.triangles)) {
      r.error = src.error;
      return r;
    }
    if (b.wind) b.add_wind(*scene);
  }
  if (cancelled(o)) { r.error = "export cancelled"; return r; }
  scene->mNumMeshes = unsigned(b.meshes.size());
  scene->mMeshes = copy_array(b.meshes);
  scene->mNumMaterials = unsigned(b.materials.size());
  scene->mMaterials = copy_array(b.materials);
  if (scene->mNumMaterials == 0) {   // an empty tree still gets a valid file
    scene->mNumMaterials = 1;
    scene->mMaterials = new aiMaterial*[1]{new aiMaterial};
  }
  scene->mMetaData = aiMetadata::Alloc(2);
  scene->mMetaData->Set(0, "generator", aiString("Sylva " + info.generator));
  scene->mMetaData->Set(1, "seed", aiString(std::to_string(info.seed)));

  Assimp::Exporter exporter;
  const aiExportDataBlob* blob = exporter.ExportToBlob(scene.get(), "fbx");
  if (!blob) {
    r.error = "cannot export " + path + ": assimp's FBX writer failed: " + exporter.GetErrorString();
    return r;
  }
  std::vector<std::pair<std::string, std::string>> files;
  const std::string dir = std::filesystem::path(path).parent_path().string();
  for (auto& [name, bytes] : b.files) files.emplace_back((std::filesystem::path(dir) / name).string(), std::move(bytes));
  std::string fbx(static_cast<const char*>(blob->data), blob->size);
  // assimp 5.2 leaves the null record out under some records (FBXHeaderExtension's
  // CreationTimeStamp), which Blender's importer refuses: the records are written again, each
  // closed. With levels, the "<tree>" node becomes an FBX LOD group (assimp cannot write one), its
  // thresholds the screen sizes (percent of the view's height) down to which LOD0..LOD2 show.
  fbx::document doc;
  if (std::string why = fbx::parse(fbx, doc); !why.empty()) {
    if (!o.lods.empty()) r.warning += std::string(r.warning.empty() ? "" : "\n") + "no FBX LOD group: assimp's file: " + why;
  } else {
    if (!o.lods.empty()) {
      std::vector<double> thresholds{100.0 * double(o.lod0_coverage)};
      for (size_t k = 0; k + 1 < o.lods.size(); ++k) thresholds.push_back(100.0 * double(o.lods[k].coverage));
      if (std::string why = fbx::make_lod_group(doc, tree, thresholds); !why.empty())
        r.warning += std::string(r.warning.empty() ? "" : "\n") + "no FBX LOD group: " + why;
    }
    fbx = fbx::write(doc);
  }
  files.emplace_back(path, std::move(fbx));
  r.bytes = files.back().second.size();
  if (o.dry_run) return r;
  r.error = write_all(files, r);
  return r;
}

}  // namespace sylva::export_internal
