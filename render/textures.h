// Procedural bark and leaf textures made on the CPU (deterministic), and PNG I/O for user textures.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

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

// PNG through stb. Each returns "" or the error.
std::string encode_png(const image& img, std::string& out);
std::string decode_png(std::string_view bytes, image& out);  // always RGBA
std::string load_png(const std::string& path, image& out);
std::string save_png(const image& img, const std::string& path);  // atomic (write_file_atomic)

}  // namespace sylva
