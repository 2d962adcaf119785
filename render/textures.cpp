// Procedural textures: periodic value noise for bark, analytic leaf outlines; PNG via stb.
#include "render/textures.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include <stb_image.h>
#include <stb_image_write.h>

#include "render/files.h"

namespace sylva {
namespace {

float hash01(uint64_t x) {  // SplitMix64 finaliser (Steele et al. 2014) as a lattice hash
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return float((x ^ (x >> 31)) >> 40) * (1.0f / 16777216.0f);
}

// Value noise on a cells_x * cells_y lattice that wraps, so the texture tiles seamlessly.
float periodic_noise(float x, float y, int cells_x, int cells_y, uint64_t seed) {
  const float fx = x * float(cells_x), fy = y * float(cells_y);
  const int ix = int(std::floor(fx)), iy = int(std::floor(fy));
  const float tx = fx - float(ix), ty = fy - float(iy);
  auto at = [&](int i, int j) {
    const int wi = ((i % cells_x) + cells_x) % cells_x, wj = ((j % cells_y) + cells_y) % cells_y;
    return hash01(seed * 0x100000001B3ull + uint64_t(wj) * 65537u + uint64_t(wi));
  };
  const float sx = tx * tx * (3 - 2 * tx), sy = ty * ty * (3 - 2 * ty);
  const float a = at(ix, iy) + (at(ix + 1, iy) - at(ix, iy)) * sx;
  const float b = at(ix, iy + 1) + (at(ix + 1, iy + 1) - at(ix, iy + 1)) * sx;
  return a + (b - a) * sy;
}

// Bark height in [0,1]: ridges stretched along y (the branch), cut by darker fissures.
std::vector<float> bark_height(int n, uint64_t seed) {
  std::vector<float> h(size_t(n) * size_t(n));
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const float u = float(x) / float(n), v = float(y) / float(n);
      float f = 0, amp = 0.5f;
      int cx = 12, cy = 3;
      for (int o = 0; o < 4; ++o, amp *= 0.5f, cx *= 2, cy *= 2) f += amp * periodic_noise(u, v, cx, cy, seed + o);
      const float ridge = 1 - std::abs(2 * periodic_noise(u, v, 10, 2, seed + 17) - 1);  // crest lines
      h[size_t(y) * n + x] = std::clamp(0.55f * f / 0.9375f + 0.45f * ridge * ridge, 0.0f, 1.0f);
    }
  return h;
}

uint8_t to_byte(float v) { return uint8_t(std::clamp(v, 0.0f, 1.0f) * 255.0f + 0.5f); }

image bark_color_from(const std::vector<float>& h, int n, uint64_t seed) {
  image img{n, n, 3, std::vector<uint8_t>(size_t(n) * n * 3)};
  for (size_t k = 0; k < h.size(); ++k) {
    const float t = h[k], grain = 0.9f + 0.2f * hash01(seed * 31 + k);
    // Fissures dark and reddish, crests greyish: a generic broadleaf bark.
    img.pixels[k * 3 + 0] = to_byte((0.18f + 0.42f * t) * grain);
    img.pixels[k * 3 + 1] = to_byte((0.13f + 0.34f * t) * grain);
    img.pixels[k * 3 + 2] = to_byte((0.09f + 0.27f * t) * grain);
  }
  return img;
}

image bark_normal_from(const std::vector<float>& h, int n) {
  image img{n, n, 3, std::vector<uint8_t>(size_t(n) * n * 3)};
  const float strength = 4.0f;  // height units per texture width -> slope
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      auto H = [&](int i, int j) { return h[size_t((j + n) % n) * n + size_t((i + n) % n)]; };
      const float dx = (H(x + 1, y) - H(x - 1, y)) * 0.5f * strength, dy = (H(x, y + 1) - H(x, y - 1)) * 0.5f * strength;
      // Image rows grow downward while glTF's tangent-space +Y (green) points up the texture.
      float nx = -dx, ny = dy, nz = 1;
      const float len = std::sqrt(nx * nx + ny * ny + nz * nz);
      nx /= len, ny /= len, nz /= len;
      uint8_t* p = &img.pixels[(size_t(y) * n + x) * 3];
      p[0] = to_byte(nx * 0.5f + 0.5f);
      p[1] = to_byte(ny * 0.5f + 0.5f);
      p[2] = to_byte(nz * 0.5f + 0.5f);
    }
  return img;
}

}  // namespace

