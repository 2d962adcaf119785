// The wood pass: each internode is a cantilever beam segment that bends under the wood and leaves
// it carries; the growth is replayed by born step so that a branch sags as it gets heavier.
//
// Model (small deflection, Euler-Bernoulli): the bending moment at the middle of internode k is
// M = Σ m_i (x_i - c_k) × g over the loads beyond that point, its curvature M / (E I) with
// I = π r⁴ / 4, so the internode turns by θ = M⊥ L / (E I) about M. Half of θ is applied at the
// internode's base and the rest at its tip (a hinge at its middle), which makes a chain of n equal
// segments match the beam formulas to O(1/n²). Loads and moments are accumulated from the tips down
// in one reverse sweep (parents precede children), positions in one forward sweep: O(n) per step.
//
// History (permanent set): as in Jirasek, Prusinkiewicz & Moulia 2000 ("Integrating biomechanics
// into developmental plant models expressed using L-systems"), new wood is laid down on the bent
// branch, so at each bend step an internode turns by the *increase* of its moment since the last
// bend divided by its stiffness *now*: load added while the branch was thin bends it for good.
// Reaction wood then turns young shoots back toward their set direction by a share per step.
#include "generators/wood.h"

#include "generators/job_pool.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <new>
#include <string>
#include <type_traits>

#ifdef __linux__
#include <sys/mman.h>
#endif

#include <glm/geometric.hpp>
#include <glm/gtx/quaternion.hpp>
#include <glm/gtc/quaternion.hpp>

