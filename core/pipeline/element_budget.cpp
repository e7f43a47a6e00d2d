// The element budget on the size field (element_budget.h).
#include "core/pipeline/element_budget.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "core/geom/vec3.h"
#include "core/mesh/enclosed_volume.h"
#include "core/surface/element_estimate.h"
#include "core/util/weighted_percentile.h"

namespace vm {

namespace {

/// `x` > 0 rounded up to `digits` significant digits.
double round_up(double x, int digits) {
  if (!(x > 0) || !std::isfinite(x)) return x;
  const double unit = std::pow(10.0, std::floor(std::log10(x)) - (digits - 1));
  return std::ceil(x / unit * (1 - 1e-12)) * unit;
}

struct Estimate {
  double triangles = 0, tetrahedra = 0;
};

/// The estimates at the sizes `h` (one per vertex of `wall`); tetrahedra,
/// when counted here, at the median size of the remeshed wall's vertices
/// (as check_volume_budget takes it after remeshing): each triangle of the
/// input weighs the triangles the remeshing puts on it, its area over the
/// square of its corners' mean size (as estimate_triangles counts them).
Estimate estimate(const SurfaceMesh& wall, double volume, const std::vector<double>& h,
                  const ElementBudget& budget) {
  Estimate e;
  e.triangles = estimate_triangles(wall, h);
  if (!budget.volume || budget.core_size > 0 || !(volume > 0)) return e;
  std::vector<std::pair<double, double>> weighed;  // (size, triangles there)
  for (size_t t = 0; t < wall.num_triangles(); ++t) {
    const int32_t* f = &wall.triangles[3 * t];
    const double size = (h[size_t(f[0])] + h[size_t(f[1])] + h[size_t(f[2])]) / 3;
    const Vec3 a = at(wall.points, f[0]);
    const double area = 0.5 * norm(cross(at(wall.points, f[1]) - a, at(wall.points, f[2]) - a));
    if (!(size > 0) || !(area > 0)) continue;
    weighed.emplace_back(size, area / (size * size));
  }
  if (!weighed.empty())
    e.tetrahedra = estimate_tetrahedra(volume, weighted_percentile(std::move(weighed), 0.5));
  return e;
}

/// How much larger the sizes must get for `e` to fit `max` triangles and
/// `tets` tetrahedra (1: it fits): triangles go as 1 / h^2, tetrahedra as
/// 1 / h^3.
double growth(const Estimate& e, double max, double tets) {
  return std::max({1.0, std::sqrt(e.triangles / max), std::cbrt(e.tetrahedra / tets)});
}

/// The estimate that needs the sizes to grow most, in words ("triangles on
/// the wall"), and its value.
std::pair<std::string, double> over(const Estimate& e, double max, double tets) {
  if (std::sqrt(e.triangles / max) >= std::cbrt(e.tetrahedra / tets))
    return {"triangles on the wall", e.triangles};
  return {"tetrahedra in the lumen", e.tetrahedra};
}

std::string count_text(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, x >= 1e6 ? "%.3g" : "%.0f", x);
  return buf;
}

std::string budget_text(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.0f", x);
  return buf;
}

}  // namespace

double tetrahedra_in_memory(double memory_bytes) {
  return memory_bytes > 0 ? memory_bytes / kWasmBytesPerTetrahedron : 0;
}

std::string memory_text(double memory_bytes) {
  char buf[160];
  std::snprintf(buf, sizeof buf,
                "the mesher's memory (%.2g GB free: about %.2g tetrahedra at %.0f bytes each)",
                memory_bytes / 1e9, tetrahedra_in_memory(memory_bytes), kWasmBytesPerTetrahedron);
  return buf;
}

TetrahedronLimit tetrahedron_limit(double max_elements, double memory_bytes) {
  const double in_memory = tetrahedra_in_memory(memory_bytes);
  if (in_memory > 0 && in_memory < max_elements) return {in_memory, true};
  return {max_elements, false};
}