image make_bark_color(int size, uint64_t seed) {
  const int n = std::clamp(size, 4, 4096);
  return bark_color_from(bark_height(n, seed), n, seed);
}

image make_bark_normal(int size, uint64_t seed) {
  const int n = std::clamp(size, 4, 4096);
  return bark_normal_from(bark_height(n, seed), n);
}

image make_leaf_texture(int size, int variant, uint64_t seed) {
  const int n = std::clamp(size, 8, 4096);
  variant = ((variant % 4) + 4) % 4;
  image img{n, n, 4, std::vector<uint8_t>(size_t(n) * n * 4)};
  const float base[4][3] = {{0.20f, 0.42f, 0.10f}, {0.26f, 0.46f, 0.12f}, {0.17f, 0.36f, 0.09f}, {0.30f, 0.44f, 0.11f}};
  const float* c = base[variant];
  const float stem = 0.12f;  // lower share of the height: the petiole
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const float s = 1 - (float(y) + 0.5f) / float(n);      // 0 at the bottom edge (petiole), 1 at the tip
      const float w = (float(x) + 0.5f) / float(n) * 2 - 1;  // -1..1 across
      const float b = (s - stem) / (0.97f - stem);           // 0..1 along the blade
      float half = 0;
      if (b > 0 && b < 1) {
        const float pi = 3.14159265f;
        switch (variant) {
          case 0: half = 0.80f * std::pow(std::sin(pi * b), 0.8f); break;                      // elliptic
          case 1: half = 0.42f * std::sin(pi * b) * (1.2f - 0.4f * b); break;                  // lanceolate
          case 2: half = 0.90f * std::sin(pi * std::pow(b, 0.65f)) * (1 - 0.2f * b); break;   // ovate
          default: half = 0.85f * std::sin(pi * b) * (0.78f + 0.22f * std::cos(5 * pi * b)); break;  // lobed
        }
      }
      const bool blade = std::abs(w) < half * 0.96f, petiole = s < stem + 0.02f && std::abs(w) < 0.035f;
      const float vein = std::abs(w) < 0.025f ? 0.25f : (std::abs(std::fmod(b * 8 + std::abs(w) * 3, 1.0f) - 0.5f) < 0.04f ? 0.1f : 0);
      const float shade = 0.85f + 0.15f * (1 - std::abs(w)) + 0.08f * (hash01(seed * 977 + uint64_t(y) * n + x) - 0.5f) + vein;
      uint8_t* p = &img.pixels[(size_t(y) * n + x) * 4];
      p[0] = to_byte(c[0] * shade);
      p[1] = to_byte(c[1] * shade);
      p[2] = to_byte(c[2] * shade);
      p[3] = blade || petiole ? 255 : 0;  // outside keeps the leaf colour, so filtering adds no dark fringe
    }
  return img;
}

texture_set make_textures(int bark_size, int leaf_size, uint64_t seed) {
  texture_set t;
  const int n = std::clamp(bark_size, 4, 4096);
  const std::vector<float> h = bark_height(n, seed);  // one height field for both maps
  t.bark_color = bark_color_from(h, n, seed);
  t.bark_normal = bark_normal_from(h, n);
  for (int k = 0; k < 4; ++k) t.leaf[k] = make_leaf_texture(leaf_size, k, seed + uint64_t(k));
  return t;
}

