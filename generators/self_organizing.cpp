// Self-organizing trees (Palubicki et al. 2009) with the extensions of seed 001.
#include "generators/self_organizing.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "generators/history.h"
#include "generators/keyframes.h"
#include "generators/pruning.h"
#include "generators/resume.h"
#include "generators/self_organizing_cone.h"
#include "generators/self_organizing_grid.h"
#include "generators/self_organizing_markers.h"
#include "generators/vec_util.h"

namespace sylva {

namespace {

constexpr int32_t bud_here = -1;  // main/lat: a live bud sits there
constexpr int32_t no_bud = -2;    // main/lat: nothing (shed, or never had one)
// A step's cones are scanned on the pool when each holds at least parallel_scan_cone voxels and
// shoots × cone voxels reach parallel_scan_work (a few hundred µs of scanning, against some tens
// for waking the helpers). Smaller cones scan faster on the growth thread however many there are:
// the grid's chunks around the buds are in its cache, as its light pass just read them (with
// every step of 200,000 on the pool, self_organizing_forest grew in 118 ms against 95).
constexpr size_t parallel_scan_cone = 256, parallel_scan_work = 200000, parallel_scan_window = 512;

glm::vec3 safe_normalize(const glm::vec3& v, const glm::vec3& fallback) {
  const float l2 = glm::dot(v, v);
  return l2 > 1e-12f && std::isfinite(l2) ? v / std::sqrt(l2) : fallback;
}

// A shoot a step grows: bud k of node (0: the main bud, 1: the lateral, 2: the far lateral of
// opposite phyllotaxis) and its plan.
struct planned_shoot {
  int32_t node;
  int k;
  shoot_plan plan;
};

// What the step loop carries from one step to the next besides the tree, the RNG and the working
// params: a resumed growth (generators/resume.h) restores exactly this.
struct so_vars {
  shadow_grid grid;
  marker_state markers;
  // Per node (generator state, not part of the skeleton).
  std::vector<glm::vec3> side;       // unit, perpendicular to the internode: where the lateral bud points
  std::vector<int32_t> main, lat;    // child index, bud_here or no_bud
  std::vector<int32_t> lat2;         // opposite phyllotaxis only: the lateral bud on the far side
  size_t nb = 2;                     // buds a node: 3 when the growth may use opposite phyllotaxis
  std::vector<float> q;              // nb per node: bud light Q, then bud resource v (apical, lateral, far lateral)
  std::vector<float> flow;           // basipetal Q flow, then acropetal resource v
  std::vector<float> tips;           // living tips supported (pipe model: (r/r₀)^n)
  std::vector<int32_t> buds;         // living buds supported
  std::vector<glm::vec3> opt;        // markers only, nb per node: direction towards the bud's markers
  std::vector<glm::ivec3> voxel;     // shadow only: each node's voxel, found once (nodes never move)
  float cos_theta = 0;               // perception cone (keyframes change it)
};

struct so_state : so_vars {
  const self_organizing_params& p;
  tree_skeleton& t;
  rng& r;
  perception_cone cone;              // voxel offsets within the perception distance
  float reach = 0;                   // perception reach in metres
  float l = 0.1f;
  // k^e for whole k, filled on first use: tip counts and bud ages repeat every step, and std::pow
  // per node and step was ~7% of a default tree's growth. Same calls, so the same bits.
  std::vector<float> tips_pow, age_pow;
  // Scratch of shed: the nodes shed this step, their voxels, the ancestors to sweep again (marked).
  std::vector<int32_t> shed_nodes, resweep;
  std::vector<glm::ivec3> shed_voxels;
  std::vector<uint8_t> resweep_mark;
  // Scratch of compute_marker_light: the live buds, in bud order, and perceive_markers'.
  std::vector<int32_t> marker_buds;
  marker_scratch marker_work;

  so_state(const self_organizing_params& pp, tree_skeleton& tt, rng& rr) : p(pp), t(tt), r(rr) {}

  // The memo's hit inline (once per node and step in the sweep), the rest out of line.
  static float whole_pow(std::vector<float>& memo, float k, float e) {
    if (k >= 0 && k < float(memo.size()) && float(size_t(k)) == k) return memo[size_t(k)];
    return whole_pow_fill(memo, k, e);
  }
  [[gnu::noinline]] static float whole_pow_fill(std::vector<float>& memo, float k, float e) {
    constexpr size_t limit = size_t(1) << 22;
    if (!(k >= 0 && k < float(limit)) || float(size_t(k)) != k) return std::pow(k, e);
    const size_t i = size_t(k);
    for (size_t j = memo.size(); j <= i; ++j) memo.push_back(std::pow(float(j), e));
    return memo[i];
  }