std::string budget_warning(const BudgetFit& f) {
  const std::string where = f.counted == "triangles" ? " on the wall" : " in the lumen";
  if (f.memory)
    return "the default size ({per_circumference} " + number_text(f.asked_per_circumference) +
           ") would make about " + count_text(f.asked_elements) + " " + f.counted + where +
           ", more than fit in " + memory_text(f.memory_bytes) +
           ": coarsened to {per_circumference} " + number_text(f.per_circumference) + " (about " +
           count_text(f.elements) + ")";
  return "the default size ({per_circumference} " + number_text(f.asked_per_circumference) +
         ") would make about " + count_text(f.asked_elements) + " " + f.counted + where +
         ", over the element budget of " + budget_text(f.max_elements) +
         " ({max_elements}): coarsened to {per_circumference} " + number_text(f.per_circumference) +
         " (about " + count_text(f.elements) +
         "); ask for the finer mesh with {per_circumference} " +
         number_text(f.asked_per_circumference) + " and {max_elements} " + budget_text(f.enough);
}

double volume_closed_by_fans(const SurfaceMesh& wall, const std::vector<Opening>& openings) {
  SurfaceMesh closed = wall;
  for (const Opening& op : openings) {
    const int32_t c = int32_t(closed.num_vertices());
    closed.points.insert(closed.points.end(), op.centroid.begin(), op.centroid.end());
    for (size_t i = 0; i < op.loop.size(); ++i)
      closed.triangles.insert(closed.triangles.end(),
                              {op.loop[(i + 1) % op.loop.size()], op.loop[i], c});
  }
  return enclosed_volume(closed);
}

double fewest_per_circumference(double max_volume_change) {
  if (!(max_volume_change > 0)) return 20;
  const double n = 2 * std::numbers::pi / std::sqrt(6 * 0.8 * max_volume_change);
  return std::max(3.0, std::ceil(n));
}

double fitting_size(double area, double volume, double max_elements) {
  // An equilateral triangle of side h has sqrt(3)/4 h^2 (estimate_triangles).
  const double for_triangles = std::sqrt(area / (std::sqrt(3.0) / 4 * max_elements));
  const double for_tetrahedra =
      volume > 0 ? std::cbrt(estimate_tetrahedra(volume, 1.0) / max_elements) : 0;
  return round_up(1.02 * std::max(for_triangles, for_tetrahedra), 2);
}

