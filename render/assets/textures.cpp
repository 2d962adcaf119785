// PNG I/O through stb and the checked loading of user textures (the procedural archetype sets are
// made in archetype_textures.cpp).
#include "render/assets/textures.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <limits>
#include <string>

#include <stb_image.h>
#include <stb_image_write.h>

#include "render/files.h"

namespace sylva {

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

std::string encode_jpeg(const image& img, int quality, std::string& out) {
  out.clear();
  if (img.width <= 0 || img.height <= 0 || (img.channels != 3 && img.channels != 4) ||
      img.pixels.size() != size_t(img.width) * img.height * img.channels)
    return "cannot encode JPEG: malformed image";
  auto sink = [](void* ctx, void* data, int size) { static_cast<std::string*>(ctx)->append(static_cast<const char*>(data), size_t(size)); };
  if (!stbi_write_jpg_to_func(sink, &out, img.width, img.height, img.channels, img.pixels.data(), std::clamp(quality, 1, 100)))
    return "cannot encode JPEG";
  return "";
}

namespace {

// Binary PGM/PPM (P5, P6: the PNM stb reads), checked before stb sees it: Debian's stb reads past
// the end of a 16-bit one whose pixels are cut short, so only 8-bit files whose pixels are all
// there go on. "" or why not; other formats pass.
std::string pnm_problem(std::string_view b) {
  if (b.size() < 2 || b[0] != 'P' || (b[1] != '5' && b[1] != '6')) return "";
  size_t at = 2;
  auto field = [&](uint64_t& v) {
    for (;;) {  // whitespace and # comments before each field
      while (at < b.size() && std::isspace(static_cast<unsigned char>(b[at]))) ++at;
      if (at < b.size() && b[at] == '#') {
        while (at < b.size() && b[at] != '\n' && b[at] != '\r') ++at;
        continue;
      }
      break;
    }
    const size_t start = at;
    v = 0;
    while (at < b.size() && at - start < 9 && b[at] >= '0' && b[at] <= '9') v = v * 10 + uint64_t(b[at++] - '0');
    return at > start && at - start < 9 && at < b.size() && std::isspace(static_cast<unsigned char>(b[at]));
  };
  uint64_t w = 0, h = 0, maxval = 0;
  if (!field(w) || !field(h) || !field(maxval)) return "cannot decode image: malformed PNM header";
  ++at;  // the one whitespace byte before the pixels
  if (maxval < 1 || maxval > 255) return "cannot decode image: PNM of " + std::to_string(maxval) + " levels (only 8-bit PNM is read)";
  if (uint64_t(b.size() - at) < w * h * (b[1] == '5' ? 1 : 3)) return "cannot decode image: the PNM's pixels are cut short";
  return "";
}

}  // namespace

std::string decode_png(std::string_view bytes, image& out) {
  if (std::string e = pnm_problem(bytes); !e.empty()) return e;
  int w = 0, h = 0, ch = 0;
  stbi_uc* data = stbi_load_from_memory(reinterpret_cast<const stbi_uc*>(bytes.data()), int(bytes.size()), &w, &h, &ch, 4);
  if (!data) return std::string("cannot decode image: ") + (stbi_failure_reason() ? stbi_failure_reason() : "unknown");
  if (w < 1 || h < 1) {  // stb takes a PNM header of width or height 0 (an 18-byte PGM) as an image
    stbi_image_free(data);
    return "cannot decode image: it is " + std::to_string(w) + "x" + std::to_string(h) + " pixels (empty)";
  }
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

std::string decode_user_texture(std::string_view bytes, image& out) {
  if (bytes.size() > max_texture_file_bytes || bytes.size() > size_t(std::numeric_limits<int>::max()))
    return "the file is " + std::to_string(bytes.size() >> 20) + " MB, over the limit of " +
           std::to_string(max_texture_file_bytes >> 20) + " MB";
  if (std::string e = pnm_problem(bytes); !e.empty()) return e;   // before stb reads its header
  int w = 0, h = 0, ch = 0;
  if (!stbi_info_from_memory(reinterpret_cast<const stbi_uc*>(bytes.data()), int(bytes.size()), &w, &h, &ch))
    return std::string("not a readable image (corrupt, or another format: ") +
           (stbi_failure_reason() ? stbi_failure_reason() : "unknown") + ")";
  if (w > max_texture_pixels || h > max_texture_pixels)
    return std::to_string(w) + "x" + std::to_string(h) + " pixels, over the limit of " +
           std::to_string(max_texture_pixels) + " a side";
  if (w < 1 || h < 1) return std::to_string(w) + "x" + std::to_string(h) + " pixels: an empty image";
  return decode_png(bytes, out);
}

std::string read_user_texture(const std::string& path, image& out, std::string* bytes_out) {
  std::error_code ec;
  const auto bytes_on_disk = std::filesystem::file_size(path, ec);
  if (ec) return "cannot read it (" + ec.message() + ")";
  if (bytes_on_disk > max_texture_file_bytes)   // refused before a byte is read
    return "the file is " + std::to_string(bytes_on_disk >> 20) + " MB, over the limit of " +
           std::to_string(max_texture_file_bytes >> 20) + " MB";
  std::string bytes;
  if (std::string err = read_file(path, bytes, max_texture_file_bytes); !err.empty()) return err;
  if (std::string err = decode_user_texture(bytes, out); !err.empty()) return err;
  if (bytes_out) *bytes_out = std::move(bytes);
  return "";
}

std::string load_user_texture(const std::string& path, image& out) {
  const std::string err = read_user_texture(path, out);
  return err.empty() ? "" : path + ": " + err;
}

std::string save_png(const image& img, const std::string& path) {
  std::string bytes;
  if (std::string err = encode_png(img, bytes); !err.empty()) return path + ": " + err;
  return write_file_atomic(path, bytes);
}

}  // namespace sylva
