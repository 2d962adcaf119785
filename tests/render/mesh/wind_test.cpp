// Wind on the CPU: per-node sway data, the skin's weights and joint cap, the seamless loop, the
// glTF skin + animation (re-read, and the Khronos validator) and the render-side parameters. The
// viewport's sway in pixels is tests/gl/wind_test.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>

#include <nlohmann/json.hpp>

#include "render/io/export.h"
#include "render/io/export_wind.h"
#include "render/io/preset.h"
#include "render/mesh/wind.h"
#include "tests/scratch_dir.h"
#include "tests/wind_tree.h"

using namespace sylva;
namespace fs = std::filesystem;

namespace {

using honda = sylva_test::honda_tree;
using sylva_test::blowing;

bool on_skeleton(const tree_skeleton& t, glm::vec3 p) {
  for (const glm::vec3& q : t.position)
    if (q == p) return true;
  return false;
}

// A GLB's JSON and BIN chunks.
struct glb {
  nlohmann::json j;
  std::string bin;
  explicit glb(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    std::string s((std::istreambuf_iterator<char>(f)), {});
    uint32_t len = 0;
    std::memcpy(&len, s.data() + 12, 4);
    j = nlohmann::json::parse(s.substr(20, len));
    uint32_t blen = 0;
    std::memcpy(&blen, s.data() + 20 + len, 4);
    bin = s.substr(28 + len, blen);
  }
  template <class T>
  std::vector<T> read(int accessor) const {
    const auto& a = j["accessors"][size_t(accessor)];
    const auto& v = j["bufferViews"][a["bufferView"].get<size_t>()];
    const size_t off = v.value("byteOffset", size_t(0)) + a.value("byteOffset", size_t(0));
    std::vector<T> out(a["count"].get<size_t>());
    std::memcpy(out.data(), bin.data() + off, out.size() * sizeof(T));
    return out;
  }
};

}  // namespace

TEST(Wind, RigPivotsLieOnTheSkeletonAndFollowTheHierarchy) {
  honda h(7);
  const wind_rig rig = build_wind_rig(h.t);
  ASSERT_EQ(rig.nodes.size(), h.t.size());
  size_t majors = 0, minors = 0;
  for (size_t i = 0; i < h.t.size(); ++i) {
    const wind_node& w = rig.nodes[i];
    if (h.t.order[i] == 0) {   // the trunk only bends
      EXPECT_EQ(w.major_amp, 0.0f) << i;
      EXPECT_EQ(w.minor_amp, 0.0f) << i;
      continue;
    }
    ASSERT_GE(rig.major[i], 0) << i;
    ++majors;
    EXPECT_EQ(h.t.order[size_t(rig.major[i])], 1) << i;
    EXPECT_TRUE(on_skeleton(h.t, w.major_pivot)) << i;
    // The major pivot is the trunk node the branch leaves from.
    EXPECT_EQ(h.t.order[size_t(h.t.parent[size_t(rig.major[i])])], 0) << i;
    EXPECT_GT(w.major_amp, 0.0f);
    EXPECT_TRUE(std::isfinite(w.major_phase) && w.major_phase >= 0 && w.major_phase < 6.3f);
    EXPECT_GE(w.major_freq, 1.0f);
    if (h.t.order[i] >= 2) {
      ++minors;
      ASSERT_GE(rig.minor[i], 0) << i;
      EXPECT_TRUE(on_skeleton(h.t, w.minor_pivot)) << i;
      EXPECT_GT(w.minor_amp, 0.0f);
    } else {
      EXPECT_EQ(rig.minor[i], -1);
    }
  }
  EXPECT_GT(majors, 0u);
  EXPECT_GT(minors, 0u);
}

