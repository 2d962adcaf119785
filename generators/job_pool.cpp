// The shared helper threads (job_pool.h).
#include "generators/job_pool.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

namespace sylva {
namespace {

struct batch {
  const std::function<void(size_t)>* job = nullptr;
  size_t count = 0;
  std::atomic<size_t> next{0}, done{0};
  std::atomic<int> seats{0};   // helpers that may still join
  std::mutex mutex;
  std::condition_variable finished;
  std::exception_ptr error;

  // Takes jobs until none is left; true when this thread finished the last one.
  void work() {
    for (size_t k; (k = next.fetch_add(1)) < count;) {
      try {
        (*job)(k);
      } catch (...) {
        std::lock_guard<std::mutex> lock(mutex);
        if (!error) error = std::current_exception();
      }
      if (done.fetch_add(1) + 1 == count) {
        std::lock_guard<std::mutex> lock(mutex);
        finished.notify_all();
      }
    }
  }
};

class pool {
 public:
  pool() {
    const unsigned hw = std::thread::hardware_concurrency();
    const int helpers = std::clamp(int(hw) - 1, 1, 7);
    for (int i = 0; i < helpers; ++i) threads_.emplace_back([this] { run(); });
  }
  ~pool() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      quit_ = true;
    }
    wake_.notify_all();
    for (std::thread& t : threads_) t.join();
  }
  int helpers() const { return int(threads_.size()); }
  void post(const std::shared_ptr<batch>& b) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      queue_.push_back(b);
    }
    wake_.notify_all();
  }
  // A batch other than `own` with a seat and jobs left, its seat taken (as a helper takes it), or
  // null: a caller waiting for its own batch's last jobs helps with the others meanwhile.
  std::shared_ptr<batch> take_other(const batch* own) {
    std::lock_guard<std::mutex> lock(mutex_);
    for (auto it = queue_.begin(); it != queue_.end(); ++it) {
      const std::shared_ptr<batch> b = *it;
      if (b.get() == own || b->next.load() >= b->count) continue;
      if (b->seats.fetch_sub(1) <= 1) queue_.erase(it);
      return b;
    }
    return nullptr;
  }
  void retire(const std::shared_ptr<batch>& b) {
    std::lock_guard<std::mutex> lock(mutex_);
    std::erase(queue_, b);
  }

 private:
  void run() {
    for (;;) {
      std::shared_ptr<batch> b;
      {
        std::unique_lock<std::mutex> lock(mutex_);
        wake_.wait(lock, [&] { return quit_ || !queue_.empty(); });
        if (quit_) return;
        b = queue_.front();
        // A batch leaves the queue when its seats are taken or its jobs all handed out.
        if (b->seats.fetch_sub(1) <= 1 || b->next.load() >= b->count) queue_.pop_front();
      }
      b->work();
    }
  }
  std::vector<std::thread> threads_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<std::shared_ptr<batch>> queue_;
  bool quit_ = false;
};

std::atomic<int> limit{0};

pool& the_pool() {
  static pool p;   // started on first use, so a process that forks before meshing forks no threads
  return p;
}

}  // namespace

int job_pool_helpers() { return the_pool().helpers(); }

int set_job_pool_limit(int threads) { return limit.exchange(std::max(threads, 0)); }

int job_pool_threads() {
  const int all = job_pool_helpers() + 1, cap = limit.load();
  return cap > 0 ? std::min(cap, all) : all;
}

void parallel_jobs(size_t count, const std::function<void(size_t)>& job, int threads) {
  if (count == 0) return;
  if (const int cap = limit.load(); cap > 0) threads = threads <= 0 ? cap : std::min(threads, cap);
  if (threads == 1 || count == 1) {
    for (size_t k = 0; k < count; ++k) job(k);
    return;
  }
  pool& p = the_pool();
  auto b = std::make_shared<batch>();
  b->job = &job;
  b->count = count;
  const int helpers = threads <= 0 ? p.helpers() : std::min(threads - 1, p.helpers());
  b->seats = int(std::min<size_t>(size_t(helpers), count - 1));
  if (b->seats > 0) p.post(b);
  b->work();
  // While helpers finish this batch's last jobs, the calling thread takes jobs of other batches
  // (a helper's nested ones: the leaves placed beside the bark), looking again every 50 µs.
  while (b->done.load() != b->count) {
    if (const std::shared_ptr<batch> other = p.take_other(b.get())) {
      other->work();
      continue;
    }
    std::unique_lock<std::mutex> lock(b->mutex);
    b->finished.wait_for(lock, std::chrono::microseconds(50), [&] { return b->done.load() == b->count; });
  }
  if (b->seats > 0) p.retire(b);
  if (b->error) std::rethrow_exception(b->error);
}

void parallel_chunks(size_t n, size_t grain, const std::function<void(size_t, size_t)>& body, int threads) {
  grain = std::max<size_t>(grain, 1);
  const size_t chunks = (n + grain - 1) / grain;
  parallel_jobs(chunks, [&](size_t c) { body(c * grain, std::min(n, (c + 1) * grain)); }, threads);
}

}  // namespace sylva
