// Export materials: the user's textures and the procedural archetypes' PNGs, encoded once.
#include "render/io/export_internal.h"

#include "render/io/export.h"
#include "render/mesh/lod_cards.h"
#include "render/io/export_wind.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include <algorithm>
#include <array>
#include <cassert>
#include <atomic>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cctype>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string_view>
#include <thread>
#include <tuple>

#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>
#include <stb_image.h>

#include "render/io/preset.h"
#include "render/assets/textures.h"

namespace sylva::export_internal {

// "" with `out` filled, or why the file cannot be used (missing, too big, not an image).
std::string load_user_image(const std::string& path, user_image& out) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(path, ec)) return "file not found";
  if (!fs::is_regular_file(path, ec)) return "not a file";
  std::string bytes;
  if (std::string err = read_user_texture(path, out.pixels, &bytes); !err.empty()) return err;
  static constexpr std::string_view png_signature("\x89PNG\r\n\x1a\n", 8);
  if (std::string_view(bytes).substr(0, 8) == png_signature) out.png = std::move(bytes);
  return "";
}

// The PNGs of a procedural material (bark: colour, normal, roughness; leaf: colour, normal), the
// colour tinted as the viewport tints it. PNG compression is most of an export's time, so the
// images are encoded in parallel and the result is kept for the process: the export dialog's size
// estimate and the export after it encode once. nullptr with `error` set when encoding fails.
std::shared_ptr<const material_pngs> procedural_pngs(bool bark, int archetype, int size, uint64_t seed,
                                                     const glm::vec3& tint, std::string& error) {
  using key_type = std::tuple<bool, int, int, uint64_t, float, float, float>;
  static std::mutex mutex;
  static std::map<key_type, std::shared_ptr<const material_pngs>> cache;
  const key_type key{bark, archetype, size, seed, tint.x, tint.y, tint.z};
  {
    std::lock_guard lock(mutex);
    if (auto it = cache.find(key); it != cache.end()) return it->second;
  }
  std::vector<image> images;
  if (bark) {
    const bark_texture_set& set = bark_archetype_textures(bark_archetype(std::clamp(archetype, 0, bark_archetype_count - 1)), size, seed);
    images = {tinted_texture(set.color, tint), set.normal, set.roughness};
  } else {
    const leaf_texture_set& set = leaf_archetype_textures(leaf_archetype(std::clamp(archetype, 0, leaf_slots - 1)), size, seed);
    images = {tinted_texture(set.color, tint), set.normal};
  }
  std::vector<std::string> png(images.size()), err(images.size());
  std::vector<std::thread> helpers;
  for (size_t k = 1; k < images.size(); ++k) helpers.emplace_back([&, k] { err[k] = encode_png(images[k], png[k]); });
  err[0] = encode_png(images[0], png[0]);
  for (std::thread& t : helpers) t.join();
  for (const std::string& e : err)
    if (!e.empty()) {
      error = e;
      return nullptr;
    }
  auto out = std::make_shared<const material_pngs>(material_pngs{std::move(png[0]), std::move(png[1]), bark ? std::move(png[2]) : ""});
  std::lock_guard lock(mutex);
  if (cache.size() >= 32) cache.clear();  // tints being edited: keep the memory bounded
  cache.emplace(key, out);
  return out;
}

}  // namespace sylva::export_internal