namespace sylva {

namespace {

constexpr float standard_gravity = 9.80665f;  // m/s² (CGPM 1901)
constexpr float pi = 3.14159265358979f;
constexpr float min_beam_radius = 1e-4f;      // metres: a zero radius would have no stiffness

// The rotation by vector v (axis · angle in radians); a Taylor series for the small turns of one step.
glm::quat rotation_quat(const glm::vec3& v) {
  const float a2 = glm::dot(v, v);
  if (!(a2 > 1e-24f)) return glm::quat(1, 0, 0, 0);
  float c, s;
  if (a2 < 1e-2f) {   // |v| < 0.1: cos(a/2) and sin(a/2)/a to better than 1e-10
    c = 1 - a2 * (1.0f / 8) + a2 * a2 * (1.0f / 384);
    s = 0.5f - a2 * (1.0f / 48) + a2 * a2 * (1.0f / 3840);
  } else {
    const float a = std::sqrt(a2);
    c = std::cos(0.5f * a);
    s = std::sin(0.5f * a) / a;
  }
  return glm::quat(c, v.x * s, v.y * s, v.z * s);
}

// x^y for x > 0 to about 1e-5 relative: the pass needs each node's pipe radius at every bend step,
// and the library pow was a fifth of its time. log2 of the mantissa and exp2 of the fraction by
// their Taylor-fitted polynomials (degree 6 / 5); the exponent from the float's bits.
float fast_pow(float x, float y) {
  if (!(x >= 1e-37f) || !(x < 1e37f)) return std::pow(x, y);   // normal floats only
  uint32_t bits;
  std::memcpy(&bits, &x, 4);
  const int e = int((bits >> 23) & 0xff) - 126;
  bits = (bits & 0x007fffffu) | 0x3f800000u;
  float m;
  std::memcpy(&m, &bits, 4);               // x = m · 2^(e-1), m in [1, 2)
  // log2(m) = ln(m) / ln 2 with ln(1 + u) = 2 atanh(u / (2 + u)), t = u / (2 + u) in [0, 1/3).
  const float t = (m - 1) / (m + 1), t2 = t * t;
  const float ln_m = 2 * t * (1 + t2 * (1.0f / 3 + t2 * (1.0f / 5 + t2 * (1.0f / 7 + t2 * (1.0f / 9)))));
  const float l = float(e - 1) + ln_m * 1.44269504f;
  const float z = y * l;
  if (!(std::fabs(z) < 120)) return std::pow(x, y);
  int zi = int(z);
  if (float(zi) > z) --zi;                                 // floor
  const float f = (z - float(zi)) * 0.693147181f;          // 2^z = 2^zi · e^f, f in [0, ln 2)
  const float ef = 1 + f * (1 + f * (0.5f + f * (1.0f / 6 + f * (1.0f / 24 + f * (1.0f / 120 + f * (1.0f / 720))))));
  const uint32_t scale = uint32_t(zi + 127) << 23;   // 2^zi, |zi| < 120
  float p2;
  std::memcpy(&p2, &scale, 4);
  return ef * p2;
}

// atan2(y, x) for y >= 0, to about 1e-5 rad: Abramowitz & Stegun 4.4.49's odd polynomial on [0, 1].
float fast_atan2(float y, float x) {
  const float ax = std::fabs(x);
  const bool swap = y > ax;
  const float q = swap ? ax / y : y / std::max(ax, 1e-30f), q2 = q * q;
  float a = q * (0.9998660f + q2 * (-0.3302995f + q2 * (0.1801410f + q2 * (-0.0851330f + q2 * 0.0208351f))));
  if (swap) a = 1.57079633f - a;
  return x < 0 ? 3.14159265f - a : a;
}

// One block for all of the pass's scratch arrays (about 90 bytes a node), left uninitialised. On a
// large tree, faulting in 4 KiB pages one at a time was about a fifth of the pass: on Linux the
// block asks for transparent huge pages (2 MiB), which the kernel grants in "madvise" mode too.
class scratch_block {
 public:
  explicit scratch_block(size_t bytes) {
    constexpr size_t huge = size_t(2) << 20;
    // Small trees (tests, scrubbing a sapling) keep ordinary pages: a huge one is zeroed whole.
    const size_t align = bytes >= 2 * huge ? huge : 64;
    size_ = std::max<size_t>((bytes + align - 1) / align * align, align);
    data_ = static_cast<unsigned char*>(std::aligned_alloc(align, size_));
    if (!data_) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    if (align == huge) madvise(data_, size_, MADV_HUGEPAGE);   // a hint: without it the pages are small
#endif
  }
  ~scratch_block() { std::free(data_); }
  scratch_block(const scratch_block&) = delete;
  scratch_block& operator=(const scratch_block&) = delete;
  // The next `count` objects of T, 64-byte aligned; trivially copyable types only, uninitialised.
  template <class T>
  T* take(size_t count) {
    static_assert(std::is_trivially_copyable_v<T>);
    used_ = (used_ + 63) / 64 * 64;
    T* p = reinterpret_cast<T*>(data_ + used_);
    used_ += count * sizeof(T);
    return p;
  }
  static size_t room(size_t count, size_t size) { return (count * size + 63) / 64 * 64; }

 private:
  unsigned char* data_ = nullptr;
  size_t size_ = 0, used_ = 0;
};

struct engine {
  const tree_skeleton& t;
  const std::vector<glm::vec3>& rest;
  wood_params p;
  size_t n;
  bool recover = true;
  bool monotone = false;
  const std::vector<float>* point_mass = nullptr;

  // Parents are read at random (a node's parent was often born many steps earlier), so what a
  // sweep reads of a parent sits in one record; the rest is read in index order.
  // No member initialisers: `at` and `acc` are allocated uninitialised (a forward sweep writes
  // every pose before a reverse sweep reads it, and reverse clears the loads it sums), which
  // saves a pass over tens of megabytes on a large tree.
  struct pose {
    glm::quat frame;               // the rotation of everything beyond the node
    glm::vec3 x;                   // bent position
  };
  struct load {
    glm::vec3 s;                   // first moment of the mass beyond the node
    float m;                       // mass beyond the node
    float pipe;                    // Σ r_tip^n of the pipes through it
  };
  scratch_block block;
  pose* at;
  load* acc;
  glm::vec4* rest_d;               // per internode: unbent vector from its parent (xyz) and length (w)
  glm::quat* bend;                 // per internode: its turn relative to its parent's end frame
  glm::vec3* moment_prev;          // moment at the middle of each internode at the last bend
  uint8_t* clamped;
  float recovery_share[65] = {};   // 1 - (1 - recovery)^k for k young steps
  float max_turn = 0, cos_half_max = 1;