  int32_t add_node(const glm::vec3& pos, int32_t parent, uint16_t born, uint8_t order, const glm::vec3& s) {
    const int32_t i = t.add_node(pos, parent, 0, born, order);
    if (p.environment == so_environment::shadow) voxel.push_back(voxel_of(grid, pos));
    side.push_back(s);
    main.push_back(bud_here);
    lat.push_back(bud_here);
    if (nb == 3) lat2.push_back(p.phyllotaxis == so_phyllotaxis::opposite ? bud_here : no_bud);
    q.insert(q.end(), nb, 0.0f);
    flow.push_back(0);
    tips.push_back(1);
    buds.push_back(0);
    return i;
  }

  glm::vec3 heading(int32_t i) const {
    const int32_t par = t.parent[i];
    return par < 0 ? glm::vec3(0, 1, 0) : safe_normalize(t.position[i] - t.position[par], glm::vec3(0, 1, 0));
  }
  // The lateral bud's default direction; far = the opposite phyllotaxis' second lateral, across the axis.
  glm::vec3 lateral_direction(int32_t i, bool far = false) const {
    const float b = glm::radians(p.branch_angle);
    return safe_normalize(std::cos(b) * heading(i) + std::sin(b) * (far ? -side[i] : side[i]), heading(i));
  }
  // The default direction of bud k of node i (0 the apical bud, 1 and 2 the laterals).
  glm::vec3 shoot_default(int32_t i, int k) const { return k == 0 ? heading(i) : lateral_direction(i, k == 2); }
  // Bud k of node i: 0 the apical bud, 1 the lateral, 2 the far lateral (child, bud_here or no_bud).
  // k = 2 exists only when nb is 3.
  int32_t& bud(size_t i, int k) { return k == 0 ? main[i] : k == 1 ? lat[i] : lat2[i]; }
  int32_t far(size_t i) const { return nb == 3 ? lat2[i] : no_bud; }

  // Bud light l from the environment, then seed 001 eq. 1: Q = l^((T−T₀)^σ).
  void compute_bud_light(int step) {
    const size_t n = t.size();
    const bool shadow = p.environment == so_environment::shadow;
    if (!shadow) compute_marker_light();
    for (size_t i = 0; i < n; ++i) {
      if (t.died[i] != never_died || (main[i] != bud_here && lat[i] != bud_here && far(i) != bud_here)) continue;
      const float age = float(step - t.born[i]);  // ≥ 1: buds are first seen the step after they form
      const float e = p.sigma == 0 ? 1.0f : whole_pow(age_pow, age, p.sigma);
      if (shadow) {
        // Palubicki 2009 §4.2: Q = max(C − s + a, 0); both buds of a node share its voxel.
        const float s = shadow_at(grid, voxel[i]);
        float light = std::max(p.full_exposure - s + p.shadow_a, 0.0f);
        light = e == 1.0f ? light : std::pow(light, e);
        // Seed 001 §3.1 counts a node's light once if it has either bud (per_node: shared by its
        // buds); Sylva's default lets each live bud count it, as Palubicki 2009 gives each bud a Q.
        const int live = (main[i] == bud_here) + (lat[i] == bud_here) + (far(i) == bud_here);
        if (live > 1 && p.light_count == so_light_count::per_node) light /= float(live);
        q[nb * i] = main[i] == bud_here ? light : 0.0f;
        q[nb * i + 1] = lat[i] == bud_here ? light : 0.0f;
        if (nb == 3) q[nb * i + 2] = lat2[i] == bud_here ? light : 0.0f;
      } else {
        int lit = 0;
        for (int k = 0; k < int(nb); ++k) {
          q[nb * i + k] = q[nb * i + k] > 0 ? 1.0f : 0.0f;  // 0^e = 0 and 1^e = 1: σ changes nothing here
          lit += q[nb * i + k] > 0;
        }
        if (p.light_count == so_light_count::per_node && lit > 1)
          for (int k = 0; k < int(nb); ++k) q[nb * i + k] = q[nb * i + k] > 0 ? 1.0f / float(lit) : 0.0f;
      }
    }
  }

  // Palubicki 2009 §4.1: each marker in a bud's perception cone goes to the closest such bud
  // (perceive_markers); a bud with markers has Q = 1 and its optimal direction is the sum of unit
  // vectors to them.
  void compute_marker_light() {
    const size_t n = t.size();
    opt.assign(nb * n, glm::vec3(0));
    std::fill(q.begin(), q.end(), 0.0f);
    std::vector<int32_t>& live = marker_buds;
    live.clear();
    for (size_t i = 0; i < n; ++i) {
      if (t.died[i] != never_died) continue;
      for (int k = 0; k < int(nb); ++k)
        if (this->bud(i, k) == bud_here) live.push_back(int32_t(nb * i + size_t(k)));
    }
    auto bud_at = [&](size_t j, glm::vec3& pos, glm::vec3& def) {
      pos = t.position[size_t(live[j]) / nb], def = shoot_default(int32_t(size_t(live[j]) / nb), int(size_t(live[j]) % nb));
    };
    perceive_markers(markers, live.size(), bud_at, reach, cos_theta, marker_work, [&](size_t j, uint32_t m) {
      const size_t bud = size_t(live[j]);
      opt[bud] += safe_normalize(markers.pos[m] - t.position[bud / nb], glm::vec3(0));
      q[bud] = 1;
    });
  }

