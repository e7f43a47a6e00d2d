// Benchmark of the volume fill (issue 4): a sphere or a capped cylinder
// surface at several sizes, tetrahedralized as boundary recovery hands it
// over (the Delaunay of the surface points, hull faces constrained; its
// time is reported apart), then refined to the graded size field and
// optimized. Per size, the median over runs of: refinement points/s,
// optimization time, total fill time, final gamma_t (min, mean,
// histogram), and the peak resident memory of a run (each run in its own
// child process, so the peak is that run's).
//
// usage: volume_bench [--runs N] [--shape sphere|cylinder|cube]
//                     [--h h1,h2,...] [--gradation g] [--core H] [--hist]
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "core/quality/tet_quality.h"
#include "core/util/allocator_tuning.h"
#include "core/volume/tetrahedralize.h"
#include "tests/support/volume_inputs.h"

namespace {

struct RunResult {
  double build_s, fill_s, refine_s, optimize_s, points_per_s;
  double tets, inserted, qmin, qmean, peak_mb;
  double below[4];  // fraction of tets below 0.1, 0.2, 0.3, 0.5
  double hist[20];
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::vector<double> surface_points(const std::string& shape, double h) {
  if (shape == "cube")
    return vm::testing::cube_surface_points(std::max(2, int(std::lround(1 / h))));
  if (shape == "cylinder") return vm::testing::capped_cylinder_points(1.0, 6.0, h);
  // Sphere: the icosphere level whose edge is closest to h, then scaled so
  // that its edges are about h.
  int level = 0;
  while (level < 9 && 1.1 / std::pow(2.0, level + 0.5) > h) ++level;
  auto p = vm::testing::sphere_points(level, 1.0);
  return p;
}

bool run_once(const std::string& shape, double h, const vm::FillOptions& fo, RunResult* out) {
  using clock = std::chrono::steady_clock;
  auto t0 = clock::now();
  vm::testing::VolumeInput in;
  if (!vm::testing::convex_input(surface_points(shape, h), &in)) return false;
  out->build_s = std::chrono::duration<double>(clock::now() - t0).count();
  vm::FillStats st;
  auto res = vm::fill_volume(in.kernel, in.sizes, fo, &st);
  if (!res.ok()) {
    std::fprintf(stderr, "fill_volume: %s\n", res.message().c_str());
    return false;
  }
  out->fill_s = st.seconds;
  out->refine_s = st.refine_seconds;
  out->optimize_s = st.optimize_seconds;
  out->points_per_s = st.refine.inserted / std::max(1e-9, st.refine_seconds);
  out->tets = double(st.tets);
  out->inserted = double(st.inserted_vertices);
  auto q = vm::tet_qualities(res.value());
  auto qs = vm::quality_stats(q, 20);
  out->qmin = qs.min;
  out->qmean = qs.mean;
  const double thr[4] = {0.1, 0.2, 0.3, 0.5};
  for (int i = 0; i < 4; ++i)
    out->below[i] = double(std::count_if(q.begin(), q.end(), [&](float x) { return x < thr[i]; })) /
                    double(q.size());
  for (int i = 0; i < 20; ++i) out->hist[i] = double(qs.histogram[size_t(i)]) / double(q.size());
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  vm::keep_freed_memory_for_reuse();
  int runs = 3;
  std::string shape = "sphere";
  std::vector<double> hs = {0.08, 0.035, 0.02};
  bool hist = false;
  vm::FillOptions fo;
  fo.gradation = 0.0;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() { return i + 1 < argc ? std::string(argv[++i]) : std::string(); };
    if (a == "--runs") {
      runs = std::max(1, std::atoi(next().c_str()));
    } else if (a == "--shape") {
      shape = next();
    } else if (a == "--h") {
      hs.clear();
      std::string s = next();
      for (size_t pos = 0; pos <= s.size();) {
        size_t end = s.find(',', pos);
        if (end == std::string::npos) end = s.size();
        hs.push_back(std::atof(s.substr(pos, end - pos).c_str()));
        pos = end + 1;
      }
    } else if (a == "--gradation") {
      fo.gradation = std::atof(next().c_str());
    } else if (a == "--core") {
      fo.core_size = std::atof(next().c_str());
    } else if (a == "--hist") {
      hist = true;
    } else if (a == "--no-optimize") {
      fo.optimize = false;
    } else {
      std::fprintf(stderr,
                   "usage: volume_bench [--runs N] [--shape sphere|cylinder|cube] [--h h1,...] "
                   "[--gradation g] [--core H] [--hist] [--no-optimize]\n");
      return 2;
    }
  }
  std::printf("shape %s, gradation %g, core %g, median of %d runs (each in its own process)\n",
              shape.c_str(), fo.gradation, fo.core_size, runs);
  std::printf("%8s %9s %9s %8s %10s %9s %9s %9s %7s %7s %7s %7s %8s\n", "h", "tets", "new_pts",
              "build_s", "refine_pt/s", "refine_s", "optim_s", "fill_s", "min", "mean", "<0.2",
              "<0.3", "peak_MB");
  for (double h : hs) {
    std::vector<RunResult> rs;
    for (int r = 0; r < runs; ++r) {
      int fds[2];
      if (pipe(fds) != 0) return 1;
      const pid_t pid = fork();
      if (pid == 0) {
        close(fds[0]);
        RunResult res{};
        const bool ok = run_once(shape, h, fo, &res);
        if (ok && write(fds[1], &res, sizeof(res)) != ssize_t(sizeof(res))) _exit(1);
        _exit(ok ? 0 : 1);
      }
      close(fds[1]);
      RunResult res{};
      const ssize_t got = read(fds[0], &res, sizeof(res));
      close(fds[0]);
      int status = 0;
      struct rusage ru {};
      wait4(pid, &status, 0, &ru);
      if (got != ssize_t(sizeof(res)) || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        std::fprintf(stderr, "run failed for h = %g\n", h);
        return 1;
      }
      res.peak_mb = double(ru.ru_maxrss) / 1024.0;
      rs.push_back(res);
    }
    auto med = [&](double RunResult::*f) {
      std::vector<double> v;
      for (const auto& r : rs) v.push_back(r.*f);
      return median(v);
    };
    std::vector<double> b2, b3;
    for (const auto& r : rs) b2.push_back(r.below[1]), b3.push_back(r.below[2]);
    std::printf("%8.4f %9.0f %9.0f %8.3f %10.0f %9.3f %9.3f %9.3f %7.3f %7.3f %7.1e %7.1e %8.0f\n",
                h, med(&RunResult::tets), med(&RunResult::inserted), med(&RunResult::build_s),
                med(&RunResult::points_per_s), med(&RunResult::refine_s),
                med(&RunResult::optimize_s), med(&RunResult::fill_s), med(&RunResult::qmin),
                med(&RunResult::qmean), median(b2), median(b3), med(&RunResult::peak_mb));
    if (hist) {
      std::printf("  gamma_t histogram (fraction per 0.05 bin, first run):");
      for (int i = 0; i < 20; ++i) std::printf(" %.4f", rs[0].hist[i]);
      std::printf("\n");
    }
    std::fflush(stdout);
  }
  return 0;
}
