// Procedural bark and leaf textures made on the CPU (deterministic), and PNG I/O for user textures.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

#include "generators/archetypes.h"

namespace sylva {

// 8-bit image, rows top to bottom (glTF's UV origin is the top-left corner).
struct image {
  int width = 0, height = 0;
  int channels = 4;             // 3 (RGB) or 4 (RGBA)
  std::vector<uint8_t> pixels;  // width * height * channels
};

struct texture_set {
  image bark_color;             // RGB, tiles in both directions: x around the branch, y along it
  image bark_normal;            // RGB tangent-space normal map (+Z out of the surface)
  std::array<image, 4> leaf;    // RGBA: alpha is the blade's outline; petiole at the bottom edge
};

// Bark: fissured ridges running along the branch, from one periodic height field.
image make_bark_color(int size, uint64_t seed);
image make_bark_normal(int size, uint64_t seed);
// Leaf variant 0..3: elliptic, lanceolate, ovate, lobed.
image make_leaf_texture(int size, int variant, uint64_t seed);
texture_set make_textures(int bark_size = 256, int leaf_size = 128, uint64_t seed = 1);

// The four leaf textures in a 2x2 atlas; leaf variant k sits in cell (k % 2, k / 2).
image make_leaf_atlas(const std::array<image, 4>& leaves);
// UV rectangle of atlas cell k: {u0, v0, u1, v1}.
std::array<float, 4> leaf_atlas_cell(int k);

// ---- Archetype texture sets (issue 11) -------------------------------------------------------
// Each is generated deterministically from (archetype, size, seed) and cached for the life of the
// process: the first call makes it, later calls return the same object (thread-safe).

// A leaf card: blade in the square, petiole at the bottom edge centre (skeleton.h's leaf frame).
struct leaf_texture_set {
  image color;       // RGBA (sRGB): alpha is the cut-out; colour carries veins, edge darkening
  image normal;      // RGB tangent-space normal map (+Z out of the blade, +Y up the image)
  image thickness;   // RGB grey: white where the blade is thin (lets most light through)
};
struct bark_texture_set {
  image color;       // RGB (sRGB), tiles in both directions: x around the branch, y along it
  image normal;      // RGB tangent-space normal map
  image roughness;   // RGB grey (glTF metallicRoughness: G is roughness, B metalness = 0)
};
const leaf_texture_set& leaf_archetype_textures(leaf_archetype a, int size = 512, uint64_t seed = 1);
const bark_texture_set& bark_archetype_textures(bark_archetype a, int size = 512, uint64_t seed = 1);

// The albedo a tint gives a procedural texture, the same formula in the renderer's shaders and in
// every export (which bakes it into the PNG), so exports look like the viewport.
image tinted_texture(const image& color, const glm::vec3& tint_linear);

// PNG through stb. Each returns "" or the error.
std::string encode_png(const image& img, std::string& out);
std::string decode_png(std::string_view bytes, image& out);  // always RGBA
std::string load_png(const std::string& path, image& out);
std::string save_png(const image& img, const std::string& path);  // atomic (write_file_atomic)

}  // namespace sylva
