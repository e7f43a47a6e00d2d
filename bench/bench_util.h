// Helpers shared by the native benchmarks: the thread CPU clock (the
// machine may be shared), medians, one run in a child process with its
// peak resident memory, and one timed fill_volume with its gamma_t.
#pragma once

#include <sys/resource.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <type_traits>
#include <vector>

#include "core/quality/tet_quality.h"
#include "core/volume/fill_volume.h"

namespace vm::bench {

/// CPU seconds used by this thread.
inline double thread_cpu() {
  timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

/// Median of v (the mean of the two middle values for an even count).
inline double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/// Median over runs of one field of a result struct.
template <class R>
double median_of(const std::vector<R>& runs, double R::*field) {
  std::vector<double> v;
  for (const R& r : runs) v.push_back(r.*field);
  return median(v);
}

/// Runs run(&result) in a child process (so the peak resident memory is
/// that run's) and copies `result` back through a pipe; *peak_mb gets the
/// child's peak. False if the run failed. R must be trivially copyable.
template <class R, class F>
bool run_in_child(F&& run, R* result, double* peak_mb) {
  static_assert(std::is_trivially_copyable_v<R>);
  int fds[2];
  if (pipe(fds) != 0) return false;
  const pid_t pid = fork();
  if (pid < 0) return false;
  if (pid == 0) {
    close(fds[0]);
    const bool ok = run(result);
    if (ok && write(fds[1], result, sizeof(R)) != ssize_t(sizeof(R))) _exit(1);
    _exit(ok ? 0 : 1);
  }
  close(fds[1]);
  const ssize_t got = read(fds[0], result, sizeof(R));
  close(fds[0]);
  int status = 0;
  struct rusage ru {};
  wait4(pid, &status, 0, &ru);
  *peak_mb = double(ru.ru_maxrss) / 1024.0;
  return got == ssize_t(sizeof(R)) && WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

/// One fill_volume, timed, with the gamma_t of its tetrahedra.
struct FillRun {
  FillStats stats;
  double cpu_s = 0;            ///< thread CPU time of the call
  std::vector<float> quality;  ///< gamma_t per tetrahedron
  QualityStats summary;        ///< of quality, 20 bins
};

/// Fills the region of `kernel` (sizes: one per kernel vertex); false,
/// with a message on stderr, on error.
inline bool timed_fill(Delaunay3D& kernel, const std::vector<double>& sizes,
                       const FillOptions& options, FillRun* out) {
  const double c0 = thread_cpu();
  auto filled = fill_volume(kernel, sizes, options, &out->stats);
  out->cpu_s = thread_cpu() - c0;
  if (!filled.ok()) {
    std::fprintf(stderr, "fill_volume: %s\n", filled.message().c_str());
    return false;
  }
  out->quality = tet_qualities(filled.value());
  out->summary = quality_stats(out->quality, 20);
  return true;
}

}  // namespace vm::bench
