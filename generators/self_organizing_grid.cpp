// The sparse shadow grid: chunked voxels behind an open-addressing hash.
#include "generators/self_organizing_grid.h"

#include <algorithm>
#include <cmath>


namespace sylva {
namespace {

constexpr int32_t coord_limit = (1 << 20) - 1;  // chunk coordinates fit 21 bits each

uint64_t pack(const glm::ivec3& c) {
  return (uint64_t(uint32_t(c.x + (1 << 20))) << 42) | (uint64_t(uint32_t(c.y + (1 << 20))) << 21) |
         uint64_t(uint32_t(c.z + (1 << 20)));
}

size_t slot_of(uint64_t key, size_t mask) {
  key ^= key >> 29;
  key *= 0xBF58476D1CE4E5B9ull;
  key ^= key >> 32;
  return size_t(key) & mask;
}

// 1 inside [a, b] of an 8-voxel chunk row, 0 outside: ds times this is the row's increment.
struct row_mask_table {
  float m[shadow_grid::chunk_side][shadow_grid::chunk_side][shadow_grid::chunk_side];
};
constexpr row_mask_table make_row_masks() {
  row_mask_table t{};
  for (int a = 0; a < shadow_grid::chunk_side; ++a)
    for (int b = 0; b < shadow_grid::chunk_side; ++b)
      for (int k = 0; k < shadow_grid::chunk_side; ++k) t.m[a][b][k] = k >= a && k <= b ? 1.0f : 0.0f;
  return t;
}
constexpr row_mask_table row_masks = make_row_masks();

glm::ivec3 chunk_of_voxel(const glm::ivec3& v) {
  return {v.x >> shadow_grid::chunk_bits, v.y >> shadow_grid::chunk_bits, v.z >> shadow_grid::chunk_bits};
}

int cell_index(const glm::ivec3& v) { return shadow_cell(v); }

const float* find_chunk(const shadow_grid& g, const glm::ivec3& c) {
  if (g.keys.empty()) return nullptr;
  const uint64_t key = pack(c);
  const size_t mask = g.keys.size() - 1;
  for (size_t s = slot_of(key, mask);; s = (s + 1) & mask) {
    if (g.keys[s] == key) return g.cells.data() + size_t(g.chunk_of[s]) * shadow_grid::chunk_cells;
    if (g.keys[s] == shadow_grid::empty_key) return nullptr;
  }
}

void insert_slot(shadow_grid& g, uint64_t key, int32_t chunk) {
  const size_t mask = g.keys.size() - 1;
  size_t s = slot_of(key, mask);
  while (g.keys[s] != shadow_grid::empty_key) s = (s + 1) & mask;
  g.keys[s] = key;
  g.chunk_of[s] = chunk;
}

float* get_chunk(shadow_grid& g, const glm::ivec3& c) {
  if (g.keys.empty()) {
    g.keys.assign(64, shadow_grid::empty_key);
    g.chunk_of.assign(64, -1);
  }
  const uint64_t key = pack(c);
  size_t mask = g.keys.size() - 1;
  for (size_t s = slot_of(key, mask);; s = (s + 1) & mask) {
    if (g.keys[s] == key) return g.cells.data() + size_t(g.chunk_of[s]) * shadow_grid::chunk_cells;
    if (g.keys[s] == shadow_grid::empty_key) break;
  }
  if (g.chunk_pos.size() >= g.chunk_cap) {  // over the memory cap: the write goes nowhere
    g.full = true;
    g.scratch.assign(shadow_grid::chunk_cells, 0.0f);
    return g.scratch.data();
  }
  // Keep the load factor under 1/2 so probes stay short.
  if (2 * (g.chunk_pos.size() + 1) > g.keys.size()) {
    std::vector<uint64_t> old_keys = std::move(g.keys);
    std::vector<int32_t> old_chunks = std::move(g.chunk_of);
    g.keys.assign(old_keys.size() * 2, shadow_grid::empty_key);
    g.chunk_of.assign(old_keys.size() * 2, -1);
    for (size_t s = 0; s < old_keys.size(); ++s)
      if (old_keys[s] != shadow_grid::empty_key) insert_slot(g, old_keys[s], old_chunks[s]);
  }
  const int32_t k = int32_t(g.chunk_pos.size());
  insert_slot(g, key, k);
  g.chunk_pos.push_back(c);
  g.cells.resize(g.cells.size() + shadow_grid::chunk_cells, 0.0f);
  return g.cells.data() + size_t(k) * shadow_grid::chunk_cells;
}

}  // namespace

const float* shadow_chunk(const shadow_grid& g, const glm::ivec3& chunk) { return find_chunk(g, chunk); }

size_t shadow_grid::memory_bytes() const {
  return keys.capacity() * sizeof(uint64_t) + chunk_of.capacity() * sizeof(int32_t) +
         cells.capacity() * sizeof(float) + chunk_pos.capacity() * sizeof(glm::ivec3);
}

glm::ivec3 voxel_of(const shadow_grid& g, const glm::vec3& p) {
  constexpr float lim = float(coord_limit) * shadow_grid::chunk_side;
  glm::ivec3 v;
  for (int i = 0; i < 3; ++i) {
    float f = std::floor(p[i] / g.voxel_size);
    if (!(f > -lim)) f = -lim;  // NaN lands here too
    if (f > lim - 1) f = lim - 1;
    v[i] = int(f);
  }
  return v;
}

glm::vec3 voxel_centre(const shadow_grid& g, const glm::ivec3& v) {
  return (glm::vec3(v) + 0.5f) * g.voxel_size;
}

float shadow_at(const shadow_grid& g, const glm::ivec3& v) {
  const float* c = find_chunk(g, chunk_of_voxel(v));
  return c ? c[cell_index(v)] : 0.0f;
}

namespace {

// A few recently used chunks by coordinates, direct-mapped: the pyramids of one step lie close
// together, so most lookups end here instead of in the grid's large hash. Chunk indices stay
// valid as chunks are added (only the cells move), and chunks are never removed.
struct chunk_cache {
  static constexpr size_t size = 256;
  uint64_t key[size];
  int32_t id[size];
  chunk_cache() { std::fill(key, key + size, shadow_grid::empty_key); }
};

// The index of chunk c, made if new; -1 where the memory cap sends the write nowhere.
int32_t chunk_id(shadow_grid& g, const glm::ivec3& c, chunk_cache& cache) {
  const uint64_t key = pack(c);
  const size_t slot = size_t((key ^ (key >> 21) ^ (key >> 42)) & (chunk_cache::size - 1));
  if (cache.key[slot] == key) return cache.id[slot];
  const float* cells = get_chunk(g, c);
  if (cells == g.scratch.data()) return -1;   // over the cap: not remembered
  cache.key[slot] = key;
  cache.id[slot] = int32_t((cells - g.cells.data()) / shadow_grid::chunk_cells);
  return cache.id[slot];
}

// Adds one pyramid's Δs, layer by layer, z then x chunk row segments: the order in which chunks
// are created. Each chunk of the pyramid's chunk box is looked up once, on its first row (a
// pyramid of depth 4 spans at most 2 × 2 × 2 chunks but some 20 row segments). Each chunk row takes
// one fixed 8-wide add (two SIMD adds) of ds inside [x0, x1] and ds·0 = ±0 outside. Adding ±0
// changes no value a cell can hold: cells start at +0 and a sum is -0 only when both terms are, so
// no cell is ever -0.
void add_pyramid(shadow_grid& g, const glm::ivec3& v, float a, float b, int q_max, float sign, chunk_cache& cache) {
  constexpr int side = shadow_grid::chunk_side, bits = shadow_grid::chunk_bits, m = side - 1;
  constexpr int32_t unknown = -2;
  const int cx0 = (v.x - q_max) >> bits, cy0 = (v.y - q_max) >> bits, cz0 = (v.z - q_max) >> bits;
  const int nx = ((v.x + q_max) >> bits) - cx0 + 1, ny = (v.y >> bits) - cy0 + 1, nz = ((v.z + q_max) >> bits) - cz0 + 1;
  constexpr int box_max = 128;   // q_max ≤ 16 (its range) spans at most 3 × 5 × 5 chunks
  int32_t box[box_max];
  const bool boxed = q_max >= 0 && int64_t(nx) * ny * nz <= box_max;
  if (boxed) std::fill(box, box + nx * ny * nz, unknown);
  float ds = sign * a;  // Palubicki 2009 §4.2: Δs = a·b^(−q), one division by b per layer
  for (int q = 0; q <= q_max; ++q, ds /= b) {
    const int y = v.y - q, x0 = v.x - q, x1 = v.x + q, z0 = v.z - q, z1 = v.z + q;
    const int cy = y >> bits;
    for (int cz = z0 >> bits; cz <= z1 >> bits; ++cz) {
      const int za = std::max(z0, cz * side), zb = std::min(z1, cz * side + m);
      for (int cx = x0 >> bits; cx <= x1 >> bits; ++cx) {
        int32_t id;
        if (boxed) {
          int32_t& at = box[((cy - cy0) * nz + (cz - cz0)) * nx + (cx - cx0)];
          if (at == unknown) at = chunk_id(g, {cx, cy, cz}, cache);
          id = at;
        } else {
          id = chunk_id(g, {cx, cy, cz}, cache);
        }
        if (id < 0) continue;
        const int xa = std::max(x0, cx * side) & m, xb = std::min(x1, cx * side + m) & m;
        const float* mask = row_masks.m[xa][xb];
        float add[side];
        for (int k = 0; k < side; ++k) add[k] = ds * mask[k];
        float* row = g.cells.data() + size_t(id) * shadow_grid::chunk_cells + cell_index({0, y, za});
        for (int z = za; z <= zb; ++z, row += side)
          for (int k = 0; k < side; ++k) row[k] += add[k];
      }
    }
  }
}

}  // namespace

void add_shadow_pyramid(shadow_grid& g, const glm::ivec3& v, float a, float b, int q_max, float sign) {
  chunk_cache cache;
  add_pyramid(g, v, a, b, q_max, sign, cache);
}

void add_shadow_pyramids(shadow_grid& g, const std::vector<glm::ivec3>& voxels, float a, float b, int q_max, float sign) {
  // One pass, one pyramid after another, on the calling thread: splitting the adds among threads
  // by chunk needed a first pass to list every row segment's chunk, and that pass plus each part
  // walking every segment cost more than the adds themselves (a default tree grew ~5 ms slower).
  chunk_cache cache;
  for (const glm::ivec3& v : voxels) add_pyramid(g, v, a, b, q_max, sign, cache);
}

size_t count_shadowed_voxels(const shadow_grid& g) {
  return size_t(std::count_if(g.cells.begin(), g.cells.end(), [](float s) { return s != 0.0f; }));
}

void sample_shadow_grid(const shadow_grid& g, size_t max_points, std::vector<glm::vec3>& points,
                        std::vector<float>& values) {
  constexpr int side = shadow_grid::chunk_side;
  for (size_t k = 0; k < g.chunk_pos.size(); ++k) {
    const float* chunk = g.cells.data() + k * shadow_grid::chunk_cells;
    const glm::ivec3 base = g.chunk_pos[k] * side;
    for (int y = 0; y < side; ++y)
      for (int z = 0; z < side; ++z)
        for (int x = 0; x < side; ++x) {
          const float s = chunk[(y * side + z) * side + x];
          if (s == 0.0f) continue;
          if (points.size() >= max_points) return;
          points.push_back(voxel_centre(g, base + glm::ivec3(x, y, z)));
          values.push_back(s);
        }
  }
}

}  // namespace sylva
