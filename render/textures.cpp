// PNG I/O through stb and the checked loading of user textures (the procedural archetype sets are
// made in archetype_textures.cpp).
#include "render/textures.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include <stb_image.h>
#include <stb_image_write.h>

#include "render/file_io.h"

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
