// Benchmark: boundary-layer extrusion (core/layers, Marchandise et al.
// section 2.2) on a remeshed bifurcation phantom of about 100k wall
// triangles: the viscous layer (4 layers, 0.2 R) and the vessel wall
// (4 layers, 0.1 R), medians of several runs with the per-phase split, next
// to the other stages of the pipeline on the same wall (remeshing, caps of
// the front, boundary recovery of the core) so the layer stage's share of
// the whole can be read off. CPU time is printed beside wall time since the
// machine may be shared.
//
// usage: layers_bench [--runs N] [--size H] [--voxel V] [--no-verify] [--no-measure]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <vector>

#include "bench/bench_util.h"
#include "core/layers/extrude_layers.h"
#include "core/mesh/chord_radius.h"
#include "core/phantom/vessel_phantom.h"
#include "core/surface/cap_openings.h"
#include "core/surface/remesh_surface.h"
#include "core/util/allocator_tuning.h"
#include "core/volume/boundary_recovery.h"

namespace {

using vm::bench::median;

struct Timer {
  std::chrono::steady_clock::time_point wall0 = std::chrono::steady_clock::now();
  std::clock_t cpu0 = std::clock();
  double wall() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  }
  double cpu() const { return double(std::clock() - cpu0) / CLOCKS_PER_SEC; }
};

}  // namespace

int main(int argc, char** argv) {
  vm::keep_freed_memory_for_reuse();
  int runs = 5;
  double size = 0.045, voxel = 0.06;
  bool verify = true, measure = true;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--runs" && i + 1 < argc) {
      runs = std::atoi(argv[++i]);
    } else if (a == "--size" && i + 1 < argc) {
      size = std::atof(argv[++i]);
    } else if (a == "--voxel" && i + 1 < argc) {
      voxel = std::atof(argv[++i]);
    } else if (a == "--no-verify") {
      verify = false;
    } else if (a == "--no-measure") {
      measure = false;
    } else {
      std::fprintf(stderr,
                   "usage: layers_bench [--runs N] [--size H] [--voxel V] [--no-verify] "
                   "[--no-measure]\n");
      return 2;
    }
  }

  vm::PhantomOptions po;
  po.kind = vm::PhantomKind::kBifurcation;
  po.voxel = voxel;
  po.noise = 0.3;
  auto raw = vm::make_vessel_phantom(po);
  if (!raw.ok()) return std::fprintf(stderr, "%s\n", raw.message().c_str()), 1;
  vm::RemeshOptions ro;
  ro.size.mode = vm::SizeMode::kUniform;
  ro.size.size = size;
  Timer t_remesh;
  auto remeshed = vm::remesh_surface(raw.value(), ro);
  const double remesh_wall = t_remesh.wall(), remesh_cpu = t_remesh.cpu();
  if (!remeshed.ok()) return std::fprintf(stderr, "%s\n", remeshed.message().c_str()), 1;
  const vm::SurfaceMesh& wall = remeshed.value().mesh;
  std::printf("wall: %zu triangles, %zu vertices (phantom %zu triangles, h = %g)\n",
              wall.num_triangles(), wall.num_vertices(), raw.value().num_triangles(), size);
  std::printf("remesh: %.3f s wall, %.3f s CPU\n", remesh_wall, remesh_cpu);

  Timer t_radius;
  const std::vector<double> radius = vm::chord_radius(wall);
  std::printf("chord_radius: %.3f s wall, %.3f s CPU\n", t_radius.wall(), t_radius.cpu());

  double layer_total = 0;
  vm::LayerMesh inward;
  for (bool outward : {false, true}) {
    vm::LayerSpec spec;
    spec.outward = outward;
    spec.thickness_fraction = outward ? 0.1 : 0.2;
    spec.verify_intersections = verify;
    std::vector<double> wall_s, cpu_s, dir, gap, val, ver, mea;
    vm::LayerStats st;
    for (int r = 0; r < runs; ++r) {
      Timer t;
      auto res = vm::extrude_layers(wall, radius, spec, &st);
      wall_s.push_back(t.wall());
      cpu_s.push_back(t.cpu());
      if (!res.ok()) return std::fprintf(stderr, "%s\n", res.message().c_str()), 1;
      dir.push_back(st.seconds_directions);
      gap.push_back(st.seconds_gap);
      val.push_back(st.seconds_validity);
      ver.push_back(st.seconds_verify);
      mea.push_back(st.seconds_measure);
      if (!outward) inward = std::move(res).value();
    }
    layer_total += median(cpu_s);
    if (measure) {  // once more with the distance measurements, for the accuracy
      spec.measure = true;
      if (!vm::extrude_layers(wall, radius, spec, &st).ok()) return 1;
    }
    std::printf(
        "%s (%s): %.3f s wall, %.3f s CPU (median of %d); phases (wall): directions %.3f, "
        "gap %.3f, validity %.3f, verify %.3f, stats %.3f\n",
        outward ? "vessel wall" : "viscous layer", outward ? "4 x 0.1 R" : "4 x 0.2 R",
        median(wall_s), median(cpu_s), runs, median(dir), median(gap), median(val), median(ver),
        median(mea));
    std::printf(
        "  reduced area %.3f%% (min factor %.3f), total within 10%% on %.2f%% of the area, "
        "measured first/total within 10%% on %.2f%% / %.2f%%, front gamma min %.3f mean %.3f "
        "(wall min %.3f), rounds %d\n",
        100 * st.reduced_area_fraction, st.min_factor, 100 * st.thickness_within_10pct,
        100 * st.measured_first_within_10pct, 100 * st.measured_total_within_10pct,
        st.front_quality_min, st.front_quality_mean, st.wall_quality_min, st.rounds);
  }

  // The core of the lumen on the same wall: caps of the front, recovery.
  Timer t_caps;
  auto capped = vm::cap_openings(vm::front_surface(inward), {});
  const double caps_wall = t_caps.wall(), caps_cpu = t_caps.cpu();
  if (!capped.ok()) return std::fprintf(stderr, "%s\n", capped.message().c_str()), 1;
  Timer t_rec;
  auto rec = vm::recover_boundary(capped.value().mesh.points, capped.value().mesh.triangles,
                                  capped.value().triangle_tag);
  const double rec_wall = t_rec.wall(), rec_cpu = t_rec.cpu();
  if (!rec.ok()) return std::fprintf(stderr, "%s\n", rec.message().c_str()), 1;
  std::printf(
      "front caps %.3f s wall %.3f s CPU, core boundary recovery %.3f s wall %.3f s CPU (%zu "
      "tets, %lld Steiner points)\n",
      caps_wall, caps_cpu, rec_wall, rec_cpu, rec.value().mesh.num_tets(),
      (long long)rec.value().steiner_points);
  const double others = remesh_cpu + caps_cpu + rec_cpu;
  std::printf(
      "layer stage (both layers) %.3f s CPU = %.1f%% of remesh + layers + caps + recovery (%.3f "
      "s CPU; reading, refinement and writing not counted, so the true share is smaller)\n",
      layer_total, 100 * layer_total / (layer_total + others), layer_total + others);
  return 0;
}
