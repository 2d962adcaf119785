// One small pool of helper threads shared by every parallel job in the process (the mesher's
// stages, the archetype textures): no thread is started per call.
#pragma once

#include <cstddef>
#include <functional>

namespace sylva {

// Helper threads in the pool: one less than the hardware threads, 1 to 7. Started on first use.
int job_pool_helpers();

// Caps every later parallel_jobs call at this many threads (0: no cap; 1: every job on its calling
// thread, the single-threaded path the parallel one must match bit for bit). Returns the old cap.
int set_job_pool_limit(int threads);

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

}  // namespace sylva