TEST(Wind, OffOrCalmMovesNothingAndOnMovesTheTips) {
  honda h(6);
  const wind_rig rig = build_wind_rig(h.t);
  wind_params off = blowing();
  off.enabled = false;
  const wind_motion still = make_wind_motion(off), moving = make_wind_motion(blowing());
  float most = 0;
  for (size_t i = 0; i < h.t.size(); ++i) {
    EXPECT_EQ(wind_displace(rig, still, uint32_t(i), h.t.position[i], 1.3f), h.t.position[i]);
    const glm::vec3 q = wind_displace(rig, moving, uint32_t(i), h.t.position[i], 1.3f);
    ASSERT_TRUE(std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z));
    most = std::max(most, glm::length(q - h.t.position[i]));
  }
  EXPECT_GT(most, 0.01f * rig.height);
  EXPECT_LT(most, 0.6f * rig.height);   // a sway, not a collapse
  // The root stays put.
  EXPECT_EQ(wind_displace(rig, moving, 0, h.t.position[0], 2.0f), h.t.position[0]);
}

TEST(Wind, ExtremesAreClampedWithAMessage) {
  wind_params w;
  EXPECT_EQ(clamp_wind(w), "");
  w.strength = 50;
  w.frequency = 0;
  w.gustiness = std::nanf("");
  const std::string msg = clamp_wind(w);
  EXPECT_NE(msg.find("strength 50 clamped to 2"), std::string::npos) << msg;
  EXPECT_NE(msg.find("frequency"), std::string::npos) << msg;
  EXPECT_EQ(w.strength, wind_strength_max);
  EXPECT_EQ(w.frequency, wind_frequency_min);
  EXPECT_EQ(w.gustiness, wind_params{}.gustiness);
  // Even a storm turns no branch past the cap.
  const wind_motion m = make_wind_motion(w);
  for (float t = 0; t < 5; t += 0.1f) EXPECT_LE(glm::length(wind_branch_rotation(m, 10.0f, 0.3f, 2.5f, t)), 0.8f + 1e-5f);
}

TEST(Wind, SkinWeightsSumToOneWithAtMost64Joints) {
  honda h(9);
  const wind_rig rig = build_wind_rig(h.t);
  for (int cap : {wind_max_joints, 8}) {
    const wind_skin s = build_wind_skin(h.t, rig, cap);
    ASSERT_LE(int(s.joints.size()), cap);
    ASSERT_GE(s.joints.size(), 2u);
    EXPECT_EQ(s.joints[0].parent, -1);
    for (size_t k = 1; k < s.joints.size(); ++k) {
      EXPECT_GE(s.joints[k].parent, 0);
      EXPECT_LT(size_t(s.joints[k].parent), k) << "parents come first";
      if (s.joints[k].kind == 2) {
        EXPECT_TRUE(on_skeleton(h.t, s.joints[k].pivot)) << k;
      }
    }
    ASSERT_EQ(s.node_weights.size(), h.t.size());
    for (size_t i = 0; i < h.t.size(); ++i) {
      const glm::vec4 w = s.node_weights[i];
      const glm::u8vec4 j = s.node_joints[i];
      EXPECT_NEAR(w.x + w.y + w.z + w.w, 1.0f, 1e-6f) << i;
      std::set<int> used;
      for (int c = 0; c < 4; ++c) {
        EXPECT_GE(w[c], 0.0f);
        EXPECT_LT(int(j[c]), int(s.joints.size()));
        if (w[c] > 0) {
          EXPECT_TRUE(used.insert(j[c]).second) << "joint twice in node " << i;
        } else {
          EXPECT_EQ(j[c], 0) << "unused slots name joint 0";
        }
      }
    }
    EXPECT_EQ(s.merged, s.candidates - int(s.joints.size()) + 1 + [&] {
      int trunk = 0;
      for (const wind_joint& jt : s.joints) trunk += jt.kind == 1;
      return trunk;
    }());
    if (cap == 8) {   // far more branches than joints: they merge, and the user is told
      EXPECT_GT(s.merged, 0);
      EXPECT_NE(s.message.find("at most 8 joints"), std::string::npos) << s.message;
    }
  }
}

