// Benchmark of the volume stages on real data (issue: volume speed): the
// pipeline of `vesselmesh mesh IN --size H --layers 0` up to the capped
// surface is run once (or read from a cache file), then, per run, each in
// its own child process: boundary recovery and fill_volume (refinement,
// optimization), exactly as core/pipeline/mesh_job.cpp calls them, timed
// with the thread CPU clock (the machine may be shared) beside wall time;
// the tetrahedra's gamma_t and the peak resident memory of the run.
//
// usage: arch_volume_bench [--stl FILE] [--size H] [--core H] [--runs N]
//                          [--cache FILE] [--inline] [--threads T]
// --inline runs once in this process (for perf / callgrind).
#include <sys/resource.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "bench/bench_util.h"
#include "core/pipeline/mesh_job.h"
#include "core/pipeline/option_table.h"
#include "core/quality/tet_quality.h"
#include "core/surface/cap_openings.h"
#include "core/util/allocator_tuning.h"
#include "core/util/parallel.h"
#include "core/volume/boundary_recovery.h"
#include "core/volume/fill_volume.h"

namespace {

struct Capped {
  std::vector<double> points, sizes;
  std::vector<int32_t> triangles, tags;
};

struct RunResult {
  double recovery_s, recovery_cpu, refine_s, optimize_s, fill_s, fill_cpu;
  double tets, inserted, qmin, qmean, below02, peak_mb, steiner;
};

using vm::bench::median_of;
using vm::bench::thread_cpu;

template <class T>
void put(std::ofstream& f, const std::vector<T>& v) {
  const uint64_t n = v.size();
  f.write(reinterpret_cast<const char*>(&n), sizeof(n));
  f.write(reinterpret_cast<const char*>(v.data()), std::streamsize(n * sizeof(T)));
}
template <class T>
bool get(std::ifstream& f, std::vector<T>& v) {
  uint64_t n = 0;
  if (!f.read(reinterpret_cast<char*>(&n), sizeof(n))) return false;
  v.resize(n);
  return bool(f.read(reinterpret_cast<char*>(v.data()), std::streamsize(n * sizeof(T))));
}

// Mean length of the edges at each vertex (mesh_job.cpp's mean_edge_lengths).
std::vector<double> mean_edge_lengths(const std::vector<double>& pts,
                                      const std::vector<int32_t>& tr) {
  std::vector<double> sum(pts.size() / 3, 0.0), cnt(pts.size() / 3, 0.0);
  for (size_t t = 0; t < tr.size(); t += 3)
    for (int k = 0; k < 3; ++k) {
      const int32_t a = tr[t + size_t(k)], b = tr[t + size_t((k + 1) % 3)];
      const double* p = &pts[3 * size_t(a)];
      const double* q = &pts[3 * size_t(b)];
      const double l = std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                                 (p[2] - q[2]) * (p[2] - q[2]));
      for (int32_t v : {a, b}) sum[size_t(v)] += l, cnt[size_t(v)] += 1;
    }
  for (size_t v = 0; v < sum.size(); ++v) sum[v] = cnt[v] > 0 ? sum[v] / cnt[v] : 0;
  return sum;
}

bool make_capped(const std::string& stl, double size, Capped* out) {
  std::ifstream f(stl, std::ios::binary);
  if (!f) return false;
  std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  vm::MeshJobOptions o;
  if (!vm::set_option_text(o, "size", std::to_string(size)).ok()) return false;
  o.viscous.layers = 0;
  o.volume = false;
  auto r = vm::run_mesh_job(bytes, o);
  if (!r.ok()) {
    std::fprintf(stderr, "mesh job: %s\n", r.message().c_str());
    return false;
  }
  const vm::SurfaceMesh& wall = r.value().output_surface;
  // Uniform mode: the remeshing's target size is h at every wall vertex.
  std::vector<double> wall_sizes(wall.num_vertices(), size);
  auto capped = vm::cap_openings(wall, wall_sizes);
  if (!capped.ok()) {
    std::fprintf(stderr, "caps: %s\n", capped.message().c_str());
    return false;
  }
  out->points = capped.value().mesh.points;
  out->triangles = capped.value().mesh.triangles;
  out->tags = capped.value().triangle_tag;
  out->sizes = mean_edge_lengths(out->points, out->triangles);
  std::copy(wall_sizes.begin(), wall_sizes.end(), out->sizes.begin());
  return true;
}

