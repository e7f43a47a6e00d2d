// Benchmark: 3D Delaunay kernel throughput (points per second, including
// the BRIO/Hilbert sort), median of several runs, for random points in a
// cube, on a sphere, and on a cylinder surface plus its interior (a vessel-
// like mix of surface and volume points). The median thread CPU time is
// printed beside the wall time (the machine may be shared). --constrained
// also times, after each build, the insertion of n/4 more points of the same
// kind (in BRIO order) in constrained mode after one flip (the refinement path: the kernel
// is no longer Delaunay, insert(p, hint, true)). --threads N (default 1) runs the build's
// partitioned rounds on N threads; --parts P sets their slab count
// (DelaunayBuildOptions::parts; 1: sequential). --cgal compares with CGAL's sequential
// Delaunay_triangulation_3 (thread CPU time against ours: wall time with threads) and,
// with threads and TBB (libtbb-dev), with its parallel one on as many threads (wall time).
//
// usage: delaunay_bench [--runs N] [--sizes 100000,1000000] [--kinds cube,sphere,cylinder]
//                       [--constrained] [--cgal] [--threads N] [--parts P]
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "bench/bench_util.h"
#include "core/util/allocator_tuning.h"
#include "core/util/parallel.h"
#include "core/volume/delaunay3d.h"

#ifdef VM_HAVE_CGAL
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#endif
#ifdef VM_HAVE_CGAL_TBB
#include <CGAL/Bbox_3.h>
#include <tbb/global_control.h>
#endif

namespace {

using vm::bench::median;
using vm::bench::thread_cpu;

std::vector<double> make_points(const std::string& kind, int n, uint32_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::normal_distribution<double> g;
  std::vector<double> p;
  p.reserve(3 * size_t(n));
  for (int i = 0; i < n; ++i) {
    if (kind == "cube") {
      p.insert(p.end(), {u(rng), u(rng), u(rng)});
    } else if (kind == "sphere") {
      double v[3] = {g(rng), g(rng), g(rng)};
      double l = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
      p.insert(p.end(), {v[0] / l, v[1] / l, v[2] / l});
    } else {  // cylinder radius 1, length 10: half the points on the wall
      double a = 2 * M_PI * u(rng), z = 10 * u(rng);
      double r = i % 2 ? 1.0 : std::sqrt(u(rng));
      p.insert(p.end(), {r * std::cos(a), r * std::sin(a), z});
    }
  }
  return p;
}

#ifdef VM_HAVE_CGAL
/// CGAL's Delaunay triangulation of pts (3 doubles each): thread CPU
/// seconds of the construction (the conversion to CGAL points excluded),
/// and its finite cells into *cells.
double cgal_build_cpu(const std::vector<double>& pts, size_t* cells) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  std::vector<K::Point_3> p;
  p.reserve(pts.size() / 3);
  for (size_t i = 0; i + 2 < pts.size(); i += 3) p.emplace_back(pts[i], pts[i + 1], pts[i + 2]);
  const double c0 = thread_cpu();
  CGAL::Delaunay_triangulation_3<K> dt(p.begin(), p.end());
  const double c = thread_cpu() - c0;
  *cells = dt.number_of_finite_cells();
  return c;
}
#endif

#ifdef VM_HAVE_CGAL_TBB
/// CGAL's parallel Delaunay triangulation of pts on `threads` TBB threads
/// (its lock grid of 50^3 cells over the points' box, as in CGAL's
/// examples): wall seconds of the construction.
double cgal_parallel_build_wall(const std::vector<double>& pts, int threads, size_t* cells) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Tds = CGAL::Triangulation_data_structure_3<CGAL::Triangulation_vertex_base_3<K>,
                                                   CGAL::Delaunay_triangulation_cell_base_3<K>,
                                                   CGAL::Parallel_tag>;
  using PDT = CGAL::Delaunay_triangulation_3<K, Tds>;
  std::vector<K::Point_3> p;
  p.reserve(pts.size() / 3);
  for (size_t i = 0; i + 2 < pts.size(); i += 3) p.emplace_back(pts[i], pts[i + 1], pts[i + 2]);
  const CGAL::Bbox_3 box = CGAL::bbox_3(p.begin(), p.end());
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
  const auto t0 = std::chrono::steady_clock::now();
  PDT::Lock_data_structure locks(box, 50);
  PDT dt(p.begin(), p.end(), &locks);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  *cells = dt.number_of_finite_cells();
  return s;
}
#endif

}  // namespace