  engine(const tree_skeleton& tree, const std::vector<glm::vec3>& rest_pos, const wood_params& params)
      : t(tree), rest(rest_pos), p(params), n(tree.size()),
        block(scratch_block::room(n, sizeof(pose)) + scratch_block::room(n, sizeof(load)) +
              scratch_block::room(n, sizeof(glm::vec4)) + scratch_block::room(n, sizeof(glm::quat)) +
              scratch_block::room(n, sizeof(glm::vec3)) + scratch_block::room(n, 1)) {
    at = block.take<pose>(n);
    acc = block.take<load>(n);
    rest_d = block.take<glm::vec4>(n);
    bend = block.take<glm::quat>(n);
    moment_prev = block.take<glm::vec3>(n);
    clamped = block.take<uint8_t>(n);
    for (size_t k = 0; k < n; ++k) {
      glm::vec3 d(0);
      if (t.parent[k] >= 0) d = rest[k] - rest[size_t(t.parent[k])];
      rest_d[k] = glm::vec4(d, t.parent[k] >= 0 ? glm::length(d) : 0.0f);
    }
    std::fill(bend, bend + n, glm::quat(1, 0, 0, 0));
    std::fill(moment_prev, moment_prev + n, glm::vec3(0));
    std::fill(clamped, clamped + n, uint8_t(0));
    for (int k = 0; k <= 64; ++k) recovery_share[k] = 1.0f - std::pow(1.0f - p.recovery, float(k));
    max_turn = p.max_bend * pi / 180.0f;
    cos_half_max = std::cos(0.5f * max_turn);
  }

  std::vector<glm::vec3> positions() const {
    std::vector<glm::vec3> out(n);
    for (size_t k = 0; k < n; ++k) out[k] = at[k].x;
    return out;
  }
  const glm::vec3& position(size_t k) const { return at[k].x; }

  bool alive(size_t k, int s) const { return t.born[k] <= s && s < t.died[k]; }

  // The turn of internode k for the bend of step s (previous bend step prev): its moment increase
  // `m` over its stiffness now (squared radius rr2), plus reaction wood. `fp`: its parent's end frame.
  void turn_internode(size_t k, const glm::quat& fp, glm::vec3 m, float rr2, int s, int prev) {
    const glm::vec3 rd(rest_d[k]);
    const float len = rest_d[k].w;
    if (!(len > 1e-9f)) return;
    const float ei = p.modulus * 1e9f * pi * rr2 * rr2 * 0.25f;   // E·I, I = π r⁴ / 4
    const float flex = len / ei;
    const int young = recover && p.recovery > 0
                          ? std::min(s, int(t.born[k]) + p.recovery_age) - std::max(prev + 1, int(t.born[k])) + 1
                          : 0;
    // Without reaction wood the turn is at most |m|·L/(EI) (the projection below only shortens
    // it): when that is already under the skip threshold, nothing below would change the bend.
    if (young <= 0 && glm::dot(m, m) * flex * flex <= 1e-12f) return;
    const glm::vec3 dir = at[k].frame * (rd / len);   // the direction of its tip now
    m -= glm::dot(m, dir) * dir;             // the axial part twists; only the rest bends
    glm::vec3 turn = m * flex;
    // Reaction wood (gravitropic recovery): a young shoot turns its tip back toward its set
    // direction by `recovery` of the angle between them per step it was young in (prev, s].
    {
      if (young > 0) {
        glm::vec3 target = rd / len;
        if (p.recovery_up > 0) {
          const glm::vec3 up = (1 - p.recovery_up) * target + glm::vec3(0, p.recovery_up, 0);
          const float l = glm::length(up);
          if (l > 1e-6f) target = up / l;
        }
        const glm::vec3& tip = dir;
        const glm::vec3 c = glm::cross(tip, target);
        const float sn = glm::length(c);
        if (sn > 1e-7f) {
          const float cs = glm::dot(tip, target);
          const float angle = fast_atan2(sn, cs);
          turn += c * (angle * recovery_share[std::min(young, 64)] / sn);
        }
      }
    }
    const float a2 = glm::dot(turn, turn);
    // Below a microradian a turn moves nothing by more than microns: skip the quaternion work.
    if (!(a2 > 1e-12f)) return;
    if (!(a2 <= max_turn * max_turn)) {  // NaN or a fold: clamp
      turn = std::isfinite(a2) ? turn * (max_turn / std::sqrt(a2)) : glm::vec3(0);
      clamped[k] = 1;
    }
    // World rotation at the joint -> the parent's end frame: q' = rot(R_p⁻¹ θ) q.
    glm::quat b = glm::normalize(rotation_quat(glm::conjugate(fp) * turn) * bend[k]);
    if (b.w < 0) b = -b;
    if (b.w < cos_half_max) {  // the accumulated bend of one internode stays below max_bend
      const glm::vec3 v(b.x, b.y, b.z);
      const float vl = glm::length(v);
      b = vl > 1e-12f ? glm::angleAxis(max_turn, v / vl) : glm::quat(1, 0, 0, 0);
      clamped[k] = 1;
    }
    bend[k] = b;
  }