TEST(Wind, QuantizedWeightsSumTo255) {
  for (glm::vec4 w : {glm::vec4(1, 0, 0, 0), glm::vec4(0.5f, 0.5f, 0, 0), glm::vec4(0.333f, 0.333f, 0.334f, 0),
                      glm::vec4(0.001f, 0.999f, 0, 0), glm::vec4(0.25f)}) {
    const glm::u8vec4 q = quantize_weights(w);
    EXPECT_EQ(int(q.x) + q.y + q.z + q.w, 255);
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(q[c] / 255.0f, w[c], 2.0f / 255.0f);
  }
}

TEST(Wind, BakedLoopIsSeamless) {
  honda h(7);
  const wind_bake b = bake_wind(h.t, blowing(), 3.0f);
  ASSERT_GE(b.times.size(), 3u);
  EXPECT_EQ(b.times.front(), 0.0f);
  EXPECT_EQ(b.times.back(), 3.0f);
  // Whole cycles per loop: the computed pose at the end equals the start (not just the copied key).
  for (size_t j = 0; j < b.skin.joints.size(); ++j) {
    const glm::quat a = wind_joint_rotation(b.skin, b.motion, j, 0.0f), z = wind_joint_rotation(b.skin, b.motion, j, 3.0f);
    EXPECT_NEAR(std::abs(glm::dot(a, z)), 1.0f, 1e-4f) << j;
    EXPECT_EQ(b.keys[j].front(), b.keys[j].back());
  }
  // And it moves in between.
  bool moved = false;
  for (size_t j = 1; j < b.skin.joints.size(); ++j) moved |= std::abs(glm::dot(b.keys[j][0], b.keys[j][b.times.size() / 2])) < 0.99999f;
  EXPECT_TRUE(moved);
  // Bad loop lengths are clamped with a note.
  EXPECT_NE(bake_wind(h.t, blowing(), 1000.0f).note.find("clamped to 60"), std::string::npos);
}

TEST(Wind, GlbCarriesASkinAndALoopingAnimation) {
  honda h(7);
  const sylva_test::scratch_dir scratch("sylva_wind_test");
  const fs::path& dir = scratch.dir;
  export_options o;
  o.mesh = h.p;
  o.texture_size = 64;
  o.wind = blowing();
  o.wind_seconds = 2.0f;
  const std::string path = (dir / "wind.glb").string();
  const export_result r = export_tree(h.t, h.m, {"lsystem", 1}, path, o);
  ASSERT_EQ(r.error, "");
  EXPECT_NE(r.warning.find("leaf flutter"), std::string::npos) << r.warning;
  const glb g(path);
  ASSERT_EQ(g.j["skins"].size(), 1u);
  const auto& joints = g.j["skins"][0]["joints"];
  EXPECT_LE(joints.size(), 64u);
  // Every mesh node is skinned, a scene root, without transforms; every primitive has weights.
  std::set<int> roots(g.j["scenes"][0]["nodes"].begin(), g.j["scenes"][0]["nodes"].end());
  int meshes = 0;
  for (size_t n = 0; n < g.j["nodes"].size(); ++n) {
    const auto& node = g.j["nodes"][n];
    if (!node.contains("mesh")) continue;
    ++meshes;
    EXPECT_EQ(node["skin"], 0);
    EXPECT_TRUE(roots.count(int(n)));
    for (const auto& prim : g.j["meshes"][node["mesh"].get<size_t>()]["primitives"]) {
      ASSERT_TRUE(prim["attributes"].contains("JOINTS_0"));
      const auto w = g.read<glm::u8vec4>(prim["attributes"]["WEIGHTS_0"]);   // normalised bytes
      const auto jj = g.read<glm::u8vec4>(prim["attributes"]["JOINTS_0"]);
      ASSERT_EQ(w.size(), jj.size());
      for (size_t v = 0; v < w.size(); ++v) {
        EXPECT_EQ(int(w[v].x) + w[v].y + w[v].z + w[v].w, 255);
        for (int c = 0; c < 4; ++c) {
          EXPECT_LT(size_t(jj[v][c]), joints.size());
          if (w[v][c] == 0) {
            EXPECT_EQ(jj[v][c], 0);
          }
        }
      }
    }
  }
  EXPECT_EQ(meshes, 2);   // bark and leaves
  ASSERT_EQ(g.j["animations"].size(), 1u);
  const auto& anim = g.j["animations"][0];
  EXPECT_EQ(anim["name"], "wind");
  EXPECT_EQ(anim["channels"].size(), joints.size() - 1);
  for (const auto& s : anim["samplers"]) {
    const auto t = g.read<float>(s["input"]);
    const auto q = g.read<glm::vec4>(s["output"]);
    EXPECT_EQ(t.front(), 0.0f);
    EXPECT_EQ(t.back(), 2.0f);
    EXPECT_EQ(q.front(), q.back()) << "first key == last key";
  }
  // Growth and wind together: a growth animation and a wind animation.
  o.growth_animation = true;
  const std::string both = (dir / "both.glb").string();
  ASSERT_EQ(export_tree(h.t, h.m, {"lsystem", 1}, both, o).error, "");
  const glb gb(both);
  ASSERT_EQ(gb.j["animations"].size(), 2u);
  EXPECT_EQ(gb.j["animations"][0]["name"], "growth");
  EXPECT_EQ(gb.j["animations"][1]["name"], "wind");
}

