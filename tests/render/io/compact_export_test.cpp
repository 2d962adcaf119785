// Compact glTF (KHR_mesh_quantization + EXT_meshopt_compression, JPEG textures): decoded here with
// meshoptimizer's own decoder, the file holds the same triangles as the plain export, within the
// quantisation grid; every compact flavour passes the Khronos validator.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <glm/glm.hpp>
#include <meshoptimizer.h>
#include <nlohmann/json.hpp>

#include "tests/scratch_dir.h"
#include "render/io/export.h"
#include "render/io/preset.h"

using namespace sylva;
namespace fs = std::filesystem;
using json = nlohmann::json;

using sylva_test::slurp;

namespace {

struct scratch : sylva_test::scratch_dir {
  scratch() : scratch_dir("sylva_compact_test") {}
};

// A GLB read back: its JSON and every buffer view's bytes, EXT_meshopt_compression views decoded.
struct glb {
  json j;
  std::vector<std::string> views;
  explicit glb(const std::string& bytes) {
    uint32_t json_len = 0;
    std::memcpy(&json_len, bytes.data() + 12, 4);
    j = json::parse(bytes.substr(20, json_len));
    const std::string bin = bytes.substr(20 + json_len + 8);
    for (const json& v : j["bufferViews"]) {
      if (v.contains("extensions") && v["extensions"].contains("EXT_meshopt_compression")) {
        const json& e = v["extensions"]["EXT_meshopt_compression"];
        const size_t count = e["count"], stride = e["byteStride"];
        std::string out(count * stride, '\0');
        const auto* src = reinterpret_cast<const unsigned char*>(bin.data()) + e["byteOffset"].get<size_t>();
        const size_t len = e["byteLength"];
        int rc = e["mode"] == "TRIANGLES" ? meshopt_decodeIndexBuffer(out.data(), count, stride, src, len)
                                          : meshopt_decodeVertexBuffer(out.data(), count, stride, src, len);
        EXPECT_EQ(rc, 0) << "meshopt decode of a buffer view";
        if (e.value("filter", "NONE") == "OCTAHEDRAL") meshopt_decodeFilterOct(out.data(), count, stride);
        views.push_back(out);
      } else {
        views.push_back(bin.substr(v["byteOffset"].get<size_t>(), v["byteLength"].get<size_t>()));
      }
    }
  }
  // Element i of accessor a as floats (normalised integers mapped as glTF says).
  std::array<float, 4> get(const json& a, size_t i) const {
    const int type = a["componentType"];
    const size_t n = a["type"] == "SCALAR" ? 1 : a["type"] == "VEC2" ? 2 : a["type"] == "VEC3" ? 3 : 4;
    const size_t size = type == 5126 || type == 5125 ? 4 : type == 5122 || type == 5123 ? 2 : 1;
    const json& v = j["bufferViews"][a["bufferView"].get<size_t>()];
    const size_t stride = v.contains("byteStride") ? v["byteStride"].get<size_t>() : n * size;
    const char* p = views[a["bufferView"].get<size_t>()].data() + a.value("byteOffset", size_t(0)) + i * stride;
    const bool norm = a.value("normalized", false);
    std::array<float, 4> out{};
    for (size_t c = 0; c < n; ++c) {
      const char* q = p + c * size;
      float x = 0;
      if (type == 5126) std::memcpy(&x, q, 4);
      else if (type == 5125) { uint32_t u; std::memcpy(&u, q, 4); x = float(u); }
      else if (type == 5123) { uint16_t u; std::memcpy(&u, q, 2); x = norm ? u / 65535.0f : float(u); }
      else if (type == 5122) { int16_t u; std::memcpy(&u, q, 2); x = norm ? std::max(u / 32767.0f, -1.0f) : float(u); }
      else if (type == 5121) { uint8_t u = uint8_t(*q); x = norm ? u / 255.0f : float(u); }
      else { int8_t u = int8_t(*q); x = norm ? std::max(u / 127.0f, -1.0f) : float(u); }
      out[c] = x;
    }
    return out;
  }
};

// Every triangle of the scene's meshes, in world space: per axis the sorted centroid coordinates
// and the sorted areas (equal lists within the grid when the triangles are the same).
struct triangle_lists {
  std::array<std::vector<float>, 3> centroid;
  std::vector<float> area;
  std::vector<float> normal_length;
  size_t count() const { return area.size(); }
};

triangle_lists triangles_of(const glb& g) {
  triangle_lists out;
  for (const json& node : g.j["nodes"]) {
    if (!node.contains("mesh")) continue;
    glm::vec3 t(0), s(1);
    if (node.contains("translation")) t = {node["translation"][0], node["translation"][1], node["translation"][2]};
    if (node.contains("scale")) s = {node["scale"][0], node["scale"][1], node["scale"][2]};
    for (const json& prim : g.j["meshes"][node["mesh"].get<size_t>()]["primitives"]) {
      const json& pos = g.j["accessors"][prim["attributes"]["POSITION"].get<size_t>()];
      const json& nrm = g.j["accessors"][prim["attributes"]["NORMAL"].get<size_t>()];
      const json& idx = g.j["accessors"][prim["indices"].get<size_t>()];
      auto world = [&](size_t v) {
        const auto p = g.get(pos, v);
        return t + s * glm::vec3(p[0], p[1], p[2]);
      };
      for (size_t k = 0; k + 2 < idx["count"].get<size_t>(); k += 3) {
        glm::vec3 c[3];
        for (int e = 0; e < 3; ++e) c[e] = world(size_t(g.get(idx, k + size_t(e))[0]));
        const glm::vec3 m = (c[0] + c[1] + c[2]) / 3.0f;
        for (int a = 0; a < 3; ++a) out.centroid[size_t(a)].push_back(m[a]);
        out.area.push_back(0.5f * glm::length(glm::cross(c[1] - c[0], c[2] - c[0])));
      }
      for (size_t v = 0; v < nrm["count"].get<size_t>(); ++v) {
        const auto n = g.get(nrm, v);
        out.normal_length.push_back(glm::length(glm::vec3(n[0], n[1], n[2])));
      }
    }
  }
  for (auto& c : out.centroid) std::sort(c.begin(), c.end());
  std::sort(out.area.begin(), out.area.end());
  return out;
}

struct tree_case {
  preset p;
  tree_skeleton t;
  tree_mesh m;
  explicit tree_case(const char* name) {
    EXPECT_TRUE(load_preset_file(std::string(SYLVA_SOURCE_DIR) + "/presets/" + name + ".json", p).ok);
    t = grow(p.spec, grow_options{});
    m = mesh_tree(t, p.mesh, p.spec.seed);
  }
  export_result write(const std::string& path, bool compact, bool instancing = false, bool animation = false) const {
    export_options o;
    o.mesh = p.mesh;
    o.texture_size = 64;
    apply_render_params(o, p.render);
    o.compact = compact;
    o.gltf_instancing = instancing;
    o.growth_animation = animation;
    return export_tree(t, m, {"test", p.spec.seed}, path, o);
  }
};

}  // namespace