  // Node k of the forward sweep: its position and frame from its parent's and its bend.
  // clear_load: also zero its load for the reverse sweep that follows (one pass less).
  void forward_node(size_t k, bool clear_load) {
    if (clear_load) acc[k] = load{glm::vec3(0), 0, 0};
    const int32_t par = t.parent[k];
    if (par < 0) {
      at[k].x = rest[k];
      at[k].frame = bend[k];
      return;
    }
    const glm::vec3 rd(rest_d[k]);
    const pose pp = at[size_t(par)];
    const glm::quat& b = bend[k];
    if (b.x == 0 && b.y == 0 && b.z == 0) {  // unbent (young nodes): skip the half rotation
      at[k].x = pp.x + pp.frame * rd;
      at[k].frame = pp.frame;
    } else {
      // The hinge at the middle turns rd by half of b = (w, u). That half is (1 + w, u) / |·|, so
      // it turns rd to rd + u × rd + u × (u × rd) / (1 + w): no square root (w > 0, see turn_internode).
      const glm::vec3 u(b.x, b.y, b.z);
      const glm::vec3 c = glm::cross(u, rd);
      at[k].x = pp.x + pp.frame * (rd + c + glm::cross(u, c) * (1.0f / (1.0f + b.w)));
      at[k].frame = pp.frame * b;
    }
  }

  // One sweep parents-first over [0, end): positions and frames from the bends.
  void forward(size_t end, bool clear_loads) {
    if (!split) {
      for (size_t k = 0; k < end; ++k) forward_node(k, clear_loads);
      return;
    }
    for (const uint32_t e : split->top) {   // the trunk first: the tasks' roots hang from it
      if ((e & ~root_bit) >= end) break;
      if (!(e & root_bit)) forward_node(e, clear_loads);
    }
    parallel_jobs(split->job_end.size(), [&](size_t j) {
      for (size_t i = j ? split->job_end[j - 1] : 0; i < split->job_end[j]; ++i)
        for (const uint32_t* q = split->task_first(i); q != split->task_last(i) && *q < end; ++q)
          forward_node(*q, clear_loads);
    });
  }