  void remove_markers_near(const glm::vec3& pos) {
    markers.visit_near(pos, p.occupancy_radius * l, [&](uint32_t m, const glm::vec3&) { markers.alive[m] = 0; });
  }

  // Basipetal pass (children before parents): Q flow with seed 001 eq. 2 upkeep, living tips and
  // buds. Dead nodes are never reached: their parents' links say no_bud.
  void sweep_flow() {
    const float be_over_n = p.be / p.pipe_exponent, bm = upkeep_bm();
    for (size_t i = t.size(); i-- > 0;) sweep_node(i, bm, be_over_n);
  }

  // Seed 001 eq. 2 prints BM·radius^BE / default_radius; with r = r₀·(r/r₀) that is
  // r₀^(BE−1)·BM·(r/r₀)^BE, r in metres. The relative form (default) does not change with the
  // choice of unit or of r₀, which is why Sylva uses it; upkeep_form = seed001 follows the text.
  float upkeep_bm() const {
    return p.upkeep_form == so_upkeep_form::seed001 ? p.bm * std::pow(p.tip_radius, p.be - 1) : p.bm;
  }

  // One node of the basipetal pass, from its children's values.
  void sweep_node(size_t i, float bm, float be_over_n) {
    if (t.died[i] != never_died) { flow[i] = 0; buds[i] = 0; return; }
    const int32_t m = main[i], la = lat[i], lb = far(i);
    const float qm = m >= 0 ? flow[m] : m == bud_here ? q[nb * i] : 0.0f;
    float ql = la >= 0 ? flow[la] : la == bud_here ? q[nb * i + 1] : 0.0f;
    float tp = (m >= 0 ? tips[m] : 0.0f) + (la >= 0 ? tips[la] : 0.0f);
    buds[i] = (m >= 0 ? buds[m] : m == bud_here) + (la >= 0 ? buds[la] : la == bud_here);
    if (lb != no_bud) {   // (skipped without one, so spiral and planar trees keep their bits)
      ql += lb >= 0 ? flow[lb] : q[nb * i + 2];
      tp += lb >= 0 ? tips[lb] : 0.0f;
      buds[i] += lb >= 0 ? buds[lb] : 1;
    }
    tips[i] = tp > 0 ? tp : 1.0f;
    // Seed 001 eq. 2 (Měch & Prusinkiewicz 1996): upkeep BM·(r/r₀)^BE, where the pipe model
    // gives (r/r₀)^n = number of tips, so (r/r₀)^BE = tips^(BE/n).
    const float upkeep = bm > 0 ? bm * whole_pow(tips_pow, tips[i], be_over_n) : 0.0f;
    flow[i] = qm + ql - upkeep;
  }

  // The basipetal pass again after shedding `gone` (in index order): only the shed nodes and their
  // ancestors can change, each computed from its children as the full pass does, children first,
  // so every value is the full pass's bit for bit.
  void resweep_after_shed(const std::vector<int32_t>& gone) {
    const float be_over_n = p.be / p.pipe_exponent, bm = upkeep_bm();
    std::vector<int32_t>& redo = resweep;
    redo.clear();
    for (int32_t i : gone) {
      flow[size_t(i)] = 0, buds[size_t(i)] = 0;
      for (int32_t a = t.parent[size_t(i)]; a >= 0 && !resweep_mark[size_t(a)]; a = t.parent[size_t(a)]) {
        resweep_mark[size_t(a)] = 1;
        redo.push_back(a);
      }
    }
    std::sort(redo.begin(), redo.end(), std::greater<int32_t>());
    for (int32_t a : redo) {
      resweep_mark[size_t(a)] = 0;
      sweep_node(size_t(a), bm, be_over_n);
    }
  }

  // Sheds per seed 001, then brings the flow up to date; returns true when anything went.
  bool shed(uint16_t step) {
    if (p.shed_min_buds <= 0) return false;
    const std::vector<uint8_t> s = select_shed(t.parent, flow, buds, p.shed_min_buds);
    std::vector<int32_t>& gone = shed_nodes;
    gone.clear();
    for (size_t i = 0; i < s.size(); ++i) {
      if (!s[i] || t.died[i] != never_died) continue;
      gone.push_back(int32_t(i));
      t.died[i] = step;
      const int32_t par = t.parent[i];
      if (main[par] == int32_t(i)) main[par] = no_bud;
      if (lat[par] == int32_t(i)) lat[par] = no_bud;
      if (nb == 3 && lat2[par] == int32_t(i)) lat2[par] = no_bud;
    }
    if (gone.empty()) return false;
    if (p.environment == so_environment::shadow) {   // their shadow goes, in the same order
      shed_voxels.clear();
      for (int32_t i : gone) shed_voxels.push_back(voxel[size_t(i)]);
      add_shadow_pyramids(grid, shed_voxels, p.shadow_a, p.shadow_b, p.q_max, -1);
    }
    resweep_mark.resize(t.size(), 0);
    resweep_after_shed(gone);
    return true;
  }