int main(int argc, char** argv) {
  vm::keep_freed_memory_for_reuse();
  int runs = 5;
  std::vector<int> sizes = {100000, 1000000};
  std::vector<std::string> kinds = {"cube", "sphere", "cylinder"};
  bool constrained = false, cgal = false;
  int threads = 1;
  vm::DelaunayBuildOptions build_options;
  auto split = [](const std::string& s) {
    std::vector<std::string> out;
    for (size_t pos = 0; pos <= s.size();) {
      size_t end = s.find(',', pos);
      if (end == std::string::npos) end = s.size();
      out.push_back(s.substr(pos, end - pos));
      pos = end + 1;
    }
    return out;
  };
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    if (a == "--runs" && i + 1 < argc) {
      runs = std::max(1, std::atoi(argv[++i]));
    } else if (a == "--sizes" && i + 1 < argc) {
      sizes.clear();
      for (const auto& s : split(argv[++i])) sizes.push_back(std::atoi(s.c_str()));
    } else if (a == "--kinds" && i + 1 < argc) {
      kinds = split(argv[++i]);
    } else if (a == "--threads" && i + 1 < argc) {
      threads = std::max(1, std::atoi(argv[++i]));
    } else if (a == "--parts" && i + 1 < argc) {
      build_options.parts = std::atoi(argv[++i]);
    } else if (a == "--constrained") {
      constrained = true;
    } else if (a == "--cgal") {
#ifdef VM_HAVE_CGAL
      cgal = true;
#else
      std::fprintf(stderr,
                   "delaunay_bench: built without CGAL (install libcgal-dev, reconfigure)\n");
      return 2;
#endif
    } else {
      std::fprintf(stderr,
                   "usage: delaunay_bench [--runs N] [--sizes N1,...] [--kinds K1,...] "
                   "[--constrained] [--cgal] [--threads N] [--parts P]\n");
      return 2;
    }
  }
  vm::set_thread_count(threads);
  std::printf("%-9s %9s %6s %10s %14s %10s %14s %8s %9s %9s %9s\n", "points", "n", "runs",
              "median_s", "points_per_s", "cpu_s", "points_per_cpu_s", "tets/pt", "steps/pt",
              "cavity", "created");
  for (const std::string& kind : kinds) {
    for (int n : sizes) {
      std::vector<double> times, cpu, ccpu, cgal_cpu, cgal_wall;
      size_t tets = 0, cgal_cells = 0;
      int64_t steps = 0, cavity = 0, created = 0;
      for (int r = 0; r < runs; ++r) {
        std::vector<double> pts = make_points(kind, n, uint32_t(r + 1));
#ifdef VM_HAVE_CGAL
        if (cgal) cgal_cpu.push_back(cgal_build_cpu(pts, &cgal_cells));
#endif
#ifdef VM_HAVE_CGAL_TBB
        if (cgal && threads > 1)
          cgal_wall.push_back(cgal_parallel_build_wall(pts, threads, &cgal_cells));
#endif
        auto t0 = std::chrono::steady_clock::now();
        const double c0 = thread_cpu();
        auto d = vm::Delaunay3D::build(std::move(pts), build_options);
        cpu.push_back(thread_cpu() - c0);
        auto t1 = std::chrono::steady_clock::now();
        if (!d.ok()) {
          std::fprintf(stderr, "%s\n", d.message().c_str());
          return 1;
        }
        times.push_back(std::chrono::duration<double>(t1 - t0).count());
        tets = d.value().num_finite_tets();
        steps = d.value().stats().walk_steps;
        cavity = d.value().stats().cavity_tets;
        created = d.value().stats().boundary_faces;
        if (!constrained) continue;
        vm::Delaunay3D& k = d.value();
        for (int32_t t = 0; t < int32_t(k.tet_capacity()); ++t)
          if (k.is_live(t) && !k.is_ghost(t) && k.flip23(t, 0).ok()) break;
        const int m = n / 4;
        std::vector<double> more = make_points(kind, m, uint32_t(r + 101));
        const std::vector<int32_t> order = vm::brio_hilbert_order(more);
        const double c1 = thread_cpu();
        int32_t hint = -1;
        for (int32_t i : order) {
          auto ins = k.insert(&more[3 * size_t(i)], hint, true);
          if (ins.status == vm::Delaunay3D::InsertStatus::kInserted)
            hint = k.vertex_tet(ins.vertex);
        }
        ccpu.push_back(thread_cpu() - c1);
      }
      // With threads the caller's CPU time misses the others': wall time.
      const double t = median(times), c = threads > 1 ? t : median(cpu);
      std::printf("%-9s %9d %6d %10.4f %14.0f %10.4f %14.0f %8.2f %9.2f %9.2f %9.2f\n",
                  kind.c_str(), n, runs, t, n / t, c, n / c, double(tets) / n, double(steps) / n,
                  double(cavity) / n, double(created) / n);
      if (cgal)
        std::printf(
            "  CGAL Delaunay_triangulation_3: cpu %.4f s, %.0f points/cpu s, %.2f tets/pt; "
            "ours %.2fx CGAL's points/cpu s\n",
            median(cgal_cpu), n / median(cgal_cpu), double(cgal_cells) / n, median(cgal_cpu) / c);
      if (!cgal_wall.empty())
        std::printf(
            "  CGAL parallel (Parallel_tag, TBB, %d threads): wall %.4f s, %.0f points/s; "
            "ours %.2fx CGAL's parallel points/s\n",
            threads, median(cgal_wall), n / median(cgal_wall), median(cgal_wall) / t);
      if (constrained)
        std::printf("  constrained insertion of %d more: cpu %.4f s, %.0f points/cpu s\n", n / 4,
                    median(ccpu), (n / 4) / median(ccpu));
      std::fflush(stdout);
    }
  }
  return 0;
}