  // What one node's reverse step adds to its parent's load (to < 0: nothing).
  struct push {
    glm::vec3 s{0};
    float m = 0, pipe = 0;
    int32_t to = -1;
  };
  void add(const push& u) {
    if (u.to < 0) return;
    load& up = acc[size_t(u.to)];
    up.m += u.m;
    up.s += u.s;
    up.pipe += u.pipe;
  }
  // The reverse sweep's terms for one bend step.
  struct reverse_terms {
    bool pipe = false, square_pipe = false;
    float rt = 0, two_over_e = 0, taper_n = 0, leaf_kg_per_m = 0;
    glm::vec3 g{0};
  };
  reverse_terms terms() const {
    reverse_terms r;
    r.pipe = t.pipe_exponent > 0;
    // The usual exponent 2 (da Vinci's rule): r² is the pipe sum itself, no power needed.
    r.square_pipe = t.pipe_exponent == 2;
    if (r.pipe) {
      r.rt = std::pow(t.pipe_tip_radius, t.pipe_exponent);
      r.two_over_e = 2.0f / t.pipe_exponent;
    }
    r.taper_n = r.pipe && t.pipe_taper > 0 ? t.pipe_exponent : 0.0f;
    r.g = glm::vec3(0, -standard_gravity * p.gravity, 0);
    r.leaf_kg_per_m = p.leaf_mass * 1e-3f * p.leaves_per_metre;
    return r;
  }

  // Node k of the reverse sweep at step s, when it is alive: its radius of that step (pipe radii
  // as compute_pipe_radii in skeleton.cpp, else the fixed one), its load, its internode's moment at
  // the middle, M = Σ m_i (x_i - c) × g, and its turn from the increase since the last bend. The
  // turn changes the bend only: positions follow in the next forward sweep. Returns what it adds to
  // its parent's load.
  push reverse_node(size_t k, int s, int prev, const reverse_terms& r) {
    push out;
    if (!alive(k, s)) return out;
    const int32_t par = t.parent[k];
    load& a = acc[k];
    const glm::vec3 xk = at[k].x;
    float sum = 0, r2;
    if (r.pipe) {
      sum = a.pipe > 0 ? a.pipe : r.rt;
      r2 = r.square_pipe ? sum : fast_pow(sum, r.two_over_e);
    } else {
      r2 = t.radius[k] * t.radius[k];
    }
    r2 = std::max(r2, min_beam_radius * min_beam_radius);
    if (point_mass && k < point_mass->size() && (*point_mass)[k] > 0) {
      a.m += (*point_mass)[k];
      a.s += (*point_mass)[k] * xk;
    }
    if (par < 0) return out;
    const float len = rest_d[k].w;
    // Wood (density × volume, the internode at its tip radius) and the foliage of a young shoot.
    float m = p.density * pi * r2 * len;
    if (s - int(t.born[k]) <= p.leaf_age) m += r.leaf_kg_per_m * len;
    const pose& pp = at[size_t(par)];
    const glm::vec3 seg = xk - pp.x;
    const glm::vec3 c = xk - 0.5f * seg;
    // The internode's own outer half acts at its three-quarter point.
    const float tm = a.m + 0.5f * m;
    const glm::vec3 ts = a.s + (0.5f * m) * (xk - 0.25f * seg);
    const glm::vec3 moment = glm::cross(ts - tm * c, r.g);
    turn_internode(k, pp.frame, moment - moment_prev[k], r2, s, prev);
    moment_prev[k] = moment;
    out.m = a.m + m;
    out.s = a.s + m * c;
    // Disused pipes (skeleton.h): a tapered internode passes (r·(1 + τ·ℓ))^n down.
    out.pipe = r.taper_n > 0 ? sum * std::pow(1.0f + t.pipe_taper * len, r.taper_n) : sum;
    out.to = par;
    return out;
  }

