// Compact exports through meshoptimizer: vertex-cache and vertex-fetch order for every exported
// primitive, EXT_meshopt_compression of a glTF's buffer views, and JPEG for opaque textures.
#include "render/io/export_internal.h"

#include <algorithm>
#include <cstring>
#include <map>
#include <numeric>

#include <meshoptimizer.h>

namespace sylva::export_internal {

namespace {

template <class T>
void remap(std::vector<T>& v, const std::vector<unsigned>& order, size_t unique) {
  if (v.empty()) return;
  std::vector<T> out(unique);
  meshopt_remapVertexBuffer(out.data(), v.data(), v.size(), sizeof(T), order.data());
  v = std::move(out);
}

constexpr int gl_byte = 5120, gl_ubyte = 5121, gl_short = 5122, gl_ushort = 5123;
constexpr int element_array_buffer = 34963;

size_t component_bytes(int type) {
  switch (type) {
    case gl_byte: case gl_ubyte: return 1;
    case gl_short: case gl_ushort: return 2;
    default: return 4;
  }
}
size_t components(const std::string& type) {
  if (type == "SCALAR") return 1;
  if (type == "VEC2") return 2;
  if (type == "VEC3") return 3;
  if (type == "VEC4" || type == "MAT2") return 4;
  if (type == "MAT3") return 9;
  return 16;
}

}  // namespace

// Triangles reordered for the post-transform vertex cache (Forsyth-style, meshoptimizer's
// optimizeVertexCache), then vertices renumbered in first-use order (optimizeVertexFetch), so the
// GPU fetches and a compressor sees them in the order the triangles use them. The triangle set is
// unchanged: each triangle keeps its corners and their winding.
void optimize_geometry(geometry& g) {
  const size_t nv = g.position.size();
  if (g.index.size() < 3 || nv == 0) return;
  std::vector<unsigned> idx(g.index.size());
  meshopt_optimizeVertexCache(idx.data(), g.index.data(), g.index.size(), nv);
  // Separate quads (leaf cards) gain nothing from reordering (every order misses each vertex
  // once, and a card's vertices are already together): they keep their own order, card by card
  // along the branches, corner by corner, unless the optimiser lowers the cache misses.
  const float before = meshopt_analyzeVertexCache(g.index.data(), g.index.size(), nv, 16, 0, 0).acmr;
  const float after = meshopt_analyzeVertexCache(idx.data(), idx.size(), nv, 16, 0, 0).acmr;
  if (after >= before * 0.999f) return;
  std::vector<unsigned> order(nv);
  const size_t unique = meshopt_optimizeVertexFetchRemap(order.data(), idx.data(), idx.size(), nv);
  meshopt_remapIndexBuffer(g.index.data(), idx.data(), idx.size(), order.data());
  remap(g.position, order, unique);
  remap(g.normal, order, unique);
  remap(g.uv, order, unique);
  remap(g.tangent, order, unique);
  remap(g.color, order, unique);
  remap(g.node, order, unique);
}

void use_extension(json& j, const char* name, bool required) {
  for (const char* list : {"extensionsUsed", "extensionsRequired"}) {
    if (list[10] == 'R' && !required) continue;
    json& used = j[list];
    if (!used.is_array()) used = json::array();
    if (std::find(used.begin(), used.end(), name) == used.end()) used.push_back(name);
  }
}

// EXT_meshopt_compression (the extension's version-0 vertex codec and version-1 index codec): every
// buffer view whose elements it can encode (vertex attributes, indices of triangle lists,
// animation keys, inverse bind matrices, instance transforms) moves into the compressed buffer 0;
// images stay as they are. Buffer 1 is the uncompressed layout without data (a "fallback"
// buffer, never loaded), where the views keep their offsets. Returns the new binary buffer.
std::string meshopt_compress(json& j, const std::string& bin) {
  // Each view's element size and count, from the accessors that read it.
  std::map<size_t, std::pair<size_t, int>> elem;   // view -> (bytes per element, component type)
  for (const json& a : j["accessors"]) {
    if (!a.contains("bufferView")) continue;
    const size_t view = a["bufferView"].get<size_t>();
    size_t bytes = component_bytes(a["componentType"].get<int>()) * components(a["type"].get<std::string>());
    const json& v = j["bufferViews"][view];
    if (v.contains("byteStride")) bytes = v["byteStride"].get<size_t>();
    auto [it, fresh] = elem.emplace(view, std::make_pair(bytes, a["componentType"].get<int>()));
    if (!fresh && it->second.first != bytes) it->second.first = 0;   // mixed element sizes: leave it
  }
  // Normals and tangents (8-bit, 4 bytes a vertex) go through the octahedral filter: two
  // components and a constant byte compress better than three (meshoptimizer's encodeFilterOct).
  std::map<size_t, bool> oct;
  for (const json& mesh : j["meshes"])
    for (const json& p : mesh["primitives"])
      for (const char* a : {"NORMAL", "TANGENT"})
        if (p["attributes"].contains(a)) {
          const json& acc = j["accessors"][p["attributes"][a].get<size_t>()];
          if (acc["componentType"] == gl_byte && acc.value("normalized", false) && acc.contains("bufferView"))
            oct[acc["bufferView"].get<size_t>()] = true;
        }
  meshopt_encodeVertexVersion(0);
  meshopt_encodeIndexVersion(1);
  std::string out;
  auto align = [&] { while (out.size() % 4) out.push_back('\0'); };
  for (size_t k = 0; k < j["bufferViews"].size(); ++k) {
    json& v = j["bufferViews"][k];
    const size_t offset = v["byteOffset"].get<size_t>(), length = v["byteLength"].get<size_t>();
    const unsigned char* data = reinterpret_cast<const unsigned char*>(bin.data()) + offset;
    const auto e = elem.find(k);
    std::string packed;
    json ext;
    if (e != elem.end() && e->second.first > 0) {
      const size_t stride = e->second.first;
      const bool indices = v.value("target", 0) == element_array_buffer;
      if (indices && (stride == 2 || stride == 4) && length % (3 * stride) == 0) {
        const size_t count = length / stride;
        std::vector<unsigned> idx(count);
        size_t top = 0;
        for (size_t i = 0; i < count; ++i) {
          if (stride == 2) { uint16_t x; std::memcpy(&x, data + 2 * i, 2); idx[i] = x; }
          else std::memcpy(&idx[i], data + 4 * i, 4);
          top = std::max<size_t>(top, idx[i]);
        }
        packed.resize(meshopt_encodeIndexBufferBound(count, top + 1));
        packed.resize(meshopt_encodeIndexBuffer(reinterpret_cast<unsigned char*>(packed.data()), packed.size(), idx.data(), count));
        ext = {{"byteStride", stride}, {"count", count}, {"mode", "TRIANGLES"}};
      } else if (!indices && stride % 4 == 0 && stride <= 256 && length % stride == 0) {
        const size_t count = length / stride;
        std::vector<unsigned char> filtered;
        const bool octahedral = oct.count(k) && stride == 4;
        if (octahedral) {
          std::vector<float> f(count * 4);
          for (size_t i = 0; i < count * 4; ++i) f[i] = std::max(float(int8_t(data[i])) / 127.0f, -1.0f);
          filtered.resize(count * 4);
          meshopt_encodeFilterOct(filtered.data(), count, 4, 8, f.data());
        }
        const unsigned char* src = octahedral ? filtered.data() : data;
        packed.resize(meshopt_encodeVertexBufferBound(count, stride));
        packed.resize(meshopt_encodeVertexBuffer(reinterpret_cast<unsigned char*>(packed.data()), packed.size(), src, count, stride));
        ext = {{"byteStride", stride}, {"count", count}, {"mode", "ATTRIBUTES"}};
        if (octahedral) ext["filter"] = "OCTAHEDRAL";
      }
    }
    align();
    if (!packed.empty()) {
      ext["buffer"] = 0;
      ext["byteOffset"] = out.size();
      ext["byteLength"] = packed.size();
      out += packed;
      v["buffer"] = 1;   // the fallback keeps the original offset and length
      v["extensions"] = {{"EXT_meshopt_compression", ext}};
    } else {
      v["byteOffset"] = out.size();
      out.append(bin, offset, length);
    }
  }
  use_extension(j, "EXT_meshopt_compression", true);
  j["buffers"] = json::array({{{"byteLength", out.size()}},
                              {{"byteLength", bin.size()}, {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}}});
  return out;
}

// The image as JPEG when every pixel is opaque (quality 85, colour as stored: sRGB stays sRGB,
// normal and roughness maps stay linear); false when it has alpha or cannot be decoded.
bool jpeg_if_opaque(const std::string& png, std::string& jpeg) {
  image img;
  if (!decode_png(png, img).empty()) return false;
  image rgb{img.width, img.height, 3, {}};
  rgb.pixels.reserve(size_t(img.width) * size_t(img.height) * 3);
  for (size_t i = 0; i + 3 < img.pixels.size(); i += 4) {
    if (img.pixels[i + 3] != 255) return false;
    rgb.pixels.insert(rgb.pixels.end(), {img.pixels[i], img.pixels[i + 1], img.pixels[i + 2]});
  }
  return encode_jpeg(rgb, 85, jpeg).empty();
}

}  // namespace sylva::export_internal
