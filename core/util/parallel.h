// Data-parallel loops on a small pool of standard threads (docs/ARCHITECTURE.md,
// "Threads"). Work is cut into chunks that depend only on the loop's length
// and grain, never on the number of threads, so that results combined chunk
// by chunk in chunk order are the same with any thread count: a mesh must not
// depend on the machine it was made on. Builds without threads (the
// single-threaded WebAssembly module) run every loop on the calling thread.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace vm {

/// Sets the number of threads loops may use, the calling one included:
/// n >= 1, or 0 for all of the machine's cores (the default). Without
/// thread support it stays 1.
void set_thread_count(int n);

/// Caps the number of threads loops may use, whatever set_thread_count
/// asks: n >= 1, or 0 for no cap (the default). The threaded WebAssembly
/// module sets it to the size of its pool of Web Workers plus one, since a
/// thread it has no Worker for cannot start while the caller blocks.
void set_thread_limit(int n);

/// The number of threads loops use now (>= 1).
int thread_count();

/// Whether this build can run threads at all.
bool threads_supported();

/// Calls fn(begin, end) once for each chunk [c * grain, min(n, (c + 1) *
/// grain)) of [0, n), spread over the threads, the caller included, and
/// returns when all are done. `grain` > 0. Chunks may run in any order and
/// at the same time: fn must only write what its chunk owns. A loop started
/// from inside another runs on its caller's thread. An exception thrown by
/// fn is rethrown here (the first one; the other chunks still run).
void parallel_for(size_t n, size_t grain, const std::function<void(size_t, size_t)>& fn);

/// The sum of fn(begin, end) (a T) over the chunks of parallel_for, added in
/// chunk order starting from T{}: with a single chunk (n <= grain) exactly
/// what a plain loop gives.
template <class T, class Fn>
T parallel_sum(size_t n, size_t grain, Fn&& fn) {
  std::vector<T> parts((n + grain - 1) / grain);
  parallel_for(n, grain, [&](size_t begin, size_t end) { parts[begin / grain] = fn(begin, end); });
  T total{};
  for (const T& p : parts) total += p;
  return total;
}

/// The indices i in [0, n) with pred(i), ascending (pred runs on the
/// threads, chunk by chunk).
template <class Pred>
std::vector<int32_t> parallel_select(size_t n, size_t grain, Pred&& pred) {
  std::vector<std::vector<int32_t>> parts((n + grain - 1) / grain);
  parallel_for(n, grain, [&](size_t begin, size_t end) {
    std::vector<int32_t>& part = parts[begin / grain];
    for (size_t i = begin; i < end; ++i)
      if (pred(i)) part.push_back(int32_t(i));
  });
  std::vector<int32_t> out;
  for (const std::vector<int32_t>& p : parts) out.insert(out.end(), p.begin(), p.end());
  return out;
}

}  // namespace vm
