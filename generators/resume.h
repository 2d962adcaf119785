// Resuming a regrow: when only keyframes from step k on changed, a generator that keeps
// its state at the top of every step can start at step k from the state it recorded there, instead
// of growing steps 1..k-1 again. The result is the full regrow's, bit for bit (tests/app/resume_test.cpp).
//
// Honda's L-system keeps such state (its apices, the tree so far, its working params), and so does
// the self-organizing generator (the tree, its RNG, working params, shadow grid or markers, and its
// per-node bud, flow and direction arrays), and space colonization's crown loop (the tree, the point
// grid with its nearest-node caches, per-node growth counts). Guiding vectors always regrow in full.
#pragma once

#include <climits>
#include <memory>
#include <vector>

#include "generators/tree_spec.h"

namespace sylva {

struct honda_state;   // generators/honda.cpp: Honda's state at the top of a derivation
struct so_snapshot;   // generators/self_organizing.cpp: the self-organizing state at the top of a step
struct sc_snapshot;   // generators/space_colonization.cpp: the crown loop's state at the top of a step

// Passed to grow() in grow_options::resume. With `from_step` > 0 a generator that supports it
// starts at the top of that step from its recorded state; with `record` it records its state at
// the top of the steps in `record_steps` (every step when empty) that it grows, replacing what was
// recorded from its first step on. Resuming from any recorded step at or before the first changed
// one is correct: grow_resumable takes the latest.
struct growth_resume {
  int from_step = 0;
  bool record = true;
  std::vector<int> record_steps;
  std::vector<std::shared_ptr<const honda_state>> honda;   // [k]: the state at the top of step k
  std::vector<std::shared_ptr<const so_snapshot>> self_organizing;   // likewise
  std::vector<std::shared_ptr<const sc_snapshot>> space_colonization;   // crown steps only
  // Self-organizing snapshots copy the shadow grid or markers too: a snapshot that would take the
  // recorded total past this many bytes is not recorded (counted in `skipped`).
  size_t byte_cap = size_t(512) << 20;
  int skipped = 0;                                         // out: snapshots left out by byte_cap
  int resumed_at = 0;                                      // out: the step growth started at (0: from scratch)
};

// The bytes held by the recorded self-organizing and space-colonization snapshots.
size_t recorded_bytes(const growth_resume& r);

// The first step whose keyframes differ between the two specs; INT_MAX when the specs are equal,
// 0 when anything but the keyframes differs (the generator, params, seed, wood or cuts).
int first_changed_step(const tree_spec& a, const tree_spec& b);

// Whether this spec's generator can resume (Honda's L-system, the self-organizing generator, space
// colonization from a crown step).
bool can_resume(const tree_spec& spec);

// Grows `spec`, resuming from `r` when `r` was recorded for `recorded` and only keyframes from a
// step at or after one it holds changed; records the new growth's states into `r` either way, at
// the spec's keyframe steps only (a snapshot costs a copy of the tree so far, and Honda's steps are
// cheap: recording every step cost more than the steps it saved). Same as grow() otherwise.
tree_skeleton grow_resumable(const tree_spec& spec, const grow_options& o, const tree_spec& recorded, growth_resume& r,
                             grow_report* report = nullptr, growth_debug* debug = nullptr);

}  // namespace sylva