TEST(Wind, KhronosValidatorReportsNoErrorsOrWarnings) {
  if (std::system("command -v node >/dev/null 2>&1 && command -v npm >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "node/npm not installed (scripts/install-deps.sh installs them)";
  const std::string src = SYLVA_SOURCE_DIR;
  ASSERT_EQ(std::system(("bash " + src + "/scripts/install-gltf-validator.sh >/dev/null").c_str()), 0);
  honda h(8);
  const sylva_test::scratch_dir scratch("sylva_wind_val");
  const fs::path& dir = scratch.dir;
  export_options o;
  o.mesh = h.p;
  o.texture_size = 64;
  o.wind = blowing();
  o.wind_seconds = 4.0f;
  std::string files;
  auto add = [&](const std::string& name, const export_options& x) {
    ASSERT_EQ(export_tree(h.t, h.m, {"lsystem", 1}, (dir / name).string(), x).error, "") << name;
    files += " '" + (dir / name).string() + "'";
  };
  add("wind.glb", o);
  add("wind.gltf", o);
  export_options grow = o;
  grow.growth_animation = true;
  add("wind_grow.glb", grow);
  const int rc = std::system(("node '" + src + "/scripts/validate-gltf.js'" + files).c_str());
  EXPECT_EQ(rc, 0) << "the validator found errors or warnings (printed above)";
}

TEST(Wind, ParametersAreRenderSideAndSurviveAPresetRoundTrip) {
  preset p, q;
  const tree_spec spec = p.spec;
  const mesh_params mesh = p.mesh;
  ASSERT_EQ(set_preset_param(p, "render.wind=true"), "");
  ASSERT_EQ(set_preset_param(p, "render.wind_strength=1.5"), "");
  ASSERT_EQ(set_preset_param(p, "render.wind_direction=90"), "");
  ASSERT_EQ(set_preset_param(p, "render.leaf_flutter=0.2"), "");
  // The editor's worker is given the spec and the mesh settings only: these are unchanged, so
  // the tree is not regrown or re-meshed.
  EXPECT_TRUE(p.spec == spec);
  EXPECT_TRUE(p.mesh == mesh);
  EXPECT_TRUE(p.render.wind.enabled);
  EXPECT_EQ(p.render.wind.strength, 1.5f);
  const load_result r = load_preset_json(save_preset_json(p), q);
  ASSERT_EQ(r.error, "");
  EXPECT_TRUE(q.render.wind == p.render.wind);
  // A preset without the wind keys loads with the defaults; out of range is clamped with a warning.
  preset d;
  ASSERT_EQ(load_preset_json(R"({"render": {"wind_strength": 9}})", d).error, "");
  EXPECT_EQ(d.render.wind.strength, wind_strength_max);
  EXPECT_FALSE(d.render.wind.enabled);
}
