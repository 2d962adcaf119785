// One small pool of helper threads shared by every parallel job in the process (the mesher's
// stages, the archetype textures): no thread is started per call.
#pragma once

#include <algorithm>
#include <cstddef>
#include <functional>
#include <vector>

namespace sylva {

// Helper threads in the pool: one less than the hardware threads, 1 to 7. Started on first use.
int job_pool_helpers();

// Caps every later parallel_jobs call at this many threads (0: no cap; 1: every job on its calling
// thread, the single-threaded path the parallel one must match bit for bit). Returns the old cap.
int set_job_pool_limit(int threads);

// Threads a parallel_jobs call with no cap of its own may use now: the calling thread and the
// helpers, under the limit above (1: a caller may take its plain one-thread path).
int job_pool_threads();

// Runs job(0) .. job(count - 1), each exactly once, on the calling thread and up to `threads` - 1
// of the pool's helpers (threads <= 0: all of them; 1: the calling thread alone), and returns when
// all are done. Jobs are taken in order from a shared counter, so which thread runs a job varies:
// a job must write only its own outputs for the result to be deterministic. The calling thread
// always works too, so a call made while the helpers are busy (or from inside a job) still ends.
// While helpers finish its last jobs, the calling thread runs jobs of other calls' batches.
// The first exception a job throws is rethrown here once every started job has finished.
void parallel_jobs(size_t count, const std::function<void(size_t)>& job, int threads = 0);

// parallel_jobs over [0, n) in contiguous chunks of about `grain` items: body(begin, end).
void parallel_chunks(size_t n, size_t grain, const std::function<void(size_t, size_t)>& body, int threads = 0);

// Results of items 0 .. count - 1 found in chunks on the pool and taken afterwards in item order
// (the growth's parallel searches: cones, colonization points): chunk c's items write their results
// one after another into chunk[c], and item j's are count(j) from first(j).
template <class T>
struct chunked_results {
  size_t grain = 1;
  std::vector<std::vector<T>> chunk;   // chunk c: items [c·grain, (c + 1)·grain), in order
  std::vector<size_t> end;             // per item: where its results end in its chunk
  size_t begin(size_t j) const { return j % grain ? end[j - 1] : 0; }
  const T* first(size_t j) const { return chunk[j / grain].data() + begin(j); }
  size_t count(size_t j) const { return end[j] - begin(j); }
  // Runs find(c, j, list, n) for every item j of each chunk c in order, in chunks of `grain`
  // items on the pool: it writes item j's results into list from n on (list may be longer) and
  // returns where they end.
  template <class Find>
  void fill(size_t items, size_t chunk_grain, Find find) {
    grain = std::max<size_t>(chunk_grain, 1);
    const size_t chunks = (items + grain - 1) / grain;
    if (chunk.size() < chunks) chunk.resize(chunks);
    end.resize(items);
    parallel_jobs(chunks, [&](size_t c) {
      size_t n = 0;
      for (size_t j = c * grain; j < std::min(items, (c + 1) * grain); ++j) end[j] = n = find(c, j, chunk[c], n);
    });
  }
};

}  // namespace sylva