Status fit_element_budget(const SurfaceMesh& wall, const std::vector<Opening>& openings,
                          std::span<const double> radius, const ElementBudget& budget,
                          SizeOptions& size, BudgetFit& fit, std::vector<double>* sizes) {
  fit = BudgetFit{};
  fit.max_elements = budget.max_elements;
  fit.memory_bytes = budget.memory_bytes;
  const bool per_circumference = size.mode == SizeMode::kPerCircumference;
  auto field = [&](const SizeOptions& o) {
    return vertex_sizes(wall, o, per_circumference ? radius : std::span<const double>{});
  };
  auto first = field(size);
  if (!first.ok()) return first.status();
  const double max = budget.max_elements;
  const TetrahedronLimit limit = tetrahedron_limit(max, budget.memory_bytes);
  const double tets = limit.tetrahedra;
  const double volume = budget.volume ? std::abs(volume_closed_by_fans(wall, openings)) : 0;
  const Estimate asked = estimate(wall, volume, first.value(), budget);
  if (!(max > 0) || growth(asked, max, tets) <= 1) {
    if (sizes) *sizes = std::move(first).value();
    return Status::Ok();
  }

  // Phase 1: the sizes grown by the growth still needed (per circumference:
  // N lowered to a whole number), measured again: clamps, curvature and
  // gradation keep them from growing in proportion.
  const bool coarsen = !budget.size_given && per_circumference;
  const double fewest = coarsen ? fewest_per_circumference(budget.max_volume_change) : 3;
  SizeOptions trial = size;
  std::vector<double> h;
  Estimate at = asked;
  bool fits = false;
  for (int round = 0; round < 8 && !fits; ++round) {
    const double g = 1.02 * growth(at, max, tets);
    if (per_circumference) {
      const double n = std::max(
          fewest, std::min(std::floor(trial.per_circumference / g), trial.per_circumference - 1));
      if (n >= trial.per_circumference) break;  // as coarse as it may get
      trial.per_circumference = n;
    } else {
      trial.size = round_up(trial.size * g, 2);
    }
    auto next = field(trial);
    if (!next.ok()) return next.status();
    h = std::move(next).value();
    at = estimate(wall, volume, h, budget);
    fits = growth(at, max, tets) <= 1;
  }
  const auto [counted, count] = over(asked, max, tets);
  // The memory is the limit when the tetrahedra are what is over it.
  const bool memory = limit.memory && counted[0] == 't' && counted[1] == 'e';
  // Raising the budget is said when the option allows it.
  auto raise = [](double needed) {
    const double enough = round_up(1.05 * needed, 2);
    return enough <= kMostElements ? "raise {max_elements} to " + budget_text(enough)
                                   : std::string();
  };

  // Phase 2: the default coarsened, or the refusal.
  if (coarsen && fits) {
    fit.coarsened = true;
    fit.asked_per_circumference = size.per_circumference;
    fit.per_circumference = trial.per_circumference;
    fit.counted = counted.substr(0, counted.find(' '));
    fit.asked_elements = count;
    fit.elements = fit.counted == "triangles" ? at.triangles : at.tetrahedra;
    fit.enough = round_up(1.05 * count, 2);
    fit.memory = memory;
    size.per_circumference = trial.per_circumference;
    if (sizes) *sizes = std::move(h);
    return Status::Ok();
  }
  if (coarsen) {
    const auto [still, still_count] = over(at, max, tets);
    if (memory)
      return Status::Error(
          "the default size ({per_circumference} " + number_text(size.per_circumference) +
          ") makes about " + count_text(count) + " " + counted + ", and {per_circumference} " +
          number_text(trial.per_circumference) +
          ", the fewest that keep the vessels' volume within {max_volume_change}, still about " +
          count_text(still_count) + " " + still + ": more than fit in " +
          memory_text(budget.memory_bytes) + ": cut the model smaller");
    return Status::BadOption(
        "max_elements",
        budget_text(max) + " is too small for this model: the default size ({per_circumference} " +
            number_text(size.per_circumference) + ") makes about " + count_text(count) + " " +
            counted + ", and {per_circumference} " + number_text(trial.per_circumference) +
            ", the fewest that keep the vessels' volume within {max_volume_change}, still about " +
            count_text(still_count) + " " + still + ": " +
            (raise(still_count).empty() ? "cut the model smaller or give a coarser {size}"
                                        : raise(still_count) + " or more"));
  }
  const char* option = per_circumference ? "per_circumference" : "size";
  std::string fitting;
  if (fits)
    fitting = per_circumference
                  ? " ({per_circumference} " + number_text(trial.per_circumference) + " fits)"
                  : " ({size} " + number_text(trial.size) + " fits)";
  const std::string beyond = memory ? "more than fit in " + memory_text(budget.memory_bytes) +
                                          ": ask for larger elements" + fitting
                                    : "more than the element budget ({max_elements} " +
                                          budget_text(max) + ") allows: ask for larger elements" +
                                          fitting +
                                          (raise(count).empty() ? "" : ", or " + raise(count));
  Status refused =
      Status::BadOption(option, "makes about " + count_text(count) + " " + counted + ", " + beyond);
  if (!fits) return refused;
  return refused.WithRemedy(
      {"coarser", {}, per_circumference ? trial.per_circumference : trial.size});
}

}  // namespace vm
