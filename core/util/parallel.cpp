// The thread pool behind parallel_for (parallel.h): workers sleep on a
// condition variable; a loop hands out its chunks through an atomic counter,
// the caller taking chunks too, and waits until every chunk is done.
#include "core/util/parallel.h"

#include <algorithm>
#include <atomic>
#include <exception>

#ifndef VM_THREADS
#define VM_THREADS 1
#endif

#if VM_THREADS
#include <condition_variable>
#include <mutex>
#include <thread>
#endif

namespace vm {
namespace {

std::atomic<int> requested_threads{0};  // 0: all cores
std::atomic<int> thread_limit{0};       // 0: no cap

/// Runs chunks [first, ...) of a loop taken from `next` until none is left;
/// the first exception is kept in `error`.
struct Loop {
  size_t n = 0, grain = 1, chunks = 0;
  const std::function<void(size_t, size_t)>* fn = nullptr;
  std::atomic<size_t> next{0};
  std::atomic<size_t> done{0};
  std::exception_ptr error;
  std::atomic<bool> failed{false};

  /// Takes and runs chunks; returns how many this thread ran.
  size_t work() {
    size_t ran = 0;
    for (size_t c = next.fetch_add(1); c < chunks; c = next.fetch_add(1), ++ran) {
      try {
        (*fn)(c * grain, std::min(n, (c + 1) * grain));
      } catch (...) {
        if (!failed.exchange(true)) error = std::current_exception();
      }
    }
    return ran;
  }
};

thread_local bool inside_loop = false;

#if VM_THREADS

int hardware_threads() { return std::max(1, int(std::thread::hardware_concurrency())); }

class Pool {
 public:
  ~Pool() { resize(0); }

  /// Runs `loop` with `helpers` workers besides the caller.
  void run(Loop& loop, int helpers) {
    std::unique_lock<std::mutex> busy(run_mutex_, std::try_to_lock);
    if (!busy.owns_lock()) {  // another thread's loop is running: this one runs alone
      loop.done += loop.work();
      return;
    }
    if (int(workers_.size()) != helpers) resize(helpers);
    {
      std::lock_guard<std::mutex> lock(mutex_);
      loop_ = &loop;
      ++generation_;
    }
    wake_.notify_all();
    const size_t ran = loop.work();
    std::unique_lock<std::mutex> lock(mutex_);
    loop.done += ran;
    finished_.wait(lock, [&] { return loop.done.load() == loop.chunks && running_ == 0; });
    loop_ = nullptr;
  }

 private:
  void resize(int helpers) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    for (std::thread& t : workers_) t.join();
    workers_.clear();
    stop_ = false;
    // A worker starts from the generation before the next loop, however
    // late its thread begins.
    for (int i = 0; i < helpers; ++i) workers_.emplace_back([this, g = generation_] { serve(g); });
  }

  void serve(uint64_t seen) {
    inside_loop = true;
    std::unique_lock<std::mutex> lock(mutex_);
    while (true) {
      wake_.wait(lock, [&] { return stop_ || (loop_ && generation_ != seen); });
      if (stop_) return;
      seen = generation_;
      Loop* loop = loop_;
      ++running_;
      lock.unlock();
      const size_t ran = loop->work();
      lock.lock();
      loop->done += ran;
      --running_;
      finished_.notify_all();
    }
  }

  std::mutex run_mutex_;  // one loop at a time
  std::mutex mutex_;
  std::condition_variable wake_, finished_;
  std::vector<std::thread> workers_;
  Loop* loop_ = nullptr;
  uint64_t generation_ = 0;
  int running_ = 0;
  bool stop_ = false;
};

Pool& pool() {
  static Pool p;
  return p;
}

#endif

}  // namespace

void set_thread_count(int n) { requested_threads = std::max(0, n); }

void set_thread_limit(int n) { thread_limit = std::max(0, n); }

bool threads_supported() { return VM_THREADS != 0; }

int thread_count() {
#if VM_THREADS
  const int n = requested_threads.load(), limit = thread_limit.load();
  const int wanted = n > 0 ? n : hardware_threads();
  return limit > 0 ? std::min(wanted, limit) : wanted;
#else
  return 1;
#endif
}

void parallel_for(size_t n, size_t grain, const std::function<void(size_t, size_t)>& fn) {
  if (n == 0) return;
  Loop loop;
  loop.n = n;
  loop.grain = std::max<size_t>(1, grain);
  loop.chunks = (n + loop.grain - 1) / loop.grain;
  loop.fn = &fn;
  const int threads = int(std::min(size_t(thread_count()), loop.chunks));
  if (threads <= 1 || inside_loop) {
    loop.work();
  } else {
#if VM_THREADS
    inside_loop = true;
    pool().run(loop, threads - 1);
    inside_loop = false;
#endif
  }
  if (loop.error) std::rethrow_exception(loop.error);
}

}  // namespace vm
