// Benchmark of the volume fill (issue 4). Inputs as boundary recovery hands
// them over (generated, tests/support/volume_inputs.h): a torus (a closed
// vessel-like tube, non-convex, its staggered surface triangles Delaunay
// faces of the points: constrained, the inside flood-filled), a sphere, a
// cube or a capped cylinder (convex: hull faces constrained), at several
// resolutions; the Delaunay of the surface points ("build", the stand-in
// for recovery) is timed apart. Then fill_volume: size field, refinement,
// optimization. Per resolution, the median over runs of: tetrahedra,
// inserted points, refinement points/s, refinement / optimization / fill
// wall time, fill CPU time (thread clock: the machine may be shared),
// final gamma_t (min, mean, fractions below 0.2 and 0.3, histogram with
// --hist) and the peak resident memory of the run (each run in its own
// child process, so the peak is that run's, input included).
//
// usage: volume_bench [--runs N] [--shape torus|sphere|cube|cylinder]
//                     [--n n1,n2,...] [--gradation g] [--core H] [--hist]
//                     [--no-optimize]
// --n is the resolution: torus: cells around the tube (2.5 n along it);
// sphere: icosphere levels; cube: intervals per edge; cylinder: points
// per circumference.
#include <sys/resource.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "bench/bench_util.h"
#include "core/quality/tet_quality.h"
#include "core/util/allocator_tuning.h"
#include "core/volume/fill_volume.h"
#include "tests/support/volume_inputs.h"

namespace {

struct RunResult {
  double build_s, fill_s, fill_cpu_s, refine_s, optimize_s, points_per_s, surface_triangles;
  double tets, inserted, qmin, qmean, peak_mb;
  double below[4];  // fraction of tets below 0.1, 0.2, 0.3, 0.5
  double hist[20];
};

bool make_input(const std::string& shape, int n, vm::testing::VolumeInput* in) {
  if (shape == "torus") return vm::testing::torus_input(int(2.5 * n), n, 3, 1, in);
  if (shape == "sphere") return vm::testing::convex_input(vm::testing::sphere_points(n), in);
  if (shape == "cube") return vm::testing::convex_input(vm::testing::cube_surface_points(n), in);
  if (shape == "cylinder")
    return vm::testing::convex_input(vm::testing::capped_cylinder_points(1.0, 6.0, 2 * M_PI / n),
                                     in);
  return false;
}

using vm::bench::median;
using vm::bench::median_of;

bool run_once(const std::string& shape, int n, const vm::FillOptions& fo, RunResult* out) {
  using clock = std::chrono::steady_clock;
  auto t0 = clock::now();
  vm::testing::VolumeInput in;
  if (!make_input(shape, n, &in)) {
    std::fprintf(stderr, "could not make the input %s %d\n", shape.c_str(), n);
    return false;
  }
  out->build_s = std::chrono::duration<double>(clock::now() - t0).count();
  out->surface_triangles = double(in.surface.num_triangles());
  vm::bench::FillRun fill;
  if (!vm::bench::timed_fill(in.kernel, in.sizes, fo, &fill)) return false;
  const vm::FillStats& st = fill.stats;
  const std::vector<float>& q = fill.quality;
  const vm::QualityStats& qs = fill.summary;
  out->fill_cpu_s = fill.cpu_s;
  out->fill_s = st.seconds;
  out->refine_s = st.refine_seconds;
  out->optimize_s = st.optimize_seconds;
  out->points_per_s = st.refine.inserted / std::max(1e-9, st.refine_seconds);
  out->tets = double(st.tets);
  out->inserted = double(st.inserted_vertices);
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
  std::string shape = "torus";
  std::vector<int> ns = {32, 85, 141};
  bool hist = false;
  vm::FillOptions fo;
  fo.gradation = 0.1;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() { return i + 1 < argc ? std::string(argv[++i]) : std::string(); };
    if (a == "--runs") {
      runs = std::max(1, std::atoi(next().c_str()));
    } else if (a == "--shape") {
      shape = next();
    } else if (a == "--n") {
      ns.clear();
      std::string s = next();
      for (size_t pos = 0; pos <= s.size();) {
        size_t end = s.find(',', pos);
        if (end == std::string::npos) end = s.size();
        ns.push_back(std::atoi(s.substr(pos, end - pos).c_str()));
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
                   "usage: volume_bench [--runs N] [--shape torus|sphere|cube|cylinder] "
                   "[--n n1,...] [--gradation g] [--core H] [--hist] [--no-optimize]\n");
      return 2;
    }
  }
  std::printf("shape %s, gradation %g, core %g, median of %d runs (each in its own process)\n",
              shape.c_str(), fo.gradation, fo.core_size, runs);
  std::printf("%5s %8s %9s %8s %7s %10s %8s %8s %7s %8s %6s %6s %7s %7s %7s\n", "n", "surf_tri",
              "tets", "new_pts", "build_s", "refine_pt/s", "refine_s", "optim_s", "fill_s",
              "fill_cpu", "min", "mean", "<0.2", "<0.3", "peak_MB");
  for (int n : ns) {
    std::vector<RunResult> rs;
    for (int r = 0; r < runs; ++r) {
      RunResult res{};
      if (!vm::bench::run_in_child([&](RunResult* out) { return run_once(shape, n, fo, out); },
                                   &res, &res.peak_mb)) {
        std::fprintf(stderr, "run failed for n = %d\n", n);
        return 1;
      }
      rs.push_back(res);
    }
    auto med = [&](double RunResult::*f) { return median_of(rs, f); };
    std::vector<double> b2, b3;
    for (const auto& r : rs) b2.push_back(r.below[1]), b3.push_back(r.below[2]);
    std::printf(
        "%5d %8.0f %9.0f %8.0f %7.2f %10.0f %8.2f %8.2f %7.2f %8.2f %6.3f %6.3f %7.1e %7.1e "
        "%7.0f\n",
        n, med(&RunResult::surface_triangles), med(&RunResult::tets), med(&RunResult::inserted),
        med(&RunResult::build_s), med(&RunResult::points_per_s), med(&RunResult::refine_s),
        med(&RunResult::optimize_s), med(&RunResult::fill_s), med(&RunResult::fill_cpu_s),
        med(&RunResult::qmin), med(&RunResult::qmean), median(b2), median(b3),
        med(&RunResult::peak_mb));
    if (hist) {
      std::printf("  gamma_t histogram (fraction per 0.05 bin, first run):");
      for (int i = 0; i < 20; ++i) std::printf(" %.4f", rs[0].hist[i]);
      std::printf("\n");
    }
    std::fflush(stdout);
  }
  return 0;
}
