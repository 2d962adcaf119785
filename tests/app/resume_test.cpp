// Resuming a regrow: when only a keyframe from step k on changed, Honda's L-system starts
// at step k from the state it recorded there, and the tree is the full regrow's, bit for bit.
#include <gtest/gtest.h>

#include <chrono>
#include <climits>
#include <cstring>
#include <thread>
#include <type_traits>

#include "app/common/worker.h"
#include "generators/keyframes.h"
#include "generators/resume.h"
#include "tests/tree_compare.h"

namespace sylva {
namespace {

tree_spec honda(int derivations) {
  tree_spec s;
  lsystem_params p;
  p.derivations = derivations;
  s.params = p;
  return s;
}

void expect_identical(const tree_skeleton& a, const tree_skeleton& b) {
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(std::memcmp(a.position.data(), b.position.data(), a.size() * sizeof(glm::vec3)), 0);
  EXPECT_EQ(std::memcmp(a.radius.data(), b.radius.data(), a.size() * sizeof(float)), 0);
  EXPECT_EQ(a.parent, b.parent);
  EXPECT_EQ(a.born, b.born);
  EXPECT_EQ(a.died, b.died);
  EXPECT_EQ(a.order, b.order);
  EXPECT_EQ(a.steps, b.steps);
}

TEST(Resume, FirstChangedStepComparesKeyframesStepByStep) {
  tree_spec a = honda(10), b = a;
  EXPECT_EQ(first_changed_step(a, b), INT_MAX);
  b.keyframes.push_back({6, "alpha1", glm::vec3(20, 0, 0)});
  EXPECT_EQ(first_changed_step(a, b), 6);
  a.keyframes.push_back({4, "r1", glm::vec3(0.8f, 0, 0)});
  EXPECT_EQ(first_changed_step(a, b), 4);
  b.keyframes.insert(b.keyframes.begin(), {4, "r1", glm::vec3(0.8f, 0, 0)});
  EXPECT_EQ(first_changed_step(a, b), 6);
  b.seed = 2;   // anything but keyframes: no resuming
  EXPECT_EQ(first_changed_step(a, b), 0);
  EXPECT_TRUE(can_resume(a));
  a.params = self_organizing_params{};
  EXPECT_TRUE(can_resume(a));
  a.params = space_colonization_params{};
  EXPECT_TRUE(can_resume(a));
  a.params = guiding_vectors_params{};
  EXPECT_FALSE(can_resume(a));
}

void expect_same_debug(const growth_debug& a, const growth_debug& b) {
  EXPECT_EQ(a.points.size(), b.points.size());
  if (a.points.size() == b.points.size()) {
    EXPECT_EQ(std::memcmp(a.points.data(), b.points.data(), a.points.size() * sizeof(glm::vec3)), 0);
  }
  EXPECT_EQ(a.point_value, b.point_value);
  EXPECT_EQ(a.point_kind, b.point_kind);
  EXPECT_EQ(a.lines.size(), b.lines.size());
  EXPECT_EQ(a.node_fate, b.node_fate);
  EXPECT_EQ(a.node_flow, b.node_flow);
}

// A keyframe edit sequence on `first` (which holds a keyframe of `key` at `k1`): edit it, add one
// of `key2` at `k2` > k1, edit that one, add one at `k0` < k1 (from scratch). Each resumed growth
// equals the full regrow: skeleton, report and the growth_debug the editor draws.
void check_edit_sequence(const tree_spec& first, const char* key2, int k0, int k2) {
  growth_resume r;
  grow_report rep0;
  growth_debug dbg0;
  const tree_skeleton t0 = grow_resumable(first, {}, tree_spec{}, r, &rep0, &dbg0);
  EXPECT_EQ(r.resumed_at, 0);
  expect_identical(t0, grow(first, {}));
  EXPECT_TRUE(rep0.missed_cuts.empty());   // the cut found its branch
  ASSERT_EQ(first.cuts.size(), 1u);
  const int cut_step = first.cuts[0].step;
  EXPECT_GT(std::count_if(t0.died.begin(), t0.died.end(), [&](uint16_t d) { return d == cut_step; }), 0);
  EXPECT_GT(t0.size(), 300u);
  ASSERT_FALSE(first.keyframes.empty());
  const int k1 = first.keyframes.back().step;
  const std::string key1 = first.keyframes.back().key;
  tree_spec recorded = first;
  tree_skeleton before = t0;
  struct edit { const char* what; const char* key; int step; float scale; int resumed; };
  for (const edit& ed : {edit{"edit the keyframe", key1.c_str(), k1, 1.3f, k1}, edit{"add a later one", key2, k2, 0.7f, k1},
                         edit{"edit the added one", key2, k2, 1.2f, k2}, edit{"add an earlier one", key2, k0, 0.8f, 0}}) {
    SCOPED_TRACE(ed.what);
    tree_spec next = recorded;
    bool edited = false;
    for (keyframe& k : next.keyframes)
      if (k.step == ed.step && k.key == ed.key) k.value.x *= ed.scale, edited = true;
    if (!edited) {
      float base = 0;
      std::visit([&](const auto& p) { visit_params(p, [&](const auto& v, const param_info& info) {
                   if constexpr (std::is_arithmetic_v<std::decay_t<decltype(v)>>)
                     if (std::string(info.key) == ed.key) base = float(v);
                 }); }, next.params);
      next.keyframes.push_back({ed.step, ed.key, glm::vec3((base != 0 ? base : 0.3f) * ed.scale, 0, 0)});
      std::stable_sort(next.keyframes.begin(), next.keyframes.end(),
                       [](const keyframe& a, const keyframe& b) { return a.step < b.step; });
    }
    grow_report rep_resumed, rep_full;
    growth_debug dbg_resumed, dbg_full;
    const tree_skeleton resumed = grow_resumable(next, {}, recorded, r, &rep_resumed, &dbg_resumed);
    EXPECT_EQ(r.resumed_at, ed.resumed);
    EXPECT_EQ(r.skipped, 0);
    const tree_skeleton full = grow(next, {}, &rep_full, &dbg_full);
    expect_identical(resumed, full);
    EXPECT_EQ(resumed.leaves.size(), full.leaves.size());
    EXPECT_EQ(rep_resumed.stop_reason, rep_full.stop_reason);
    EXPECT_EQ(rep_resumed.message, rep_full.message);
    EXPECT_EQ(rep_resumed.missed_cuts, rep_full.missed_cuts);
    expect_same_debug(dbg_resumed, dbg_full);
    if (first.wood.gravity == 0) expect_same_up_to(resumed, before, ed.resumed - 1, ed.what);
    recorded = next;
    before = resumed;
  }
}

// Adds a cut at `cut_step` on the first lateral shoot born at `born_step` of the spec's own tree
// (so that resuming has a cut to replay), and switches the wood pass on when asked.
void add_cut_and_wood(tree_spec& s, int born_step, int cut_step, bool wood) {
  const tree_skeleton plain = grow(s, {});
  for (size_t i = 0; i < plain.size(); ++i)
    if (plain.born[i] == born_step && plain.order[i] >= 1) {
      prune_cut c;
      c.step = cut_step;
      c.point = plain.position[i];
      c.reach = 0.02f;
      s.cuts.push_back(c);
      break;
    }
  EXPECT_EQ(s.cuts.size(), 1u);
  if (wood) s.wood.gravity = 1;
}

// A self-organizing tree with a cut (pruning) at step 5 on a branch the tree has then, and the
// wood pass on, or not.
tree_spec so_spec(bool markers, bool wood) {
  tree_spec s = small_spec(0, markers);
  auto& p = std::get<self_organizing_params>(s.params);
  p.steps = markers ? 16 : 14;
  add_cut_and_wood(s, 3, 5, wood);   // a lateral shoot of step 3, cut at step 5
  s.keyframes.push_back({8, "alpha", glm::vec3(p.alpha * 1.2f, 0, 0)});
  return s;
}

TEST(Resume, SelfOrganizingShadowResumedEqualsAFullRegrow) {
  check_edit_sequence(so_spec(false, false), "perception_angle", 3, 11);
}

TEST(Resume, SelfOrganizingShadowWithWoodResumedEqualsAFullRegrow) {
  check_edit_sequence(so_spec(false, true), "sigma", 2, 12);
}

TEST(Resume, SelfOrganizingMarkersResumedEqualsAFullRegrow) {
  check_edit_sequence(so_spec(true, false), "divergence", 4, 12);
}

// Keying opposite phyllotaxis into a spiral growth needs a third bud a node from the first step:
// the spiral growth's snapshots (two buds a node) cannot resume it, so it regrows; once recorded
// with three, a later edit resumes and still equals a full regrow.
TEST(Resume, KeyingOppositePhyllotaxisRegrowsThenResumes) {
  const tree_spec first = so_spec(false, false);
  growth_resume r;
  grow_resumable(first, {}, tree_spec{}, r);
  tree_spec opposite = first;
  opposite.keyframes.push_back({10, "phyllotaxis", glm::vec3(float(int(so_phyllotaxis::opposite)), 0, 0)});
  const tree_skeleton regrown = grow_resumable(opposite, {}, first, r);
  EXPECT_EQ(r.resumed_at, 0);
  const tree_skeleton full = grow(opposite, {});
  expect_identical(regrown, full);
  size_t pairs = 0;   // nodes with two laterals: only from step 10 on
  std::vector<int> laterals(full.size(), 0);
  for (size_t c = 0; c < full.size(); ++c)
    if (full.parent[c] >= 0 && full.order[c] == full.order[size_t(full.parent[c])] + 1) ++laterals[size_t(full.parent[c])];
  for (size_t i = 0; i < full.size(); ++i)
    if (laterals[i] == 2) {
      ++pairs;
      EXPECT_GE(full.born[i], 10) << i;
    }
  EXPECT_GT(pairs, 0u);
  tree_spec later = opposite;
  later.keyframes.push_back({12, "alpha", glm::vec3(2.5f, 0, 0)});
  const tree_skeleton resumed = grow_resumable(later, {}, opposite, r);
  EXPECT_GE(r.resumed_at, 10);   // a kept snapshot of the three-bud growth (at a keyframe's step)
  EXPECT_LE(r.resumed_at, 12);
  expect_identical(resumed, grow(later, {}));
}

// Space colonization resumes from a crown step (the trunk's steps are not recorded): a cut at step
// 18 on a branch of step 16, a keyframe of the segment length D at step 22.
tree_spec sc_spec(bool wood) {
  tree_spec s = small_spec(1);
  auto& p = std::get<space_colonization_params>(s.params);
  EXPECT_GT(grow(s, {}).steps, 30);
  add_cut_and_wood(s, 16, 18, wood);
  s.keyframes.push_back({22, "segment_length", glm::vec3(p.segment_length * 0.8f, 0, 0)});
  return s;
}

TEST(Resume, SpaceColonizationResumedEqualsAFullRegrow) {
  check_edit_sequence(sc_spec(false), "tropism_weight", 17, 27);
}

TEST(Resume, SpaceColonizationWithWoodResumedEqualsAFullRegrow) {
  check_edit_sequence(sc_spec(true), "segment_length", 19, 25);
}

// A keyframe at step 1: the state recorded there is the seedling's, after its RNG draws; resuming
// from it must not place the trees again.
TEST(Resume, SelfOrganizingResumesAtStepOne) {
  for (bool markers : {false, true}) {
    SCOPED_TRACE(markers ? "markers" : "shadow");
    tree_spec first = small_spec(0, markers);
    first.keyframes.push_back({1, "alpha", glm::vec3(2.2f, 0, 0)});
    growth_resume r;
    grow_resumable(first, {}, tree_spec{}, r);
    EXPECT_GT(recorded_bytes(r), 0u);
    tree_spec next = first;
    next.keyframes[0].value.x = 2.4f;
    grow_report a, b;
    const tree_skeleton t = grow_resumable(next, {}, first, r, &a);
    EXPECT_EQ(r.resumed_at, 1);
    expect_identical(t, grow(next, {}, &b));
    EXPECT_EQ(a.message, b.message);
  }
}

// The snapshots are bounded: under a cap too small for any, none is recorded, nothing resumes, and
// the tree is still the full regrow's.
TEST(Resume, SelfOrganizingSnapshotsOverTheCapAreSkipped) {
  const tree_spec first = so_spec(false, false);
  growth_resume r;
  r.byte_cap = 1000;
  grow_resumable(first, {}, tree_spec{}, r);
  EXPECT_EQ(r.skipped, 1);
  tree_spec next = first;
  next.keyframes.back().value.x *= 1.1f;
  const tree_skeleton t = grow_resumable(next, {}, first, r);
  EXPECT_EQ(r.resumed_at, 0);
  expect_identical(t, grow(next, {}));
}

// Keyframes edited and added: each resumed growth is the full regrow's tree, bit for bit (bent by
// the wood pass after it, as grow() does).
TEST(Resume, HondaResumedAtTheChangedStepEqualsAFullRegrow) {
  tree_spec first = honda(12);
  first.keyframes.push_back({6, "alpha1", glm::vec3(25, 0, 0)});
  growth_resume r;
  grow_report rep0;
  const tree_skeleton t0 = grow_resumable(first, {}, tree_spec{}, r, &rep0);
  EXPECT_EQ(r.resumed_at, 0);   // nothing recorded yet: from scratch
  expect_identical(t0, grow(first, {}));
  ASSERT_EQ(r.honda.size(), 13u);   // the top of each of the 12 derivations (index 0 unused)

  tree_spec recorded = first;
  tree_skeleton before = t0;
  struct edit { const char* what; int step; float value; int resumed; };
  // States are recorded at the spec's keyframe steps: an edit resumes from the latest at or before
  // the step it changes.
  for (const edit& ed : {edit{"edit the keyframe at 6", 6, 15.0f, 6}, edit{"add one at 9", 9, 50.0f, 6},
                         edit{"edit the one at 9", 9, 60.0f, 9}, edit{"add one at 3", 3, 40.0f, 0}}) {
    SCOPED_TRACE(ed.what);
    tree_spec next = recorded;
    bool edited = false;
    for (keyframe& k : next.keyframes)
      if (k.step == ed.step) k.value.x = ed.value, edited = true;
    if (!edited) {
      next.keyframes.push_back({ed.step, "phi1", glm::vec3(ed.value, 0, 0)});
      std::stable_sort(next.keyframes.begin(), next.keyframes.end(),
                       [](const keyframe& a, const keyframe& b) { return a.step < b.step; });
    }
    grow_report rep_resumed, rep_full;
    const tree_skeleton resumed = grow_resumable(next, {}, recorded, r, &rep_resumed);
    EXPECT_EQ(r.resumed_at, ed.resumed);
    const tree_skeleton full = grow(next, {}, &rep_full);
    expect_identical(resumed, full);
    EXPECT_EQ(rep_resumed.stop_reason, rep_full.stop_reason);
    EXPECT_EQ(rep_resumed.message, rep_full.message);
    expect_same_up_to(resumed, before, ed.resumed - 1, ed.what);   // and the steps before are the old tree's
    recorded = next;
    before = resumed;
  }
  // A change of anything else regrows from scratch, and still records.
  tree_spec other = recorded;
  std::get<lsystem_params>(other.params).r2 *= 0.9f;
  const tree_skeleton t2 = grow_resumable(other, {}, recorded, r);
  EXPECT_EQ(r.resumed_at, 0);
  expect_identical(t2, grow(other, {}));
  EXPECT_EQ(r.honda.size(), 13u);
}

std::shared_ptr<const grow_result> wait_for(worker_state& w, uint32_t g) {
  uint32_t seen = 0;
  for (int i = 0; i < 3000; ++i) {
    if (auto x = take_result(w, seen)) {
      seen = x->generation;
      if (seen == g) return x;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return nullptr;
}

// A running worker with quick meshing (no leaves, three-sided bark); result_of() posts a spec and waits
// for its tree.
struct test_worker {
  worker_state w;
  mesh_params mesh;
  test_worker() {
    mesh.leaves_enabled = false;
    mesh.radial_segments = 3;
    start_worker(w);
  }
  ~test_worker() { stop_worker(w); }
  std::shared_ptr<const grow_result> result_of(const tree_spec& spec) { return wait_for(w, post_request(w, spec, mesh)); }
};

// The editor's worker resumes a keyframe edit of a tree larger than the estimate's trial (whose
// growth it records): the result says where it resumed and is the full regrow's tree.
TEST(Resume, TheWorkerResumesAKeyframeEdit) {
  tree_spec spec = honda(16);   // 65,535 nodes: grown after the trial, so recorded
  spec.keyframes.push_back({12, "alpha1", glm::vec3(20, 0, 0)});
  test_worker w;
  auto r0 = w.result_of(spec);
  ASSERT_TRUE(r0 && r0->skeleton);
  EXPECT_EQ(r0->resumed_at, 0);
  spec.keyframes[0].value.x = 30;
  auto r1 = w.result_of(spec);
  ASSERT_TRUE(r1 && r1->skeleton);
  EXPECT_EQ(r1->resumed_at, 12);
  expect_identical(*r1->skeleton, grow(spec, {}));
  std::get<lsystem_params>(spec.params).r1 *= 0.95f;   // a base parameter: a full regrow
  auto r2 = w.result_of(spec);
  ASSERT_TRUE(r2 && r2->skeleton);
  EXPECT_EQ(r2->resumed_at, 0);
}

// The same for a self-organizing tree larger than the trial (the default, grown 29 steps), with
// the report and the debug fields the editor shows.
TEST(Resume, TheWorkerResumesASelfOrganizingKeyframeEdit) {
  tree_spec spec;
  self_organizing_params p;
  p.steps = 29;
  spec.params = p;
  spec.keyframes.push_back({24, "lambda", glm::vec3(0.6f, 0, 0)});
  test_worker w;
  auto r0 = w.result_of(spec);
  ASSERT_TRUE(r0 && r0->skeleton);
  EXPECT_GT(r0->skeleton->size(), 20000u);
  EXPECT_EQ(r0->resumed_at, 0);
  spec.keyframes[0].value.x = 0.5f;
  auto r1 = w.result_of(spec);
  ASSERT_TRUE(r1 && r1->skeleton);
  EXPECT_EQ(r1->resumed_at, 24);
  grow_report rep;
  growth_debug dbg;
  expect_identical(*r1->skeleton, grow(spec, {}, &rep, &dbg));
  EXPECT_EQ(r1->report.message, rep.message);
  EXPECT_EQ(r1->report.stop_reason, rep.stop_reason);
  ASSERT_TRUE(r1->debug);
  expect_same_debug(*r1->debug, dbg);
}

}  // namespace
}  // namespace sylva
