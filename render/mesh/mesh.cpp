// Skeleton -> generalized-cylinder bark (one ring per node; render/mesh/mesh_bark.cpp) and leaf
// instances, sorted by birth step.
#include "render/mesh/mesh.h"

#include "generators/wood.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <thread>

#include "generators/job_pool.h"
#include "generators/timing.h"
#include "generators/vec_util.h"
#include "render/mesh/mesh_bark.h"

namespace sylva {

tree_mesh mesh_tree(const tree_skeleton& t, const mesh_params& p, uint64_t seed, mesh_stage_times* times) {
  tree_mesh m;
  mesh_stage_times unused;
  mesh_stage_times& st = times ? *times : unused;
  st = {};
  auto lap_start = clock_type::now();
  auto lap = [&](double& field) {   // adds the time since the last lap to one stage
    const auto now = clock_type::now();
    field += ms_between(lap_start, now);
    lap_start = now;
  };
  m.steps = std::max(t.steps, 0);
  m.radial_segments = std::clamp(p.radial_segments, 3, 256);
  m.blade = leaf_blade_shape{p.leaves.blades, std::isfinite(p.leaves.fold) ? p.leaves.fold : 0.0f,
                             std::isfinite(p.leaves.curl) ? p.leaves.curl : 0.0f,
                             std::isfinite(p.leaves.needle_spread) ? p.leaves.needle_spread : 360.0f};
  m.index_end.assign(size_t(m.steps) + 1, 0);
  m.leaf_end.assign(size_t(m.steps) + 1, 0);
  if (!structurally_sound(t)) return m;

  const size_t n = t.size();
  std::vector<rotation_terms> turn;
  std::vector<glm::vec3> disp;
  foliage placed;
  const bool own = p.leaves.mode == leaf_mode::generator && !t.leaves.empty();
  const bool fruit = p.fruits.count > 0;   // the generator's own leaves are then copied, fruit added
  // Leaf placement and the crown's sky field read only the skeleton: they run on a pool helper
  // beside the bark (job_pool.h), or after it here when none is free (st.leaf_place and st.sky are
  // their own times). The bark runs here only (a helper taking both runs the leaves), so its arrays
  // never fill a helper's malloc arena.
  const std::thread::id caller = std::this_thread::get_id();
  const bool place = p.leaves_enabled && (!own || fruit);
  const std::vector<leaf>& src = own && !fruit ? t.leaves : placed.leaves;   // the generator's, uncopied
  const size_t cap = size_t(std::clamp(p.leaves.cap, 1, 2000000));
  const float scale = std::isfinite(p.leaf_scale) ? p.leaf_scale : 1.0f;
  auto usable = [&](const leaf& l) { return l.node >= 0 && size_t(l.node) < n && finite3(l.position); };
  auto step_of = [&](const leaf& l) { return std::min<int>(l.born, m.steps); };
  size_t kept = 0, end = 0;   // leaves kept (usable, up to the cap); src[0, end) holds them
  crown_sky sky;
  std::vector<uint32_t> slot;   // each kept leaf's place in m.leaves (the leaves job's counting sort)
  std::atomic<bool> bark_taken{false}, leaves_taken{!p.leaves_enabled};
  auto bark = [&] { mesh_bark(t, p, m, st, turn, disp); };
  auto leaves = [&] {
    const auto t0 = clock_type::now();
    if (place) {
      if (!own) placed = place_leaves(t, p.leaves, seed);
      else placed.leaves = t.leaves;
      if (fruit) place_fruits(t, p.fruits, seed, p.leaves.ground, placed.leaves);
    }
    const auto t1 = clock_type::now();
    st.leaf_place = ms_between(t0, t1);
    // One pass over the leaves the sort below keeps (usable, up to the cap): each step's count for
    // the counting sort, and where they hang before gnarl for the sky field.
    std::vector<glm::vec4> crown;
    crown.reserve(std::min(src.size(), cap));
    end = src.size();
    for (size_t k = 0; k < src.size(); ++k) {
      const leaf& l = src[k];
      if (!usable(l)) continue;
      if (kept == cap) { end = k; placed.capped = true; break; }
      ++kept;
      ++m.leaf_end[step_of(l)];
      crown.emplace_back(l.position, l.size * scale);
    }
    sky = bake_crown_sky(crown);
    // Each kept leaf's slot in the sort by born step below (a counting sort: prefix sums, then
    // the leaves in order), here beside the bark rather than after it.
    std::vector<uint32_t> cursor(m.leaf_end.size(), 0);
    for (size_t s = 1; s < m.leaf_end.size(); ++s) {
      m.leaf_end[s] += m.leaf_end[s - 1];
      cursor[s] = m.leaf_end[s - 1];
    }
    slot.assign(end, UINT32_MAX);
    for (size_t k = 0; k < end; ++k)
      if (usable(src[k])) slot[k] = cursor[step_of(src[k])]++;
    st.sky = ms_since(t1);
  };
  parallel_jobs(p.leaves_enabled ? 2 : 1, [&](size_t) {
    if (std::this_thread::get_id() == caller && !bark_taken.exchange(true)) bark();
    if (!leaves_taken.exchange(true)) leaves();
  });
  if (!bark_taken.exchange(true)) bark();
  lap_start = clock_type::now();

  // Leaves: the foliage model (leaves.h) or the generator's own, capped at the leaf cap, sorted by
  // born straight into m.leaves (no temporary copy of every leaf): the leaves job counted each
  // step's leaves and gave each its slot. Chunks of them are written, and shaded from the crown
  // field, in the batch that shades the bark.
  crown_leaf_jobs leaf_jobs;
  if (p.leaves_enabled) {
    if (placed.capped)
      m.message = "leaf cap reached: " + std::to_string(kept) + " leaves placed (raise Leaf cap or Leaf spacing)";
    m.leaves.resize(m.leaf_end.back());
    const uint8_t fallback = uint8_t(std::clamp(int(p.leaves.archetype), 0, leaf_archetype_count - 1));
    // Sun and shade leaves for the foliage model's leaves; a generator's own keep the sizes it gave.
    const float shade_size = own || !std::isfinite(p.leaves.shade_size) ? 0.0f : std::clamp(p.leaves.shade_size, 0.0f, 1.0f);
    constexpr size_t grain = 2048;
    leaf_jobs.count = (end + grain - 1) / grain;
    leaf_jobs.run = [&, fallback, shade_size](size_t j, glm::vec3& box_lo, glm::vec3& box_hi) {
      glm::vec3 lo = box_lo, hi = box_hi;   // (in registers: the leaves written could alias the box)
      for (size_t k = j * grain; k < std::min(end, (j + 1) * grain); ++k) {
        if (slot[k] == UINT32_MAX) continue;
        const leaf& l = src[k];
        const glm::quat q = l.orientation;
        const uint8_t tex = l.archetype < leaf_archetype_count ? l.archetype : fallback;  // texture = archetype
        leaf_instance& out = m.leaves[slot[k]];
        out = {gnarled_point(t, turn, disp, size_t(l.node), l.position), glm::vec4(q.x, q.y, q.z, q.w), l.size * scale,
               l.born, l.died, uint32_t(l.node), tex};
        shade_leaf(out, sky, lo, hi);
        if (shade_size > 0 && !leaf_archetype_fruit[tex]) {   // sun and shade leaves (leaves.h leaf_shade_size)
          const float open = std::clamp((float(out.occlusion) / 255.0f - 0.35f) / 0.65f, 0.0f, 1.0f);
          out.size *= 1.0f + shade_size * (0.5f - open);
          lo = glm::min(lo, out.position - glm::vec3(out.size)), hi = glm::max(hi, out.position + glm::vec3(out.size));
        }
      }
      box_lo = lo, box_hi = hi;
    };
  }
  shade_by_crown(m, sky, true, &leaf_jobs);   // and the bounds, in the same parallel passes
  lap(st.occlusion);
  std::vector<rotation_terms>().swap(turn), std::vector<glm::vec3>().swap(disp), std::vector<leaf>().swap(placed.leaves),
      std::vector<uint32_t>().swap(slot);  // done with
  return m;
}

}  // namespace sylva