  // One sweep tips-first over the nodes alive at s among [0, end) (forward(end, true) has just
  // cleared their loads). A parent's load sums its children's in falling index order. On the pool
  // each task sums its own nodes' that way and keeps what its root adds to its trunk parent; the
  // trunk's walk, falling through trunk nodes and roots alike, then adds those where the one-thread
  // sweep would: every load is the same sum in the same order.
  void reverse(int s, int prev, size_t end) {
    const reverse_terms r = terms();
    if (!split) {
      for (size_t k = end; k-- > 0;) add(reverse_node(k, s, prev, r));
      return;
    }
    parallel_jobs(split->job_end.size(), [&](size_t j) {
      for (size_t i = j ? split->job_end[j - 1] : 0; i < split->job_end[j]; ++i) {
        const uint32_t* first = split->task_first(i);
        const uint32_t* last = std::lower_bound(first, split->task_last(i), uint32_t(end));   // end ≤ n < root_bit
        push root;
        for (const uint32_t* q = last; q-- != first;) {
          const push u = reverse_node(*q, s, prev, r);
          if (q == first) root = u;
          else add(u);
        }
        split->pending[i] = root;
      }
    });
    size_t task = split->pending.size();
    for (size_t q = split->top.size(); q-- > 0;) {
      const uint32_t e = split->top[q];
      const size_t k = e & ~root_bit;
      if (e & root_bit) --task;
      if (k >= end) continue;
      add(e & root_bit ? split->pending[task] : reverse_node(k, s, prev, r));
    }
  }

  // A large tree's sweeps on the pool (job_pool.h): its subtrees of at most `grain` nodes are
  // tasks, swept on the pool in chunks of about `grain` nodes; the trunk above them (every node
  // with a larger subtree) on the calling thread, before the tasks going forward and after them
  // going back. A node's pose reads only its parent's and each load is summed in the one-thread
  // order (reverse), so the bends are the one-thread pass's bit for bit
  // (JobPool.WoodPassOnThePoolIsTheOneThreadPass). 4 bytes a node while the pass runs.
  struct pool_split {
    std::vector<uint32_t> top;        // trunk nodes and task roots (root_bit set), ascending
    std::vector<uint32_t> nodes;      // every task's nodes, ascending, task after task
    std::vector<uint32_t> task_end;   // task i: nodes[task_end[i - 1], task_end[i])
    std::vector<uint32_t> job_end;    // job j: tasks [job_end[j - 1], job_end[j])
    std::vector<push> pending;        // per task: what its root adds to its trunk parent
    const uint32_t* task_first(size_t i) const { return nodes.data() + (i ? task_end[i - 1] : 0); }
    const uint32_t* task_last(size_t i) const { return nodes.data() + task_end[i]; }
  };
  static constexpr uint32_t root_bit = 0x80000000u;
  // Below about 11,000 nodes the pool saved nothing: a small tree bends at every step, and each
  // sweep's hand-over cost what its half saved. The default tree (19,723 nodes) gains a little:
  // 0.71 to 0.99 of its one-thread time in four runs of sylva_microbench
  // --benchmark_filter=WoodPassDefaultThreads; the 642k tree 0.71.
  static constexpr size_t pool_min_nodes = 16384;
  std::unique_ptr<pool_split> split;   // null: one thread sweeps

  void plan_pool(int threads) {
    if (threads < 2 || n < pool_min_nodes || n >= root_bit) return;
    const uint32_t grain = uint32_t(std::max<size_t>(n / (size_t(threads) * 8), 1024));
    std::vector<uint32_t> a(n, 1);   // subtree sizes, then each node's task (trunk: ~0)
    for (size_t k = n; k-- > 0;) {
      const int32_t par = t.parent[k];
      if (par < 0) continue;
      if (size_t(par) >= k) return;   // a parent after its child: the one-thread order only
      a[size_t(par)] += a[k];
    }
    constexpr uint32_t trunk = ~uint32_t(0);
    auto sp = std::make_unique<pool_split>();
    uint32_t tasks = 0;
    size_t trunk_nodes = 0;
    for (size_t k = 0; k < n; ++k) {
      const int32_t par = t.parent[k];
      if (a[k] > grain) {
        a[k] = trunk;
        sp->top.push_back(uint32_t(k));
        ++trunk_nodes;
      } else if (par < 0 || a[size_t(par)] == trunk) {
        a[k] = tasks++;
        sp->top.push_back(uint32_t(k) | root_bit);
      } else {
        a[k] = a[size_t(par)];
      }
    }
    if (trunk_nodes > n / 4 || tasks < 2) return;   // a long unbranched stem: little to share
    sp->task_end.assign(tasks, 0);
    for (size_t k = 0; k < n; ++k)
      if (a[k] != trunk) ++sp->task_end[a[k]];
    std::vector<uint32_t> cursor(tasks);
    for (uint32_t i = 0, sum = 0; i < tasks; ++i) cursor[i] = sum, sum += sp->task_end[i], sp->task_end[i] = sum;
    sp->nodes.resize(n - trunk_nodes);
    for (size_t k = 0; k < n; ++k)
      if (a[k] != trunk) sp->nodes[cursor[a[k]]++] = uint32_t(k);
    for (uint32_t i = 0, in_job = 0; i < tasks; ++i) {
      in_job += sp->task_end[i] - (i ? sp->task_end[i - 1] : 0);
      if (in_job >= grain || i + 1 == tasks) sp->job_end.push_back(i + 1), in_job = 0;
    }
    sp->pending.resize(tasks);
    split = std::move(sp);
  }

