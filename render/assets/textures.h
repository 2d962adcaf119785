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

// ---- Archetype texture sets -------------------------------------------------------
// Each is generated deterministically from (archetype, size, seed) and cached for the life of the
// process: the first call makes it, later calls return the same object (thread-safe; different
// archetypes can be made in parallel). size is clamped to 8..4096; the renderer uses 512.

// A leaf card: blade in the square, petiole at the bottom edge centre (skeleton.h's leaf frame).
// The card is a square of side = leaf size, so a compound leaf, a needle tuft or a twig with its
// leaves fills one card. Texels outside the cut-out keep the blade colour (alpha 0).
struct leaf_texture_set {
  image color;       // RGBA (sRGB): alpha is the cut-out; colour carries veins, edge darkening
  image normal;      // RGB tangent-space normal map (+Z out of the blade, +Y up the image)
  image thickness;   // RGB grey: white where the blade is thin (lets most light through)
};
struct bark_texture_set {
  image color;       // RGB (sRGB), tiles in both directions: x around the branch, y along it
  image normal;      // RGB tangent-space normal map (+Z out of the bark, +Y up the image)
  image roughness;   // RGB (glTF metallicRoughness layout): R = G = roughness, B = metalness = 0
};
const leaf_texture_set& leaf_archetype_textures(leaf_archetype a, int size = 512, uint64_t seed = 1);
const bark_texture_set& bark_archetype_textures(bark_archetype a, int size = 512, uint64_t seed = 1);
// The same sets made afresh, without the cache (benchmarks, tests).
leaf_texture_set make_leaf_archetype_textures(leaf_archetype a, int size = 512, uint64_t seed = 1);
bark_texture_set make_bark_archetype_textures(bark_archetype a, int size = 512, uint64_t seed = 1);
// Fills the cache with every leaf and bark set on `threads` threads (deterministic: each set
// depends only on its own key).
void prepare_archetype_textures(int size = 512, uint64_t seed = 1, int threads = 2);
// Makes every leaf and bark set uncached on `threads` threads and returns their total bytes (the timing in
// `sylva textures --bench`).
size_t make_all_archetype_textures(int size = 512, uint64_t seed = 1, int threads = 2);

// The albedo a tint gives a procedural texture, the same formula in the renderer's shaders and in
// every export (which bakes it into the PNG), so exports look like the viewport:
//
//   albedo_linear = min(1, texture_tint_gain * tint_linear * srgb_to_linear(texel))   per channel
//
// with texture_tint_gain = 1: a plain multiply, written back as sRGB bytes (alpha untouched). A
// white texel shows the tint itself. The procedural leaves are a pale, low-chroma mid green
// (linear ~0.45), so the tint sets the hue and a leaf's albedo is a little under half its tint;
// the procedural barks are light where the bark is lit and dark in its furrows and scars.
// In GLSL, with the texture sampled from an sRGB format: min(vec3(1.0), TINT_GAIN * tint * tex.rgb)
// (render/gl/renderer.cpp defines TINT_GAIN from this constant).
inline constexpr float texture_tint_gain = 1.0f;
image tinted_texture(const image& color, const glm::vec3& tint_linear);

// A user's texture file for the renderer: PNG (or another format stb reads), checked before it is
// decoded: a missing file, a file over max_texture_file_bytes, an image wider or taller than
// max_texture_pixels, or a corrupt one gives "" only on success and otherwise the reason.
// Non-power-of-two sizes are fine (OpenGL 3.3 mipmaps them).
inline constexpr size_t max_texture_file_bytes = size_t(64) << 20;
inline constexpr int max_texture_pixels = 8192;
std::string load_user_texture(const std::string& path, image& out);
// The same checks without the path in the message: read_user_texture reads the file (and hands its
// bytes back when asked); decode_user_texture checks and decodes bytes already read.
std::string read_user_texture(const std::string& path, image& out, std::string* bytes = nullptr);
std::string decode_user_texture(std::string_view bytes, image& out);

// PNG through stb. Each returns "" or the error.
std::string encode_png(const image& img, std::string& out);
std::string encode_jpeg(const image& img, int quality, std::string& out);  // baseline JPEG, alpha dropped
std::string decode_png(std::string_view bytes, image& out);  // always RGBA (any format stb reads)
std::string load_png(const std::string& path, image& out);
std::string save_png(const image& img, const std::string& path);  // atomic (write_file_atomic)

}  // namespace sylva
