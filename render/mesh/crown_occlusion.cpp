// Crown ambient occlusion: the crown's ellipsoid for its depth, times the sky
// a point sees through the leaves around it, so each clump is darker inside as well as the crown.
#include <algorithm>
#include <bit>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "generators/job_pool.h"
#include "render/mesh/mesh.h"

namespace sylva {
namespace {

// exp(-x) for x in [0, 87]: 2^(-x·log2 e) split into a power of two 2^i, written into a float's
// exponent bits, and 2^f for the rest f in [-1/2, 1/2] from a degree-4 polynomial with p(0) = 1
// (least squares on the relative error, at most 5.7e-6; the occlusion is stored in 8 bits), so
// exp_neg(0) is exactly 1. The rounding to i adds and subtracts 1.5·2^23. Branch-free, so the
// sky's row loop below is vectorised, where std::exp is a call per cell and direction.
inline float exp_neg(float x) {
  constexpr float round = 12582912.0f;
  const float y = -1.44269504f * x;
  const float t = y + round;
  const int i = std::bit_cast<int>(t) - std::bit_cast<int>(round);
  const float f = y - (t - round);
  const float p = 1.0f + f * (0.693128033f + f * (0.240236785f + f * (0.0558704178f + f * 0.0095902286f)));
  return p * std::bit_cast<float>((i + 127) << 23);
}

// Sky visibility per cell from Beer-Lambert extinction through the leaf area density, exp(-G·LAD·s)
// with the spherical leaf projection G = 1/2 (Monsi & Saeki 1953; Ross 1981), along the zenith and
// eight directions 45° and 35° above the horizon, each weighted by its cosine to the zenith. Only
// the foliage within `window` metres counts, so a clump shades its own inside and its neighbours'
// sides, not the trunk far below the crown. Each direction is a prefix sum along its sheared rows
// (O(cells)), and the window is a difference of two prefix sums.
// g (crown_sky, mesh.h) holds the leaf area density (m² of leaf per m³) per cell on entry and the
// share of the sky each cell sees through the foliage within `window` on return.
void bake_sky(crown_sky& g, float window) {
  const std::vector<float>& lad = g.value;
  const size_t cells = lad.size(), nx = size_t(g.nx);
  const int steps = std::max(1, int(std::lround(window / g.cell)));
  // The nine directions are nine jobs on the shared pool, each with its own prefix sums, writing
  // its weighted terms to its own slice; the slices are then summed cell by cell in direction
  // order, so the bytes do not depend on which thread ran which direction. The terms take nine
  // floats a cell (the grid is at most about 41 × 48 × 41 cells: 2.9 MB). Every cell of the terms
  // and of each direction's prefix sums is written below, so neither is zeroed first.
  uninit_vector<float> terms(9 * cells);
  float weight[9];
  parallel_jobs(9, [&](size_t d) {
    const int dx = int(d / 3) - 1, dz = int(d % 3) - 1;
    const float len = std::sqrt(float(dx * dx + 1 + dz * dz));
    const float w = 1.0f / len;                   // cos of the angle to the zenith
    const float half_ds = 0.5f * g.cell * len;   // G = 1/2 times the path through a cell
    weight[d] = w;
    uninit_vector<float> prefix(cells);
    // Row by row: a row's cells read one row of the layer above (shifted by dx), or none where
    // that row is outside the box; the cells whose source falls off the box's x range read 0.
    const int xa = std::max(0, -dx), xb = std::min(g.nx, g.nx - dx);   // x + dx inside
    for (int y = g.ny; y-- > 0;)
      for (int z = 0; z < g.nz; ++z) {
        float* out = prefix.data() + g.at(0, y, z);
        const float* own = lad.data() + g.at(0, y, z);
        const bool above = y + 1 < g.ny && z + dz >= 0 && z + dz < g.nz;
        if (!above || xa >= xb) {
          for (size_t x = 0; x < nx; ++x) out[x] = own[x] + 0.0f;
          continue;
        }
        const float* from = prefix.data() + g.at(0, y + 1, z + dz);   // read at x + dx, inside for x in [xa, xb)
        for (int x = 0; x < xa; ++x) out[x] = own[x] + 0.0f;
        for (int x = xa; x < xb; ++x) out[x] = own[x] + from[x + dx];
        for (int x = xb; x < g.nx; ++x) out[x] = own[x] + 0.0f;
      }
    // A row's half optical depths first (beyond: the row `steps` layers up, 0 off the box; the
    // cell's own leaves do not shade it), then its terms.
    const int ba = std::max(0, -steps * dx), bb = std::min(g.nx, g.nx - steps * dx);   // x + steps·dx inside
    std::vector<float> depth(nx);
    float* term = terms.data() + d * cells;
    for (int y = 0; y < g.ny; ++y)
      for (int z = 0; z < g.nz; ++z) {
        const size_t c = g.at(0, y, z);
        const float* pre = prefix.data() + c;
        const float* own = lad.data() + c;
        const int by = y + steps, bz = z + steps * dz;
        const bool far = by < g.ny && bz >= 0 && bz < g.nz && ba < bb;
        const float* beyond = far ? prefix.data() + g.at(0, by, bz) : nullptr;   // read at x + steps·dx
        auto half_depth = [&](float shade) { return std::min(std::max(shade, 0.0f) * half_ds, 80.0f); };
        for (int x = 0; x < (far ? ba : g.nx); ++x) depth[size_t(x)] = half_depth(pre[x] - 0.0f - own[x]);
        if (far) {
          for (int x = ba; x < bb; ++x) depth[size_t(x)] = half_depth(pre[x] - beyond[x + steps * dx] - own[x]);
          for (int x = bb; x < g.nx; ++x) depth[size_t(x)] = half_depth(pre[x] - 0.0f - own[x]);
        }
        // No foliage in the window (most cells round and above a crown): exp_neg(0) is exactly 1.
        for (size_t x = 0; x < nx; ++x) term[c + x] = w * exp_neg(depth[x]);
      }
  });
  float weights = 0;
  for (float w : weight) weights += w;
  // Each cell's nine terms summed in direction order (left to right) and divided by the weights,
  // in one pass over chunks of cells on the pool, written over the densities (read no more).
  float* sky = g.value.data();
  parallel_chunks(cells, 8192, [&](size_t c0, size_t c1) {
    const float* t = terms.data();
    const float *t0 = t, *t1 = t + cells, *t2 = t + 2 * cells, *t3 = t + 3 * cells, *t4 = t + 4 * cells,
                *t5 = t + 5 * cells, *t6 = t + 6 * cells, *t7 = t + 7 * cells, *t8 = t + 8 * cells;
    for (size_t c = c0; c < c1; ++c)
      sky[c] = (t0[c] + t1[c] + t2[c] + t3[c] + t4[c] + t5[c] + t6[c] + t7[c] + t8[c]) / weights;
  });
}

}  // namespace

// Trilinear between cell centres, clamped to the box.
float crown_sky::sample(const glm::vec3& p) const {
  const glm::vec3 g = glm::clamp((p - origin) / cell - 0.5f, glm::vec3(0), glm::vec3(float(nx - 1), float(ny - 1), float(nz - 1)));
  if (!std::isfinite(g.x) || !std::isfinite(g.y) || !std::isfinite(g.z)) return 1;
  const int x0 = int(g.x), y0 = int(g.y), z0 = int(g.z);
  const int x1 = std::min(x0 + 1, nx - 1), y1 = std::min(y0 + 1, ny - 1), z1 = std::min(z0 + 1, nz - 1);
  const float fx = g.x - float(x0), fy = g.y - float(y0), fz = g.z - float(z0);
  auto lerp = [](float a, float b, float f) { return a + (b - a) * f; };
  const float a = lerp(lerp(value[at(x0, y0, z0)], value[at(x1, y0, z0)], fx), lerp(value[at(x0, y1, z0)], value[at(x1, y1, z0)], fx), fy);
  const float b = lerp(lerp(value[at(x0, y0, z1)], value[at(x1, y0, z1)], fx), lerp(value[at(x0, y1, z1)], value[at(x1, y1, z1)], fx), fy);
  return lerp(a, b, fz);
}

crown_sky bake_crown_sky(const std::vector<glm::vec4>& leaves) {
  crown_sky g;
  if (leaves.empty()) return g;   // no crown: nothing shades the sky
  glm::vec3 lo(1e30f), hi(-1e30f);
  for (const glm::vec4& l : leaves) { lo = glm::min(lo, glm::vec3(l)); hi = glm::max(hi, glm::vec3(l)); }
  if (!std::isfinite(lo.x + lo.y + lo.z + hi.x + hi.y + hi.z)) return g;
  g.centre = 0.5f * (lo + hi), g.inv_radius = 1.0f / glm::max(0.5f * (hi - lo), glm::vec3(0.05f));

  // The leaf area density on a grid over the leaves' box, about 40 cells along its longest side,
  // reaching one window below it (the rays only go up), so shade fades out down the trunk.
  const float longest = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z, 0.1f});
  const float window = std::clamp(longest / 6.0f, 0.1f, 3.0f);   // about a limb mass
  // Cells no smaller than a leaf's card, so one leaf never fills a cell on its own.
  double mean_size = 0;
  for (const glm::vec4& l : leaves) mean_size += std::isfinite(l.w) ? double(l.w) : 0.0;
  mean_size /= double(leaves.size());
  g.cell = std::max({longest / 40.0f, 1.5f * float(mean_size), 0.05f});
  g.origin = lo - glm::vec3(0.5f * g.cell, 0.5f * g.cell + window, 0.5f * g.cell);
  const glm::vec3 extent = hi + glm::vec3(0.5f * g.cell) - g.origin;
  g.nx = int(extent.x / g.cell) + 1, g.ny = int(extent.y / g.cell) + 1, g.nz = int(extent.z / g.cell) + 1;
  g.value.assign(size_t(g.nx) * size_t(g.ny) * size_t(g.nz), 0.0f);
  const float volume = g.cell * g.cell * g.cell;
  for (const glm::vec4& l : leaves) {
    const glm::vec3 q = (glm::vec3(l) - g.origin) / g.cell;
    const int x = std::clamp(int(q.x), 0, g.nx - 1), y = std::clamp(int(q.y), 0, g.ny - 1), z = std::clamp(int(q.z), 0, g.nz - 1);
    const float s = std::isfinite(l.w) ? l.w : 0.0f;
    g.value[g.at(x, y, z)] += 0.5f * s * s / volume;   // a blade fills about half its card
  }
  bake_sky(g, std::max(window, 2 * g.cell));
  return g;
}

