// Resuming a regrow (issue 18): when only a keyframe from step k on changed, Honda's L-system starts
// at step k from the state it recorded there, and the tree is the full regrow's, bit for bit.
#include <gtest/gtest.h>

#include <chrono>
#include <climits>
#include <cstring>
#include <thread>

#include "app/worker.h"
#include "generators/keyframes.h"
#include "generators/resume.h"
#include "tree_compare.h"

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
  EXPECT_FALSE(can_resume(a));
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

// The editor's worker resumes a keyframe edit of a tree larger than the estimate's trial (whose
// growth it records): the result says where it resumed and is the full regrow's tree.
TEST(Resume, TheWorkerResumesAKeyframeEdit) {
  tree_spec spec = honda(16);   // 65,535 nodes: grown after the trial, so recorded
  spec.keyframes.push_back({12, "alpha1", glm::vec3(20, 0, 0)});
  mesh_params mesh;
  mesh.leaves_enabled = false;
  mesh.radial_segments = 3;
  worker_state w;
  start_worker(w);
  auto r0 = wait_for(w, post_request(w, spec, mesh));
  ASSERT_TRUE(r0 && r0->skeleton);
  EXPECT_EQ(r0->resumed_at, 0);
  spec.keyframes[0].value.x = 30;
  auto r1 = wait_for(w, post_request(w, spec, mesh));
  ASSERT_TRUE(r1 && r1->skeleton);
  EXPECT_EQ(r1->resumed_at, 12);
  expect_identical(*r1->skeleton, grow(spec, {}));
  std::get<lsystem_params>(spec.params).r1 *= 0.95f;   // a base parameter: a full regrow
  auto r2 = wait_for(w, post_request(w, spec, mesh));
  ASSERT_TRUE(r2 && r2->skeleton);
  EXPECT_EQ(r2->resumed_at, 0);
  stop_worker(w);
}

}  // namespace
}  // namespace sylva