image make_leaf_atlas(const std::array<image, 4>& leaves) {
  int n = 0;
  for (const image& l : leaves) n = std::max(n, l.width);
  image atlas{2 * n, 2 * n, 4, std::vector<uint8_t>(size_t(4) * n * n * 4, 0)};
  for (int k = 0; k < 4; ++k) {
    const image& l = leaves[k];
    const int ox = (k % 2) * n, oy = (k / 2) * n;
    for (int y = 0; y < std::min(l.height, n); ++y)
      for (int x = 0; x < std::min(l.width, n); ++x)
        for (int ch = 0; ch < 4; ++ch)
          atlas.pixels[(size_t(oy + y) * 2 * n + ox + x) * 4 + ch] =
              ch < l.channels ? l.pixels[(size_t(y) * l.width + x) * l.channels + ch] : 255;
  }
  return atlas;
}

std::array<float, 4> leaf_atlas_cell(int k) {
  k = ((k % 4) + 4) % 4;
  const float u0 = 0.5f * float(k % 2), v0 = 0.5f * float(k / 2);
  return {u0, v0, u0 + 0.5f, v0 + 0.5f};
}

std::string encode_png(const image& img, std::string& out) {
  out.clear();
  if (img.width <= 0 || img.height <= 0 || (img.channels != 3 && img.channels != 4) ||
      img.pixels.size() != size_t(img.width) * img.height * img.channels)
    return "cannot encode PNG: malformed image";
  auto sink = [](void* ctx, void* data, int size) { static_cast<std::string*>(ctx)->append(static_cast<const char*>(data), size_t(size)); };
  if (!stbi_write_png_to_func(sink, &out, img.width, img.height, img.channels, img.pixels.data(), img.width * img.channels))
    return "cannot encode PNG";
  return "";
}

std::string decode_png(std::string_view bytes, image& out) {
  int w = 0, h = 0, ch = 0;
  stbi_uc* data = stbi_load_from_memory(reinterpret_cast<const stbi_uc*>(bytes.data()), int(bytes.size()), &w, &h, &ch, 4);
  if (!data) return std::string("cannot decode image: ") + (stbi_failure_reason() ? stbi_failure_reason() : "unknown");
  out.width = w, out.height = h, out.channels = 4;
  out.pixels.assign(data, data + size_t(w) * h * 4);
  stbi_image_free(data);
  return "";
}

std::string load_png(const std::string& path, image& out) {
  std::string bytes;
  if (std::string err = read_file(path, bytes); !err.empty()) return err;
  const std::string err = decode_png(bytes, out);
  return err.empty() ? "" : path + ": " + err;
}

std::string load_user_texture(const std::string& path, image& out) {
  std::error_code ec;
  const auto bytes_on_disk = std::filesystem::file_size(path, ec);
  if (ec) return path + ": cannot read (" + ec.message() + ")";
  if (bytes_on_disk > max_texture_file_bytes)
    return path + ": file is " + std::to_string(bytes_on_disk >> 20) + " MB, over the " +
           std::to_string(max_texture_file_bytes >> 20) + " MB limit for textures";
  std::string bytes;
  if (std::string err = read_file(path, bytes); !err.empty()) return err;
  int w = 0, h = 0, ch = 0;
  if (!stbi_info_from_memory(reinterpret_cast<const stbi_uc*>(bytes.data()), int(bytes.size()), &w, &h, &ch))
    return path + ": not an image stb can read (" + (stbi_failure_reason() ? stbi_failure_reason() : "unknown") + ")";
  if (w > max_texture_pixels || h > max_texture_pixels)
    return path + ": " + std::to_string(w) + "x" + std::to_string(h) + " is larger than " +
           std::to_string(max_texture_pixels) + " px on a side";
  if (w < 1 || h < 1) return path + ": empty image";
  const std::string err = decode_png(bytes, out);
  return err.empty() ? "" : path + ": " + err;
}

std::string save_png(const image& img, const std::string& path) {
  std::string bytes;
  if (std::string err = encode_png(img, bytes); !err.empty()) return path + ": " + err;
  return write_file_atomic(path, bytes);
}

}  // namespace sylva
