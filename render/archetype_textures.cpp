// Archetype texture sets (issue 11): leaf cards drawn from analytic primitives (blades, strokes)
// into float layers, and periodic bark height/colour fields; normal maps from the height fields.
// The drawing lives in render/archetype_canvas.h (shared kit), archetype_leaves.cpp,
// archetype_conifers.cpp and archetype_bark.cpp; this file holds the tables, the cache and the
// parallel preparation.
#include <algorithm>
#include <atomic>
#include <map>
#include <memory>
#include <mutex>
#include <thread>
#include <tuple>

#include "render/archetype_canvas.h"
#include "render/textures.h"

namespace sylva {
namespace {

using namespace archetype;

// A pale, low-chroma mid green (linear ~0.45), so that the tint sets the hue and the leaf's albedo
// is a little under half the tint; each archetype keeps a little character of its own.
const leaf_look leaf_looks[leaf_archetype_count] = {
    {{178, 194, 156}, {206, 208, 160}},  // ovate: fresh, slightly yellow
    {{170, 188, 156}, {196, 202, 156}},  // lobed: deeper
    {{178, 194, 152}, {210, 208, 152}},  // palmate
    {{174, 192, 158}, {202, 206, 162}},  // pinnate
    {{164, 186, 172}, {190, 202, 176}},  // needles: blue-green
    {{162, 184, 166}, {188, 200, 172}},  // flat spray: bluish
    {{176, 190, 152}, {198, 202, 152}},  // scale spray: yellow-green
    {{182, 194, 150}, {212, 208, 150}},  // palm frond: yellowish
    {{178, 194, 156}, {206, 208, 160}},  // twig cluster
};

int clamp_size(int size) { return std::clamp(size, 8, 4096); }

template <class Set>
struct cache_entry {
  std::once_flag once;
  Set set;
};
using cache_key = std::tuple<int, int, uint64_t>;

// The first caller of a key makes the set, callers of the same key wait for it, and different keys
// are made in parallel.
template <class Set, class Make>
const Set& cached(std::map<cache_key, std::unique_ptr<cache_entry<Set>>>& cache, std::mutex& mu, cache_key key, Make&& make) {
  cache_entry<Set>* e;
  {
    std::lock_guard lock(mu);
    auto& slot = cache[key];
    if (!slot) slot = std::make_unique<cache_entry<Set>>();
    e = slot.get();
  }
  std::call_once(e->once, [&] { e->set = make(); });
  return e->set;
}

}  // namespace

leaf_texture_set make_leaf_archetype_textures(leaf_archetype a, int size, uint64_t seed) {
  const int n = clamp_size(size);
  const int i = std::clamp(int(a), 0, leaf_archetype_count - 1);
  scratch_lease lease;
  leaf_canvas c(n, lease);
  rng g{mix64(seed * 1315423911ull + uint64_t(i))};
  using draw_fn = void (*)(leaf_canvas&, rng&);
  static const draw_fn draw[leaf_archetype_count] = {draw_ovate,      draw_lobed,       draw_palmate,
                                                      draw_pinnate,    draw_needles,     draw_flat_spray,
                                                      draw_scale_spray, draw_palm_frond, draw_twig_cluster};
  draw[i](c, g);
  return finish_leaf(c, lease[5], leaf_looks[i], mix64(seed + uint64_t(i) * 101));
}

bark_texture_set make_bark_archetype_textures(bark_archetype a, int size, uint64_t seed) {
  const int n = clamp_size(size);
  const int i = std::clamp(int(a), 0, bark_archetype_count - 1);
  scratch_lease lease;
  bark_field f(n, lease);
  const uint64_t s = mix64(seed * 2654435761ull + uint64_t(i));
  using fill_fn = void (*)(bark_field&, uint64_t);
  static const fill_fn fill[bark_archetype_count] = {bark_furrowed, bark_plated, bark_smooth, bark_peeling, bark_ringed};
  static const float relief[bark_archetype_count] = {14, 10, 4, 9, 8};
  fill[i](f, s);
  return finish_bark(f, relief[i]);
}

const leaf_texture_set& leaf_archetype_textures(leaf_archetype a, int size, uint64_t seed) {
  static std::mutex mu;
  static std::map<cache_key, std::unique_ptr<cache_entry<leaf_texture_set>>> cache;
  return cached(cache, mu, {int(a), clamp_size(size), seed}, [&] { return make_leaf_archetype_textures(a, size, seed); });
}

const bark_texture_set& bark_archetype_textures(bark_archetype a, int size, uint64_t seed) {
  static std::mutex mu;
  static std::map<cache_key, std::unique_ptr<cache_entry<bark_texture_set>>> cache;
  return cached(cache, mu, {int(a), clamp_size(size), seed}, [&] { return make_bark_archetype_textures(a, size, seed); });
}

namespace {
// Runs job(0 .. jobs-1) on `threads` threads taking jobs in order from a shared counter.
template <class Job>
void run_jobs(int jobs, int threads, Job&& job) {
  std::atomic<int> next{0};
  auto worker = [&] {
    for (int j; (j = next.fetch_add(1)) < jobs;) job(j);
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < std::max(threads, 1); ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
}
// The costliest first, so two threads finish close together.
constexpr int job_order[leaf_archetype_count + bark_archetype_count] = {9, 10, 11, 12, 13, 4, 6, 5, 7, 8, 0, 1, 2, 3};
}  // namespace

void prepare_archetype_textures(int size, uint64_t seed, int threads) {
  run_jobs(leaf_archetype_count + bark_archetype_count, threads, [&](int j) {
    const int k = job_order[j];
    if (k < leaf_archetype_count) leaf_archetype_textures(leaf_archetype(k), size, seed);
    else bark_archetype_textures(bark_archetype(k - leaf_archetype_count), size, seed);
  });
}

size_t make_all_archetype_textures(int size, uint64_t seed, int threads) {
  std::atomic<size_t> bytes{0};
  run_jobs(leaf_archetype_count + bark_archetype_count, threads, [&](int j) {
    const int k = job_order[j];
    if (k < leaf_archetype_count) {
      const leaf_texture_set s = make_leaf_archetype_textures(leaf_archetype(k), size, seed);
      bytes += s.color.pixels.size() + s.normal.pixels.size() + s.thickness.pixels.size();
    } else {
      const bark_texture_set s = make_bark_archetype_textures(bark_archetype(k - leaf_archetype_count), size, seed);
      bytes += s.color.pixels.size() + s.normal.pixels.size() + s.roughness.pixels.size();
    }
  });
  return bytes;
}

// albedo = min(1, texture_tint_gain * tint * linear(texel)), written back as sRGB bytes (textures.h).
image tinted_texture(const image& color, const glm::vec3& tint) {
  image out = color;
  const auto& lin = srgb().to_linear;
  const size_t count = size_t(out.width) * size_t(out.height), ch = size_t(std::max(out.channels, 1));
  if (out.pixels.size() < count * ch || ch < 3) return out;
  const float gain[3] = {texture_tint_gain * std::max(tint.x, 0.0f), texture_tint_gain * std::max(tint.y, 0.0f),
                         texture_tint_gain * std::max(tint.z, 0.0f)};
  for (size_t k = 0; k < count; ++k)
    for (size_t c = 0; c < 3; ++c) {
      uint8_t& v = out.pixels[k * ch + c];
      v = linear_byte(gain[c] * lin[v]);
    }
  return out;
}

}  // namespace sylva