TEST(CompactExport, DecodesToTheSameTrianglesWithinTheGrid) {
  scratch dir;
  tree_case c("lsystem_honda_a");
  ASSERT_EQ(c.write(dir / "plain.glb", false).error, "");
  ASSERT_EQ(c.write(dir / "compact.glb", true).error, "");
  const glb plain(slurp(dir / "plain.glb")), compact(slurp(dir / "compact.glb"));
  for (const char* ext : {"KHR_mesh_quantization", "EXT_meshopt_compression"}) {
    const json& req = compact.j["extensionsRequired"];
    EXPECT_NE(std::find(req.begin(), req.end(), ext), req.end()) << ext;
  }
  // Vertex data is compressed: no POSITION reads floats from an uncompressed view.
  for (const json& mesh : compact.j["meshes"])
    for (const json& prim : mesh["primitives"]) {
      const json& pos = compact.j["accessors"][prim["attributes"]["POSITION"].get<size_t>()];
      EXPECT_TRUE(compact.j["bufferViews"][pos["bufferView"].get<size_t>()]["extensions"].contains("EXT_meshopt_compression"));
      EXPECT_EQ(pos["componentType"], 5123) << "16-bit positions";
    }
  const triangle_lists a = triangles_of(plain), b = triangles_of(compact);
  ASSERT_GT(a.count(), size_t(1000));
  ASSERT_EQ(a.count(), b.count());
  // The coarsest grid: leaves take 16383 steps over their box's longest side.
  float extent = 0;
  for (int k = 0; k < 3; ++k) extent = std::max(extent, a.centroid[size_t(k)].back() - a.centroid[size_t(k)].front());
  const float tol = 2.0f * extent / 16383.0f;
  for (int k = 0; k < 3; ++k)
    for (size_t i = 0; i < a.count(); ++i)
      ASSERT_NEAR(a.centroid[size_t(k)][i], b.centroid[size_t(k)][i], tol) << "axis " << k << ", triangle " << i;
  for (size_t i = 0; i < a.count(); i += 7) ASSERT_NEAR(a.area[i], b.area[i], 4 * tol * std::sqrt(a.area.back()) + 1e-6f);
  for (float l : b.normal_length) ASSERT_NEAR(l, 1.0f, 0.02f);
  // Opaque maps become JPEG, the leaves' cut-out keeps its PNG alpha.
  int jpeg = 0, png = 0;
  for (const json& im : compact.j["images"]) (im["mimeType"] == "image/jpeg" ? jpeg : png)++;
  EXPECT_GE(jpeg, 3);
  EXPECT_GE(png, 1);
  EXPECT_LT(fs::file_size(dir / "compact.glb") * 3, fs::file_size(dir / "plain.glb"));
}

TEST(CompactExport, KhronosValidatorReportsNoErrorsOrWarnings) {
  if (std::system("command -v node >/dev/null 2>&1 && command -v npm >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "node/npm not installed (scripts/install-deps.sh installs them)";
  const std::string src = SYLVA_SOURCE_DIR;
  ASSERT_EQ(std::system(("bash " + src + "/scripts/install-gltf-validator.sh").c_str()), 0);
  scratch dir;
  tree_case c("lsystem_honda_a");
  ASSERT_EQ(c.write(dir / "c.glb", true).error, "");
  ASSERT_EQ(c.write(dir / "c.gltf", true).error, "");
  ASSERT_EQ(c.write(dir / "inst.glb", true, true).error, "");
  ASSERT_EQ(c.write(dir / "anim.glb", true, false, true).error, "");
  EXPECT_TRUE(fs::exists(dir / "c_bark_furrowed.jpg") || fs::exists(dir / "c.bin"));
  const std::string cmd = "node " + src + "/scripts/validate-gltf.js " + (dir / "c.glb") + " " + (dir / "c.gltf") + " " +
                          (dir / "inst.glb") + " " + (dir / "anim.glb") + " > " + (dir / "report.txt") + " 2>&1";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << slurp(dir / "report.txt");
}