  // Replays the bend steps up to `step`, then leaves the positions of the tree at `step`.
  void run(const std::vector<uint16_t>& steps, int step) {
    plan_pool(job_pool_threads());
    int prev = -1;
    for (uint16_t s : steps) {
      if (int(s) > step) break;
      const size_t reach = prefix_end(s);
      forward(reach, true);
      reverse(s, prev, reach);
      prev = s;
    }
    forward(n, false);
    rest_on_ground();
  }

  // The soil: an internode whose bent tip would lie below ground_rest above its tree's base is
  // turned up about its base until the tip lies at that height, heading where it headed (its
  // length kept); the turn carries everything beyond it. A tree that stays above the soil is
  // left exactly as it is (one scan, no other work).
  void rest_on_ground() {
    if (!(p.ground_rest >= 0) || n < 2) return;
    // Nothing can be below its soil when every node stands above the lowest base's: the common
    // case, found with no allocation.
    float lowest_base = INFINITY, lowest = INFINITY;
    for (size_t k = 0; k < n; ++k) {
      if (t.parent[k] < 0) lowest_base = std::min(lowest_base, rest[k].y);
      else lowest = std::min(lowest, at[k].x.y);
    }
    if (!(lowest < lowest_base + p.ground_rest)) return;
    std::vector<glm::vec3> bent(n);
    std::vector<glm::quat> lift(n, glm::quat(1, 0, 0, 0));
    std::vector<float> base_y(n);
    for (size_t k = 0; k < n; ++k) bent[k] = at[k].x;
    for (size_t k = 0; k < n; ++k) {
      const int32_t par = t.parent[k];
      if (par < 0) {
        base_y[k] = rest[k].y;
        continue;
      }
      const size_t pk = size_t(par);
      base_y[k] = base_y[pk];
      const glm::vec3 d = lift[pk] * (bent[k] - bent[pk]);
      glm::vec3 x = at[pk].x + d;
      lift[k] = lift[pk];
      const float floor_y = base_y[k] + p.ground_rest;
      const float len = glm::length(d);
      if (x.y < floor_y && len > 1e-9f) {
        // Level: the tip at floor_y when the base is above it, else level with the base.
        const float dy = std::clamp(floor_y - at[pk].x.y, -len, 0.0f);
        glm::vec2 h(d.x, d.z);
        const float hl = glm::length(h);
        h = hl > 1e-9f ? h / hl : glm::vec2(1, 0);
        const float hr = std::sqrt(std::max(len * len - dy * dy, 0.0f));
        const glm::vec3 e(h.x * hr, dy, h.y * hr);
        lift[k] = glm::rotation(d / len, e / len) * lift[pk];
        x = at[pk].x + e;
      }
      at[k].x = x;
    }
  }