  // Pruning (Palubicki et al. 2009, §7 and fig. 12): a cut branch goes as a shed one does. Its
  // buds and its shadow go with it, so the next step's light and flow send the resource it took to
  // the rest of the tree and the buds near the cut break. In the marker environment the markers
  // it had occupied come back, unless a remaining node still occupies them.
  void prune(const std::vector<int32_t>& cut) {
    for (int32_t i : cut) {
      const int32_t par = t.parent[i];
      if (main[par] == i) main[par] = no_bud;
      if (lat[par] == i) lat[par] = no_bud;
      if (nb == 3 && lat2[par] == i) lat2[par] = no_bud;
      if (p.environment == so_environment::shadow)
        add_shadow_pyramid(grid, voxel[i], p.shadow_a, p.shadow_b, p.q_max, -1);
    }
    if (p.environment != so_environment::markers) return;
    for (int32_t i : cut)
      markers.visit_near(t.position[i], p.occupancy_radius * l, [&](uint32_t m, const glm::vec3&) { markers.alive[m] = 1; }, true);
    for (size_t i = 0; i < t.size(); ++i)
      if (t.died[i] == never_died) remove_markers_near(t.position[i]);
  }

  // The shoots node i's buds grow from their resource (q), in bud order (k), onto `shoots`.
  void list_shoots(size_t i, std::vector<planned_shoot>& shoots) {
    for (int k = 0; k < int(nb); ++k) {
      if (bud(i, k) != bud_here) continue;
      const shoot_plan plan = plan_shoot(q[nb * i + size_t(k)], p.internode_length);
      if (plan.metamers > 0) shoots.push_back({int32_t(i), k, plan});
    }
  }