void bake_crown_occlusion(tree_mesh& m) {
  std::vector<glm::vec4> leaves(m.leaves.size());
  for (size_t k = 0; k < leaves.size(); ++k) leaves[k] = glm::vec4(m.leaves[k].position, m.leaves[k].size);
  shade_by_crown(m, bake_crown_sky(leaves));
}

void shade_by_crown(tree_mesh& m, const crown_sky& g, bool set_bounds, const crown_leaf_jobs* leaf_jobs) {
  // The bounds, when asked for, come from the same chunks: each chunk's box, merged after (min
  // and max give the same box in any order).
  struct box {
    glm::vec3 lo{1e30f}, hi{-1e30f};
    void add(const glm::vec3& a, const glm::vec3& b) { lo = glm::min(lo, a), hi = glm::max(hi, b); }
  };
  const size_t stride = size_t(std::max(m.radial_segments, 0)) + 1, nv = m.position.size();
  const bool rings = stride > 1 && nv % stride == 0 && m.node.size() == nv;
  const size_t block = rings ? stride : 8192, grain = rings ? 1024 : 1, blocks = (nv + block - 1) / block;
  constexpr size_t leaf_grain = 2048;
  std::vector<box> bark_box(set_bounds ? (blocks + grain - 1) / grain : 0);
  const size_t leaf_jobs_count = leaf_jobs ? leaf_jobs->count : (m.leaves.size() + leaf_grain - 1) / leaf_grain;
  std::vector<box> leaf_box(set_bounds || leaf_jobs ? leaf_jobs_count : 0);
  m.occlusion.resize(nv);   // every value is written below
  // Bark comes in rings of radial_segments + 1 vertices of one node. The field changes over a
  // cell, so a ring whose box is under a quarter of a cell (a twig's, most of a tree's rings)
  // takes the value at its box's centre for all its vertices: one sample instead of one per
  // vertex. Wider rings (the trunk, the limbs) sample each vertex; a vertex equal to the one
  // before (a ring's seam, a cap's apex) takes its value. Chunks of whole rings on the shared
  // pool, each writing only its own vertices, so the bytes do not depend on the chunking.
  const float small = 0.25f * g.cell;
  auto bark_chunk = [&](size_t b0, size_t b1) {
    box local;   // written to bark_box once: boxes of two threads' chunks share cache lines
    box* bb = set_bounds ? &local : nullptr;
    for (size_t b = b0; b < b1; ++b) {
      const size_t begin = b * block, end = std::min(begin + block, nv);
      if (rings) {
        glm::vec3 lo(m.position[begin]), hi(lo);
        bool one_node = true;
        for (size_t i = begin + 1; i < end; ++i) {
          lo = glm::min(lo, m.position[i]);
          hi = glm::max(hi, m.position[i]);
          one_node = one_node && m.node[i] == m.node[begin];
        }
        if (bb) bb->add(lo, hi);
        const glm::vec3 size = hi - lo;
        if (one_node && std::max({size.x, size.y, size.z}) < small) {   // false for NaN: sampled per vertex
          std::fill(m.occlusion.begin() + std::ptrdiff_t(begin), m.occlusion.begin() + std::ptrdiff_t(end),
                    crown_visibility(g, 0.5f * (lo + hi)));
          continue;
        }
      } else if (bb) {
        for (size_t i = begin; i < end; ++i) bb->add(m.position[i], m.position[i]);
      }
      for (size_t i = begin; i < end; ++i)
        m.occlusion[i] = i > begin && m.position[i] == m.position[i - 1] ? m.occlusion[i - 1] : crown_visibility(g, m.position[i]);
    }
    if (bb) bark_box[b0 / grain] = local;
  };
  auto leaf_chunk = [&](size_t begin, size_t end) {
    box local;
    for (size_t k = begin; k < end; ++k) shade_leaf(m.leaves[k], g, local.lo, local.hi);
    if (set_bounds) leaf_box[begin / leaf_grain] = local;
  };
  // The bark's chunks and the leaves' in one batch: one wait for the helpers, and no thread idle
  // between the two while the other finishes its last chunk.
  const size_t bark_jobs = (blocks + grain - 1) / grain;
  parallel_jobs(bark_jobs + leaf_jobs_count, [&](size_t j) {
    if (j < bark_jobs) bark_chunk(j * grain, std::min(blocks, (j + 1) * grain));
    else if (leaf_jobs) leaf_jobs->run(j - bark_jobs, leaf_box[j - bark_jobs].lo, leaf_box[j - bark_jobs].hi);
    else leaf_chunk((j - bark_jobs) * leaf_grain, std::min(m.leaves.size(), (j - bark_jobs + 1) * leaf_grain));
  });
  if (!set_bounds || (m.position.empty() && m.leaves.empty())) return;
  box all;
  for (const box& b : bark_box) all.add(b.lo, b.hi);
  for (const box& b : leaf_box) all.add(b.lo, b.hi);
  m.bounds_min = all.lo;
  m.bounds_max = all.hi;
}

}  // namespace sylva
