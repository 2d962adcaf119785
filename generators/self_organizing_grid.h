// The sparse, unbounded shadow grid of the self-organizing generator (Palubicki 2009 §4.2).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

namespace sylva {

// Voxels live in 8³ chunks found through an open-addressing hash of chunk coordinates, so memory
// grows with the occupied region only: seed 000's dense 200³ grid ran into its walls after a few
// steps, this one has none (chunk coordinates span ±2^20 chunks; farther voxels are clamped).
struct shadow_grid {
  static constexpr int chunk_bits = 3;
  static constexpr int chunk_side = 1 << chunk_bits;
  static constexpr int chunk_cells = chunk_side * chunk_side * chunk_side;
  static constexpr uint64_t empty_key = ~uint64_t(0);

  // Memory cap: at most this many chunks (2 KiB of cells each, 256 MiB in
  // all); writes past it go to a scratch chunk and set `full`, and the generator stops there.
  static constexpr size_t default_chunk_cap = size_t(1) << 17;
  size_t chunk_cap = default_chunk_cap;
  bool full = false;
  std::vector<float> scratch;

  float voxel_size = 1;              // metres
  std::vector<uint64_t> keys;        // hash slots: packed chunk coordinates, or empty_key
  std::vector<int32_t> chunk_of;     // hash slots: index into cells / chunk_side³
  std::vector<float> cells;          // chunk k's shadow values at [k·512, (k+1)·512)
  std::vector<glm::ivec3> chunk_pos; // chunk k's coordinates (for overlays)

  size_t chunk_count() const { return chunk_pos.size(); }
  size_t memory_bytes() const;
};

glm::ivec3 voxel_of(const shadow_grid& g, const glm::vec3& p);
glm::vec3 voxel_centre(const shadow_grid& g, const glm::ivec3& v);
// Shadow value s of a voxel (0 where nothing was ever written).
float shadow_at(const shadow_grid& g, const glm::ivec3& v);
// Palubicki 2009 §4.2: a bud in voxel (I,J,K) adds Δs = a·b^(−q) to the voxels (I±p, J−q, K±p),
// q = 0..q_max, p = 0..q. sign = −1 removes what sign = +1 added.
void add_shadow_pyramid(shadow_grid& g, const glm::ivec3& v, float a, float b, int q_max, float sign = 1);
// add_shadow_pyramid for each voxel in turn, the same bits, with one small cache of chunk indices
// shared by the pyramids (one step's lie close together).
void add_shadow_pyramids(shadow_grid& g, const std::vector<glm::ivec3>& voxels, float a, float b, int q_max, float sign = 1);
// The 512 values of a chunk (chunk coordinates = voxel >> chunk_bits), or nullptr when unwritten.
const float* shadow_chunk(const shadow_grid& g, const glm::ivec3& chunk);
// Index of a voxel's value inside its chunk.
inline int shadow_cell(const glm::ivec3& v) {
  constexpr int m = shadow_grid::chunk_side - 1;
  return ((v.y & m) * shadow_grid::chunk_side + (v.z & m)) * shadow_grid::chunk_side + (v.x & m);
}
// Voxels whose value is not 0.
size_t count_shadowed_voxels(const shadow_grid& g);
// Centres and values of the shadowed voxels, at most max_points of them (for the overlay).
void sample_shadow_grid(const shadow_grid& g, size_t max_points, std::vector<glm::vec3>& points,
                        std::vector<float>& values);

}  // namespace sylva
