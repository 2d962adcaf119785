// Archetype texture sets: leaf cards drawn from analytic primitives (blades, strokes)
// into float layers, and periodic bark height/colour fields; normal maps from the height fields.
// The drawing lives in render/assets/archetype_canvas.h (shared kit), archetype_leaves.cpp,
// archetype_conifers.cpp and archetype_bark.cpp; this file holds the tables, the cache and the
// parallel preparation.
#include <algorithm>
#include <array>
#include <iterator>
#include <atomic>
#include <map>
#include <memory>
#include <mutex>
#include <thread>
#include <tuple>

#include "generators/job_pool.h"
#include "render/assets/archetype_canvas.h"
#include "render/assets/textures.h"

namespace sylva {
namespace {

using namespace archetype;

// One row per archetype, in the order of generators/archetypes.h; the static_asserts catch a
// missing or extra row. cost: a rough rank of the time to make the set (higher first when
// preparing on several threads, so they finish close together).
struct leaf_entry {
  void (*draw)(leaf_canvas&, rng&);
  // A pale, low-chroma mid green (linear ~0.45), so that the tint sets the hue and the leaf's
  // albedo is a little under half the tint; each archetype keeps a little character of its own.
  leaf_look look;
  int cost;
};
const leaf_entry leaf_table[] = {
    {draw_ovate, {{178, 194, 156}, {206, 208, 160}}, 0},         // fresh, slightly yellow
    {draw_lobed, {{170, 188, 156}, {196, 202, 156}}, 0},         // deeper
    {draw_palmate, {{178, 194, 152}, {210, 208, 152}}, 0},
    {draw_pinnate, {{174, 192, 158}, {202, 206, 162}}, 0},
    {draw_needles, {{164, 186, 172}, {190, 202, 176}}, 2},       // blue-green
    {draw_flat_spray, {{162, 184, 166}, {188, 200, 172}}, 2},    // bluish
    {draw_scale_spray, {{176, 190, 152}, {198, 202, 152}}, 2},   // yellow-green
    {draw_palm_frond, {{182, 194, 150}, {212, 208, 150}}, 1},    // yellowish
    {draw_twig_cluster, {{178, 194, 156}, {206, 208, 160}}, 1},
    {draw_needle_tufts, {{160, 184, 172}, {186, 200, 178}}, 2},  // glaucous blue-green
    {draw_lanceolate, {{172, 192, 150}, {200, 206, 158}}, 0},    // willow: light, slightly greyish
    {draw_beech_spray, {{176, 192, 152}, {204, 206, 158}}, 1},
    {draw_hazel_spray, {{172, 190, 150}, {200, 204, 154}}, 1},
    {draw_poplar_spray, {{170, 190, 152}, {198, 204, 158}}, 1},
    // Fruit cards: final colours (no tint): shadowed scale colour, then the scales' pale edges.
    {draw_cone_hanging, {{112, 70, 40}, {176, 124, 78}}, 1},    // Picea abies: light brown when ripe
    {draw_cone_upright, {{92, 84, 58}, {150, 140, 96}}, 1},     // Abies, Cedrus: grey-green brown
    {draw_samaras, {{176, 172, 112}, {150, 98, 60}}, 1},        // pale tan-green wings, red-brown nutlets
    {draw_hazelnuts, {{140, 158, 74}, {168, 120, 64}}, 1},      // green husks, brown nuts
    {draw_cone_ovoid, {{84, 72, 58}, {150, 132, 104}}, 1},      // Pinus sylvestris: grey-brown shields
    {draw_beechnuts, {{138, 120, 70}, {120, 74, 40}}, 1},       // Fagus: olive-tan cupules, brown nuts
    {draw_coconuts, {{92, 124, 34}, {132, 96, 48}}, 1},         // Cocos: green nuts ripening to brown
    {draw_maple_spray, {{178, 194, 152}, {210, 208, 152}}, 1},  // as palmate
    {draw_ash_keys, {{182, 176, 104}, {128, 112, 60}}, 1},       // Fraxinus: pale straw-green wings, brown seeds
    {draw_cone_barrel, {{96, 84, 66}, {158, 146, 112}}, 1},      // Cedrus: grey-brown, pale scale edges
    {draw_acorns, {{116, 98, 66}, {172, 150, 76}}, 1},           // Quercus: grey-brown cups, ripening olive-tan nuts
    {draw_horse_chestnut, {{172, 190, 150}, {200, 204, 156}}, 1},  // Aesculus: deep, slightly yellow veins
    {draw_cypress_cones, {{78, 80, 62}, {150, 132, 102}}, 1},      // Cupressus: dark seams, grey-brown shields
    {draw_birch, {{180, 196, 154}, {208, 210, 158}}, 0},           // Betula: fresh, slightly yellow
};
static_assert(std::size(leaf_table) == size_t(leaf_archetype_count), "one leaf_table row per leaf archetype");

struct bark_entry {
  void (*fill)(bark_field&, uint64_t);
  float relief;  // height units per tile width (normal-map strength)
};
const bark_entry bark_table[] = {
    {bark_furrowed, 14}, {bark_plated, 10}, {bark_smooth, 4}, {bark_peeling, 9},
    {bark_ringed, 8},    {bark_mottled, 5}, {bark_fissured, 9}, {bark_fibrous, 9}, {bark_silver, 5},
};
static_assert(std::size(bark_table) == size_t(bark_archetype_count), "one bark_table row per bark archetype");

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
  leaf_table[i].draw(c, g);
  return finish_leaf(c, lease[5], leaf_table[i].look, mix64(seed + uint64_t(i) * 101));
}

bark_texture_set make_bark_archetype_textures(bark_archetype a, int size, uint64_t seed) {
  const int n = clamp_size(size);
  const int i = std::clamp(int(a), 0, bark_archetype_count - 1);
  scratch_lease lease;
  bark_field f(n, lease);
  const uint64_t s = mix64(seed * 2654435761ull + uint64_t(i));
  bark_table[i].fill(f, s);
  return finish_bark(f, bark_table[i].relief);
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
// Runs job(0 .. jobs-1) on the calling thread and threads - 1 helpers of the shared pool, in order
// from a shared counter.
template <class Job>
void run_jobs(int jobs, int threads, Job&& job) {
  parallel_jobs(size_t(std::max(jobs, 0)), [&](size_t j) { job(int(j)); }, std::max(threads, 1));
}
// Jobs 0..leaf_archetype_count-1 are the leaf sets, then the barks; the costliest first (barks
// rank above every card), so two threads finish close together.
constexpr int job_count = leaf_archetype_count + bark_archetype_count;
const std::array<int, job_count> job_order = [] {
  std::array<int, job_count> order{};
  for (int k = 0; k < job_count; ++k) order[size_t(k)] = k;
  auto cost = [](int k) { return k < leaf_archetype_count ? leaf_table[k].cost : 3; };
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return cost(a) > cost(b); });
  return order;
}();
}  // namespace

void prepare_archetype_textures(int size, uint64_t seed, int threads) {
  run_jobs(leaf_archetype_count + bark_archetype_count, threads, [&](int j) {
    const int k = job_order[size_t(j)];
    if (k < leaf_archetype_count) leaf_archetype_textures(leaf_archetype(k), size, seed);
    else bark_archetype_textures(bark_archetype(k - leaf_archetype_count), size, seed);
  });
}

size_t make_all_archetype_textures(int size, uint64_t seed, int threads) {
  std::atomic<size_t> bytes{0};
  run_jobs(leaf_archetype_count + bark_archetype_count, threads, [&](int j) {
    const int k = job_order[size_t(j)];
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