bool run_once(const Capped& in, double core, RunResult* out) {
  using clock = std::chrono::steady_clock;
  auto t0 = clock::now();
  double c0 = thread_cpu();
  auto rec = vm::recover_boundary(in.points, in.triangles, in.tags);
  out->recovery_cpu = thread_cpu() - c0;
  out->recovery_s = std::chrono::duration<double>(clock::now() - t0).count();
  if (!rec.ok()) {
    std::fprintf(stderr, "recovery: %s\n", rec.message().c_str());
    return false;
  }
  out->steiner = double(rec.value().steiner_points);
  // Sizes as mesh_job.cpp: Steiner points get their parent triangle's mean.
  std::vector<double> size = in.sizes;
  const size_t surface_vertices = size.size();
  const vm::VolumeMesh& m = rec.value().mesh;
  size.resize(m.num_vertices(), 0.0);
  for (size_t t = 0; t < m.num_triangles(); ++t) {
    const int32_t* parent = &in.triangles[3 * size_t(rec.value().triangle_parent[t])];
    for (int k = 0; k < 3; ++k) {
      const size_t v = size_t(m.triangles[3 * t + size_t(k)]);
      if (v >= surface_vertices && size[v] == 0)
        size[v] = (size[size_t(parent[0])] + size[size_t(parent[1])] + size[size_t(parent[2])]) / 3;
    }
  }
  vm::FillOptions fo;
  fo.core_size = core;
  vm::bench::FillRun fill;
  if (!vm::bench::timed_fill(rec.value().kernel, size, fo, &fill)) return false;
  const vm::FillStats& fs = fill.stats;
  const vm::Delaunay3D::Stats& ks = rec.value().kernel.stats();
  std::fprintf(stderr,
               "  kernel (recovery and refinement): %lld tets removed, %lld created, %lld shrunk "
               "and %lld checked cavities, %lld walk steps\n",
               (long long)ks.cavity_tets, (long long)ks.boundary_faces,
               (long long)ks.shrunk_cavities, (long long)ks.checked_cavities,
               (long long)ks.walk_steps);
  out->fill_cpu = fill.cpu_s;
  out->fill_s = fs.seconds;
  out->refine_s = fs.refine_seconds;
  out->optimize_s = fs.optimize_seconds;
  out->tets = double(fs.tets);
  out->inserted = double(fs.inserted_vertices);
  out->qmin = fill.summary.min;
  out->qmean = fill.summary.mean;
  out->below02 = double(
      std::count_if(fill.quality.begin(), fill.quality.end(), [](float x) { return x < 0.2f; }));
  std::fprintf(stderr,
               "  refine: %lld inserted, %lld candidates (rejected: %lld spacing, %lld boundary, "
               "%lld outside, %lld kernel), %lld size evals, %d rounds, %lld deferred, first layer "
               "%.2f s; "
               "optimize: flips %.2f s, smooth %.2f s, slivers %.2f s (%lld flips23, %lld edge "
               "removals, %lld smoothing moves, %lld sliver moves, %lld insertions)\n",
               (long long)fs.refine.inserted, (long long)fs.refine.candidates,
               (long long)fs.refine.rejected_spacing, (long long)fs.refine.rejected_boundary,
               (long long)fs.refine.rejected_outside, (long long)fs.refine.rejected_kernel,
               (long long)fs.refine.size_evaluations, fs.refine.rounds,
               (long long)fs.refine.deferred, fs.refine.first_layer_seconds,
               fs.optimize.flip_seconds, fs.optimize.smooth_seconds, fs.optimize.sliver_seconds,
               (long long)fs.optimize.flips23, (long long)fs.optimize.edge_removals,
               (long long)fs.optimize.smoothing_moves, (long long)fs.optimize.sliver_moves,
               (long long)fs.optimize.insertions);
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  vm::keep_freed_memory_for_reuse();
  std::string stl = "../shared/data/vascular/aortic-arch.stl";
  std::string cache;
  double size = 0.06, core = -1;
  int runs = 3;
  bool inline_run = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() { return i + 1 < argc ? std::string(argv[++i]) : std::string(); };
    if (a == "--stl")
      stl = next();
    else if (a == "--size")
      size = std::atof(next().c_str());
    else if (a == "--core")
      core = std::atof(next().c_str());
    else if (a == "--runs")
      runs = std::max(1, std::atoi(next().c_str()));
    else if (a == "--cache")
      cache = next();
    else if (a == "--inline")
      inline_run = true;
    else if (a == "--threads")
      vm::set_thread_count(std::max(0, std::atoi(next().c_str())));
    else {
      std::fprintf(stderr,
                   "usage: arch_volume_bench [--stl FILE] [--size H] [--core H] [--runs N] "
                   "[--cache FILE] [--inline] [--threads T]\n");
      return 2;
    }
  }
  if (core < 0) core = size;  // the CLI's default in uniform mode
  Capped in;
  bool have = false;
  if (!cache.empty()) {
    std::ifstream f(cache, std::ios::binary);
    have = f && get(f, in.points) && get(f, in.sizes) && get(f, in.triangles) && get(f, in.tags);
  }
  if (!have) {
    if (!make_capped(stl, size, &in)) return 1;
    if (!cache.empty()) {
      std::ofstream f(cache, std::ios::binary);
      put(f, in.points), put(f, in.sizes), put(f, in.triangles), put(f, in.tags);
    }
  }
  std::printf("capped surface: %zu vertices, %zu triangles; core %g; median of %d runs\n",
              in.points.size() / 3, in.triangles.size() / 3, core, runs);
  std::vector<RunResult> rs;
  for (int r = 0; r < runs; ++r) {
    RunResult res{};
    if (inline_run) {
      if (!run_once(in, core, &res)) return 1;
      struct rusage ru {};
      getrusage(RUSAGE_SELF, &ru);
      res.peak_mb = double(ru.ru_maxrss) / 1024.0;
    } else if (!vm::bench::run_in_child([&](RunResult* out) { return run_once(in, core, out); },
                                        &res, &res.peak_mb)) {
      std::fprintf(stderr, "run failed\n");
      return 1;
    }
    std::printf(
        "run %d: recovery %.2f s (cpu %.2f), refine %.2f s, optimize %.2f s, fill %.2f s (cpu "
        "%.2f); %.0f tets, %.0f new points, gamma_t min %.4f mean %.4f, %.0f below 0.2; %.0f MB\n",
        r + 1, res.recovery_s, res.recovery_cpu, res.refine_s, res.optimize_s, res.fill_s,
        res.fill_cpu, res.tets, res.inserted, res.qmin, res.qmean, res.below02, res.peak_mb);
    std::fflush(stdout);
    rs.push_back(res);
  }
  auto med = [&](double RunResult::*f) { return median_of(rs, f); };
  std::printf(
      "median: recovery %.2f s (cpu %.2f), refine %.2f s, optimize %.2f s, fill %.2f s (cpu "
      "%.2f), volume cpu %.2f s; %.0f tets, min %.4f mean %.4f; peak %.0f MB\n",
      med(&RunResult::recovery_s), med(&RunResult::recovery_cpu), med(&RunResult::refine_s),
      med(&RunResult::optimize_s), med(&RunResult::fill_s), med(&RunResult::fill_cpu),
      med(&RunResult::recovery_cpu) + med(&RunResult::fill_cpu), med(&RunResult::tets),
      med(&RunResult::qmin), med(&RunResult::qmean), med(&RunResult::peak_mb));
  return 0;
}
