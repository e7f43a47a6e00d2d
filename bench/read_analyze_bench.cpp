// Benchmark: read + weld + repair + analysis (+ gamma_k) throughput, native.
// Median of several runs per input; peak resident memory of the process.
//
// usage: read_analyze_bench [--runs N] [--threads N] [--stages] [--generated-voxel V]
//                           [FILES.stl...]
//   --threads N: threads the loops may use (default: all cores)
//   --stages: also the median seconds of each stage of the preparation
//   FILES: STL files read in place (e.g. ../shared/data/vascular/*.stl)
//   --generated-voxel V: also bench a generated bifurcation phantom at voxel V
//     (0.0115 gives about 2M triangles); 0 disables. Default 0.0123.
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

#include "bench/bench_util.h"
#include "core/io/stl.h"
#include "core/phantom/vessel_phantom.h"
#include "core/pipeline/prepare_surface.h"
#include "core/util/allocator_tuning.h"
#include "core/util/parallel.h"

namespace {

struct Input {
  std::string name;
  std::vector<uint8_t> bytes;
};

using vm::bench::median;

double peak_rss_mb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_maxrss) / 1024.0;
}

}  // namespace

int main(int argc, char** argv) {
  vm::keep_freed_memory_for_reuse();  // as the CLI does
  int runs = 7;
  bool stages = false;
  double voxel = 0.0115;
  std::vector<Input> inputs;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    if (a == "--runs" && i + 1 < argc) {
      runs = std::max(1, std::atoi(argv[++i]));
    } else if (a == "--threads" && i + 1 < argc) {
      vm::set_thread_count(std::atoi(argv[++i]));
    } else if (a == "--stages") {
      stages = true;
    } else if (a == "--generated-voxel" && i + 1 < argc) {
      voxel = std::atof(argv[++i]);
    } else {
      std::ifstream in(a, std::ios::binary);
      if (!in) {
        std::fprintf(stderr, "cannot open %s\n", a.c_str());
        return 1;
      }
      Input input{a.substr(a.find_last_of('/') + 1),
                  std::vector<uint8_t>(std::istreambuf_iterator<char>(in), {})};
      inputs.push_back(std::move(input));
    }
  }
  if (voxel > 0) {
    vm::PhantomOptions o;
    o.kind = vm::PhantomKind::kBifurcation;
    o.voxel = voxel;
    o.noise = 0.3;
    auto p = vm::make_vessel_phantom(o);
    if (!p.ok()) {
      std::fprintf(stderr, "phantom: %s\n", p.message().c_str());
      return 1;
    }
    inputs.push_back({"generated-bifurcation (voxel " + std::to_string(voxel) + ")",
                      vm::write_stl_binary(p.value())});
  }
  std::printf("%-44s %10s %10s %12s\n", "input", "triangles", "median s", "Mtri/s");
  for (const Input& in : inputs) {
    std::vector<double> times;
    size_t triangles = 0;
    // Per stage (in the order reported), the seconds of each run.
    std::vector<std::pair<std::string, std::vector<double>>> stage_times;
    for (int r = 0; r < runs; ++r) {
      auto t0 = std::chrono::steady_clock::now();
      auto since = [&] {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      };
      std::string stage;
      double stage_start = 0;
      size_t stage_index = 0;
      auto progress = [&](double, std::string_view next) {
        const double now = since();
        if (!stage.empty()) {
          if (stage_index >= stage_times.size()) stage_times.push_back({stage, {}});
          stage_times[stage_index++].second.push_back(now - stage_start);
        }
        stage = next;
        stage_start = now;
        return true;
      };
      auto s = vm::prepare_surface(in.bytes, {}, progress);
      double dt = since();
      if (!s.ok()) {
        std::fprintf(stderr, "%s: %s\n", in.name.c_str(), s.message().c_str());
        return 1;
      }
      triangles = s.value().input_triangles;
      times.push_back(dt);
    }
    double m = median(times);
    std::printf("%-44s %10zu %10.4f %12.2f\n", in.name.c_str(), triangles, m,
                double(triangles) / m / 1e6);
    if (stages)
      for (auto& [name, seconds] : stage_times)
        std::printf("  %-42s %10s %10.4f\n", name.c_str(), "", median(seconds));
  }
  std::printf("peak resident memory: %.0f MB (runs: %d, threads: %d)\n", peak_rss_mb(), runs,
              vm::thread_count());
  return 0;
}