  // One past the last node born at or before s (all nodes when they are not born in index order).
  size_t prefix_end(int s) const {
    if (!monotone) return n;
    size_t lo = 0, hi = n;
    while (lo < hi) {
      const size_t mid = (lo + hi) / 2;
      if (t.born[mid] <= s) lo = mid + 1;
      else hi = mid;
    }
    return lo;
  }
};

bool born_in_order(const tree_skeleton& t) {
  for (size_t i = 1; i < t.size(); ++i)
    if (t.born[i] < t.born[i - 1]) return false;
  return true;
}

// The steps at which the pass bends the tree. Every step while that costs at most 3 sweeps of the
// final tree; beyond, a step is kept when the tree has grown fourfold since the last kept one
// (counted back from the last step), so a large tree costs about 1.33 sweeps whatever its step count.
std::vector<uint16_t> choose_bend_steps(const tree_skeleton& t, bool monotone) {
  std::vector<size_t> alive_end(size_t(t.steps) + 1, t.size());
  if (monotone) {
    size_t k = 0;
    for (int s = 0; s <= t.steps; ++s) {
      while (k < t.size() && t.born[k] <= s) ++k;
      alive_end[size_t(s)] = k;
    }
  }
  double total = 0;
  for (size_t e : alive_end) total += double(e);
  std::vector<uint16_t> steps;
  if (total <= 3.0 * double(std::max<size_t>(t.size(), 1))) {
    for (int s = 0; s <= t.steps; ++s) steps.push_back(uint16_t(s));
    return steps;
  }
  size_t last = 0;
  for (int s = t.steps; s >= 0; --s)
    if (steps.empty() || double(alive_end[size_t(s)]) * 4 <= double(last) || alive_end[size_t(s)] < 64) {
      steps.push_back(uint16_t(s));
      last = alive_end[size_t(s)];
    }
  std::reverse(steps.begin(), steps.end());
  return steps;
}

void add_message(grow_report* report, const std::string& m) {
  if (!report) return;
  report->message += (report->message.empty() ? "" : "; ") + m;
}

}  // namespace

void apply_wood(tree_skeleton& t, const wood_params& params, grow_report* report) {
  t.wood.reset();
  if (!(params.gravity > 0) || t.size() < 2) return;
  wood_params p = params;
  const std::vector<std::string> fixed = clamp_all_params(p);
  if (!fixed.empty()) {
    std::string keys;
    for (const std::string& k : fixed) keys += (keys.empty() ? "" : ", ") + k;
    add_message(report, "wood: " + keys + " out of range, clamped");
  }
  auto h = std::make_shared<wood_history>();
  h->rest = t.position;
  h->params = p;
  const bool monotone = born_in_order(t);
  h->bend_steps = choose_bend_steps(t, monotone);
  engine e(t, h->rest, p);
  e.monotone = monotone;
  e.run(h->bend_steps, t.steps);
  size_t folds = 0;
  for (size_t k = 0; k < e.n; ++k) folds += e.clamped[k];
  if (folds)
    add_message(report, "wood: " + std::to_string(folds) + " internode" + (folds == 1 ? "" : "s") +
                            " reached the maximum bend; the load is more than the wood can carry (check gravity, "
                            "wood density, Young's modulus and leaf mass)");
  for (leaf& l : t.leaves)
    if (l.node >= 0 && size_t(l.node) < t.size()) l.position += e.position(size_t(l.node)) - h->rest[size_t(l.node)];
  for (size_t k = 0; k < t.size(); ++k) t.position[k] = e.position(k);
  t.wood = std::move(h);
}

std::vector<glm::vec3> positions_at_step(const tree_skeleton& t, int step) {
  if (!t.wood || t.wood->rest.size() != t.size()) return t.position;
  if (step >= t.steps) return t.position;
  engine e(t, t.wood->rest, t.wood->params);
  e.monotone = born_in_order(t);
  e.run(t.wood->bend_steps, std::max(step, 0));
  return e.positions();
}

std::vector<glm::vec3> bend_static(const tree_skeleton& t, const wood_params& p, const std::vector<float>* point_mass) {
  engine e(t, t.position, p);
  e.recover = false;
  e.point_mass = point_mass;
  e.run({uint16_t(std::max(t.steps, 0))}, t.steps);
  return e.positions();
}

}  // namespace sylva