  // Acropetal pass: turns flow into resource v (flow[] and q[] are overwritten with v), and lists
  // the step's shoots in bud order (node, then k) into `shoots`. Under Borchert-Honda a node's
  // buds get their v when the pass reaches the node, so they are listed then; the priority model
  // sets them axis by axis, so they are listed after it.
  // `vigour` is the step's season (generators/history.h): a good year has more resource to share.
  void allocate(int step, const std::vector<int32_t>& roots, std::vector<planned_shoot>& shoots, float vigour) {
    const float alpha = p.alpha * vigour;
    for (int32_t root : roots) flow[root] = alpha * std::max(flow[root], 0.0f);  // v_base = α·Q_base
    if (p.allocation == so_allocation::borchert_honda) {
      for (size_t i = 0; i < t.size(); ++i) {
        if (t.died[i] != never_died) continue;
        const int32_t m = main[i], la = lat[i], lb = far(i);
        const float qm = m >= 0 ? flow[m] : m == bud_here ? q[nb * i] : 0.0f;
        const float ql = la >= 0 ? flow[la] : la == bud_here ? q[nb * i + 1] : 0.0f;
        const float qb = lb >= 0 ? flow[lb] : lb == bud_here ? q[nb * i + 2] : 0.0f;
        float vm, vl, vb = 0;
        if (lb == no_bud) {
          split_borchert_honda(flow[i], qm, ql, p.lambda, vm, vl);
        } else {
          // Two laterals share the lateral side of eqs. 4-5, each in proportion to its own Q.
          split_borchert_honda(flow[i], qm, ql + qb, p.lambda, vm, vl);
          const float both = std::max(ql, 0.0f) + std::max(qb, 0.0f);
          const float to_b = both > 0 ? std::max(qb, 0.0f) / both : 0.5f;
          vb = vl * to_b;
          vl -= vb;
        }
        if (m >= 0) flow[m] = vm; else q[nb * i] = m == bud_here ? vm : 0.0f;
        if (la >= 0) flow[la] = vl; else q[nb * i + 1] = la == bud_here ? vl : 0.0f;
        if (lb >= 0) flow[lb] = vb; else if (nb == 3) q[nb * i + 2] = lb == bud_here ? vb : 0.0f;
        list_shoots(i, shoots);
      }
      return;
    }
    // Priority model: each axis, from its base, ranks its lateral branches and buds and its
    // terminal bud by Q. An axis starts at a root or a lateral child; parents precede children,
    // so an axis' resource is known when its base comes up.
    // Seed 000 sorts an axis' nodes by the *average* environmental input of the buds each supports,
    // then weights eq. 1 by its summed Q; priority_rank = summed sorts by the summed Q instead.
    struct cand { float q; float rank; int32_t target; };  // target ≥ 0: lateral child; < 0: bud −(nb·i+k)−1
    const bool by_average = p.priority_rank == so_priority_rank::average;
    std::vector<cand> c;
    std::vector<float> qs, vs;
    const bool terminal_first = step <= p.terminal_priority_steps;
    for (size_t b = 0; b < t.size(); ++b) {
      if (t.died[b] != never_died) continue;
      const int32_t par = t.parent[b];
      if (par >= 0 && lat[par] != int32_t(b) && far(size_t(par)) != int32_t(b)) continue;
      c.clear();
      int32_t j = int32_t(b);
      bool has_terminal = false;
      for (;;) {
        for (int k = 1; k < int(nb); ++k) {
          const int32_t la = bud(size_t(j), k);
          if (la >= 0) {
            const float sum = std::max(flow[la], 0.0f);
            c.push_back({sum, by_average ? sum / float(std::max(buds[la], 1)) : sum, la});
          } else if (la == bud_here) {
            c.push_back({q[nb * size_t(j) + size_t(k)], q[nb * size_t(j) + size_t(k)], -int32_t(nb * size_t(j) + size_t(k)) - 1});
          }
        }
        if (main[j] >= 0) { j = main[j]; continue; }
        if (main[j] == bud_here) {
          c.push_back({q[nb * size_t(j)], q[nb * size_t(j)], -int32_t(nb * size_t(j)) - 1});
          has_terminal = true;
        }
        break;
      }
      if (has_terminal && terminal_first) std::rotate(c.begin(), c.end() - 1, c.end());
      std::stable_sort(c.begin() + (has_terminal && terminal_first ? 1 : 0), c.end(),
                       [](const cand& x, const cand& y) { return x.rank > y.rank; });
      qs.resize(c.size());
      for (size_t k = 0; k < c.size(); ++k) qs[k] = c[k].q;
      allocate_priority(flow[b], qs, p.w_max, p.w_min, p.kappa, vs);
      for (size_t k = 0; k < c.size(); ++k) {
        if (c[k].target >= 0) flow[c[k].target] = vs[k];
        else q[size_t(-c[k].target - 1)] = vs[k];
      }
    }
    for (size_t i = 0; i < t.size(); ++i)
      if (t.died[i] == never_died) list_shoots(i, shoots);
  }
};

std::vector<glm::vec3> place_trees(const self_organizing_params& p, rng& r, std::string& warning) {
  std::vector<glm::vec3> at;
  if (p.placement == so_placement::explicit_positions) {
    if (!p.positions.empty()) return p.positions;
    warning = "explicit placement without positions: using a grid";
  }
  const int n = std::max(p.tree_count, 1);
  if (p.placement == so_placement::random && warning.empty()) {
    const float side = p.spacing * std::sqrt(float(n));
    for (int k = 0; k < n; ++k) at.push_back({r.uniform(-0.5f, 0.5f) * side, 0, r.uniform(-0.5f, 0.5f) * side});
    return at;
  }
  const int cols = int(std::ceil(std::sqrt(float(n))));
  const int rows = (n + cols - 1) / cols;
  for (int k = 0; k < n; ++k)
    at.push_back({(float(k % cols) - 0.5f * float(cols - 1)) * p.spacing, 0,
                  (float(k / cols) - 0.5f * float(rows - 1)) * p.spacing});
  return at;
}

}  // namespace

// Everything the step loop reads, at the top of step k (before its keyframes and cuts): resuming
// from it grows what a full regrow grows from there (generators/resume.h). The cone offsets, reach
// and internode length follow from the base params, which a resume requires to be unchanged.
struct so_snapshot {
  tree_skeleton t;
  rng r;
  self_organizing_params p;   // the working params, keyframes up to k − 1 applied
  so_vars v;
  float div = 0;
  grow_report rep;
  size_t bytes = 0;
};

namespace {

// What a snapshot of this state holds, in bytes (the vectors' contents; the memo tables are left
// out: they are rebuilt on use and give the same bits).
size_t snapshot_bytes(const tree_skeleton& t, const so_vars& v) {
  const marker_state& m = v.markers;
  return sizeof(so_snapshot) + vec_bytes(t.position) + vec_bytes(t.parent) + vec_bytes(t.radius) + vec_bytes(t.born) +
         vec_bytes(t.died) + vec_bytes(t.order) + vec_bytes(t.leaves) + vec_bytes(v.grid.keys) +
         vec_bytes(v.grid.chunk_of) + vec_bytes(v.grid.cells) + vec_bytes(v.grid.chunk_pos) + vec_bytes(v.grid.scratch) +
         vec_bytes(m.pos) + vec_bytes(m.alive) + vec_bytes(m.best) + vec_bytes(m.cell_key) +
         vec_bytes(m.cell_start) + vec_bytes(m.order) + vec_bytes(v.side) + vec_bytes(v.main) + vec_bytes(v.lat) + vec_bytes(v.lat2) +
         vec_bytes(v.q) + vec_bytes(v.flow) + vec_bytes(v.tips) + vec_bytes(v.buds) + vec_bytes(v.opt) + vec_bytes(v.voxel);
}

}  // namespace

size_t sc_recorded_bytes(const growth_resume& r);   // space_colonization.cpp

size_t recorded_bytes(const growth_resume& r) {
  size_t n = sc_recorded_bytes(r);
  for (const auto& x : r.self_organizing)
    if (x) n += x->bytes;
  return n;
}

tree_skeleton grow_self_organizing(const self_organizing_params& params, const grow_options& o, grow_report* report,
                                   growth_debug* debug) {
  grow_report local;
  grow_report& rep = report ? *report : local;
  self_organizing_params p = params;
  const std::vector<std::string> clamped = clamp_all_params(p);
  if (!clamped.empty()) rep.message = "clamped out-of-range parameter " + clamped.front();
  const int steps = std::min(o.steps >= 0 ? o.steps : p.steps, int(never_died) - 1);

  tree_skeleton t;
  rng r(o.seed);
  so_state st(p, t, r);
  st.l = p.internode_length;
  st.grid.voxel_size = p.voxel_size * p.internode_length;
  st.cos_theta = std::cos(glm::radians(p.perception_angle));
  st.reach = p.perception_distance * p.internode_length;
  st.cone = make_perception_cone(p.perception_distance, p.voxel_size, st.grid.voxel_size);

  float div = glm::radians(p.divergence);
  const std::vector<float> season = season_anomalies(o.seed, steps);   // years differ (history.h)
  // Opposite phyllotaxis needs a third bud a node; a growth that never uses it keeps two (8 bytes a
  // node less), and a snapshot kept with two cannot resume one that now needs three.
  bool opposite = p.phyllotaxis == so_phyllotaxis::opposite;
  if (o.keyframes)
    for (const keyframe& k : *o.keyframes)
      opposite = opposite || (k.key == "phyllotaxis" && int(k.value.x) == int(so_phyllotaxis::opposite));
  const size_t buds_per_node = opposite ? 3 : 2;
  int step = 0;
  int first = 1;
  bool resumed = false;
  std::vector<int32_t> roots;
  growth_resume* const resume = o.resume;
  std::vector<std::shared_ptr<const so_snapshot>>* const snaps = resume ? &resume->self_organizing : nullptr;
  if (resume && resume->from_step >= 1 && resume->from_step <= steps && size_t(resume->from_step) < snaps->size() &&
      (*snaps)[size_t(resume->from_step)] && (*snaps)[size_t(resume->from_step)]->v.nb == buds_per_node) {
    const so_snapshot& s = *(*snaps)[size_t(resume->from_step)];
    t = s.t;
    r = s.r;
    p = s.p;
    static_cast<so_vars&>(st) = s.v;
    div = s.div;
    rep = s.rep;
    first = resume->from_step;
    step = first - 1;
    resume->resumed_at = first;
    resumed = true;
    for (int k = 0; k < t.tree_count; ++k) roots.push_back(k);   // the seedlings are the first nodes
  }
  const bool shadow = p.environment == so_environment::shadow;   // keyframes cannot change it
  if (!resumed) {
  st.nb = buds_per_node;
  std::string warning;
  const std::vector<glm::vec3> roots_at = place_trees(p, r, warning);
  if (!warning.empty()) rep.message = warning;
  for (const glm::vec3& at : roots_at) {
    if (int64_t(t.size()) >= p.node_cap) break;
    // A random start for the phyllotactic spiral: otherwise every tree turns its first branch the same way.
    const float a = r.uniform(0.0f, 6.2831853f);
    roots.push_back(st.add_node(at, -1, 0, 0, glm::vec3(std::cos(a), 0, std::sin(a))));
    st.lat.back() = no_bud;  // the seedling has only its apical bud
    if (st.nb == 3) st.lat2.back() = no_bud;
  }
  t.tree_count = int(roots.size());
  if (p.environment == so_environment::shadow) {
    for (int32_t i : roots) add_shadow_pyramid(st.grid, st.voxel[i], p.shadow_a, p.shadow_b, p.q_max);
  } else {
    fill_marker_envelopes(st.markers, roots_at, p, r, rep.message);
    st.markers.cell = std::max(st.reach, 1e-3f);
    st.markers.build();
    for (int32_t i : roots) st.remove_markers_near(t.position[i]);
  }
  }  // !resumed

  std::vector<int32_t> grown;  // nodes made this step
  std::vector<glm::ivec3> grown_voxels;
  std::vector<planned_shoot> shoots;
  std::vector<cone_choice> choices;   // one shoot's cone at a time
  cone_scratch scratch;
  cone_scans scans;
  std::vector<float> last_flow;
  // What is recorded from here on is replaced; the state resumed from stays (it is this state).
  if (resume && resume->record) snaps->resize(size_t(first) + (resumed ? 1 : 0));
  for (int T = first; T <= steps; ++T) {
    if (o.cancelled()) { rep.cancelled = true; break; }
    if (resume && resume->record && !(T == first && resumed)) {
      const std::vector<int>& only = resume->record_steps;
      snaps->resize(size_t(T) + 1);
      if (only.empty() || std::find(only.begin(), only.end(), T) != only.end()) {
        // Bounded: a snapshot is a deep copy, so one that would take the recorded total past the
        // cap is skipped (and counted); an edit there resumes from an earlier one or regrows.
        const size_t bytes = snapshot_bytes(t, st);
        size_t held = 0;
        for (const auto& x : *snaps)
          if (x) held += x->bytes;
        if (held + bytes <= resume->byte_cap)
          (*snaps)[size_t(T)] = std::make_shared<const so_snapshot>(so_snapshot{t, r, p, st, div, rep, bytes});
        else
          ++resume->skipped;
      }
    }
    // Growth phases: new values from this step on; what the state derives from them follows.
    if (apply_keyframes(p, o.keyframes, T)) {
      clamp_all_params(p);
      st.cos_theta = std::cos(glm::radians(p.perception_angle));
      st.age_pow.clear();   // memoised powers of σ and BE/n
      st.tips_pow.clear();
      div = glm::radians(p.divergence);
    }
    if (const std::vector<int32_t> cut = apply_cuts(t, o.cuts, T, rep); !cut.empty()) st.prune(cut);
    st.compute_bud_light(T);
    st.sweep_flow();
    st.shed(uint16_t(T));   // and the flow again where it sheds
    if (debug) last_flow = st.flow;
    shoots.clear();
    st.allocate(T, roots, shoots, season_vigour(p.season_variation, season[size_t(T)]));

    // Bud fate and shoots; the environment stays as it was at the step's start, so the result
    // does not depend on the order in which buds are visited.
    grown.clear();
    // The shoots this step grows, in bud order (listed by allocate). In the shadow environment
    // each scans its cone (scan_cone reads the grid only, which stays as it was at the step's
    // start) on this thread, or, in a step of long scans of large cones (a fine grid's: past
    // parallel_scan_cone and parallel_scan_work), first on the pool, a window of
    // parallel_scan_window shoots at a time (so few choices are kept), each shoot's choices then
    // replayed on the RNG here in order. The default tree's scans are short: on the pool they made
    // its growth slower on two cores (14.7 against 13.4 ms), waking helpers for too little.
    const bool scanned = shadow && st.cone.offset.size() >= parallel_scan_cone &&
                         shoots.size() * st.cone.offset.size() >= parallel_scan_work;
    size_t window = 0;   // the first shoot of the window scanned
    for (size_t j = 0; j < shoots.size() && !rep.hit_node_cap; ++j) {
      if ((j & 4095) == 0 && o.cancelled()) { rep.cancelled = true; break; }
      if (scanned && j % parallel_scan_window == 0) {
        window = j;
        scan_cones(st.grid, st.cone, st.cos_theta, st.reach, std::min(parallel_scan_window, shoots.size() - j),
                   [&](size_t w, glm::vec3& pos, glm::ivec3& v, glm::vec3& def) {
                     const int32_t i = shoots[window + w].node;
                     pos = t.position[size_t(i)], v = st.voxel[size_t(i)], def = st.shoot_default(i, shoots[window + w].k);
                   }, scans);
      }
      const size_t i = size_t(shoots[j].node);
      const int k = shoots[j].k;
      {
        const shoot_plan plan = shoots[j].plan;
        int32_t prev = int32_t(i);
        const glm::vec3 def = st.shoot_default(int32_t(i), k);
        glm::vec3 ref = k == 0 ? st.side[i] : st.heading(int32_t(i));
        const uint8_t ord = uint8_t(std::min(int(t.order[i]) + (k > 0), 255));
        const glm::vec3 marker_dir = shadow ? glm::vec3(0) : safe_normalize(st.opt[st.nb * i + size_t(k)], def);
        // Palubicki 2009 §5: the shoot's direction blends the default, optimal and tropism
        // directions; one direction per shoot, as both seeds do, so a shoot is straight.
        glm::vec3 optimal = marker_dir;
        if (scanned) {
          optimal = pick_optimal(r, scans.choices.first(j - window), scans.choices.count(j - window), def);
        } else if (shadow) {
          choices.clear();
          scan_cone(st.grid, st.cone, st.cos_theta, st.reach, t.position[i], st.voxel[i], def, scratch, choices);
          optimal = pick_optimal(r, choices.data(), uint32_t(choices.size()), def);
        }
        glm::vec3 blend = p.w_default * def + p.w_optimal * optimal + p.w_tropism * p.tropism;
        // Phototropism towards open sky (history.h, Loehle 1986): a fourth term ψ·ô; none at ψ = 0.
        if (p.sky_lean > 0) blend += p.sky_lean * open_side_direction(p.open_side);
        const glm::vec3 dir = safe_normalize(blend, def);
        for (int m = 0; m < plan.metamers; ++m) {
          if (int64_t(t.size()) >= p.node_cap) { rep.hit_node_cap = true; break; }
          const glm::vec3 from = t.position[prev];
          // The lateral bud's side: the previous side carried along the axis, turned by φ
          // (spiral), or a random ±side in the XY plane (seed 000's planar ±45° rule).
          glm::vec3 s;
          if (p.phyllotaxis == so_phyllotaxis::planar) {
            s = safe_normalize(glm::cross(glm::vec3(0, 0, 1), dir), glm::vec3(1, 0, 0)) * (r.uniform() < 0.5f ? -1.0f : 1.0f);
          } else {
            s = safe_normalize(ref - glm::dot(ref, dir) * dir, any_perpendicular(dir));
            s = glm::angleAxis(div, dir) * s;
          }
          const int32_t node = st.add_node(from + dir * plan.length, prev, uint16_t(T), ord, s);
          if (prev == int32_t(i)) st.bud(i, k) = node;
          else st.main[prev] = node;
          grown.push_back(node);
          prev = node;
          ref = s;
        }
      }
    }
    // Grow the environment with the new nodes.
    if (shadow) {
      grown_voxels.clear();
      for (int32_t i : grown) grown_voxels.push_back(st.voxel[size_t(i)]);
      add_shadow_pyramids(st.grid, grown_voxels, p.shadow_a, p.shadow_b, p.q_max);
    } else {
      for (int32_t i : grown) st.remove_markers_near(t.position[i]);
    }
    step = T;
    if (o.progress) o.progress(float(T) / float(std::max(steps, 1)));
    if (rep.hit_node_cap || rep.cancelled || st.grid.full) break;
  }
  t.steps = step;
  apply_pipe_radii(t, p.pipe_exponent, p.tip_radius, p.pipe_taper);

  if (rep.hit_node_cap)
    rep.message = "node cap reached (" + std::to_string(p.node_cap) + " nodes) in step " + std::to_string(step) +
                  "; raise node_cap or lower the step count";
  else if (st.grid.full)
    rep.message = "shadow grid memory cap reached (" + std::to_string(st.grid.chunk_cap) + " chunks, " +
                  std::to_string((st.grid.chunk_cap * shadow_grid::chunk_cells * sizeof(float)) >> 20) +
                  " MiB) in step " + std::to_string(step) + "; raise voxel_size, lower q_max or the step count";
  rep.stop = rep.hit_node_cap ? grow_stop::node_cap : rep.cancelled ? grow_stop::cancelled
             : st.grid.full ? grow_stop::memory_cap : grow_stop::finished;
  rep.stop_reason = rep.hit_node_cap ? "node cap" : rep.cancelled ? "cancelled" : st.grid.full ? "memory cap" : "steps done";

  if (debug) {
    if (shadow) {
      sample_shadow_grid(st.grid, 1000000, debug->points, debug->point_value);
      debug->point_kind.assign(debug->points.size(), debug_kind::shadow_sample);
    } else {
      for (size_t m = 0; m < st.markers.pos.size(); ++m)
        if (st.markers.alive[m]) debug->add_point(st.markers.pos[m], -1, debug_kind::marker);
    }
    // Fates as of the last step: shed, grew in it (or used up its buds), or dormant.
    debug->node_fate.assign(t.size(), 1);
    for (size_t i = 0; i < t.size(); ++i) {
      if (t.died[i] != never_died) debug->node_fate[i] = 2;
      else if (st.main[i] != bud_here && st.lat[i] != bud_here && st.far(i) != bud_here) debug->node_fate[i] = 0;
      if (t.parent[i] >= 0 && t.born[i] == t.steps && debug->node_fate[t.parent[i]] == 1) debug->node_fate[t.parent[i]] = 0;
    }
    debug->node_flow = last_flow;
    debug->node_flow.resize(t.size(), 0.0f);
  }
  // Lower limbs shaded out by the crown above die and leave stubs (generators/history.h).
  if (const std::vector<int32_t> kept = self_prune(t, p.live_crown, p.stub_length); !kept.empty()) {
    apply_pipe_radii(t, p.pipe_exponent, p.tip_radius, p.pipe_taper);
    if (debug) {
      for (size_t j = 0; j < kept.size(); ++j)
        debug->node_fate[j] = debug->node_fate[size_t(kept[j])], debug->node_flow[j] = debug->node_flow[size_t(kept[j])];
      debug->node_fate.resize(kept.size()), debug->node_flow.resize(kept.size());
    }
  }
  return t;
}

}  // namespace sylva
