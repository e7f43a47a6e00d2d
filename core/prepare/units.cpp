// The length unit of a model (units.h): symbols, the scale measured at the
// wall, and the guess that weighs it against human anatomy (our own).
#include "core/prepare/units.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <tuple>
#include <vector>

#include "core/geom/vec3.h"
#include "core/mesh/chord_radius.h"
#include "core/util/weighted_percentile.h"

namespace vm {

std::string_view unit_symbol(LengthUnit unit) {
  switch (unit) {
    case LengthUnit::kMm:
      return "mm";
    case LengthUnit::kCm:
      return "cm";
    case LengthUnit::kM:
      return "m";
    case LengthUnit::kGuess:
      break;
  }
  return "";
}

double metres_per_unit(LengthUnit unit) {
  switch (unit) {
    case LengthUnit::kMm:
      return 1e-3;
    case LengthUnit::kCm:
      return 1e-2;
    case LengthUnit::kM:
      return 1;
    case LengthUnit::kGuess:
      break;
  }
  return 0;
}

std::string_view confidence_name(UnitConfidence confidence) {
  switch (confidence) {
    case UnitConfidence::kCertain:
      return "certain";
    case UnitConfidence::kLikely:
      return "likely";
    case UnitConfidence::kUnsure:
      break;
  }
  return "unsure";
}

double VesselScale::smallest() const {
  return smallest_opening > 0 ? std::min(small_radius, smallest_opening) : small_radius;
}

VesselScale measure_vessel_scale(const SurfaceMesh& mesh, bool oriented,
                                 std::span<const double> opening_radii, std::string label_array) {
  VesselScale s;
  s.label_array = std::move(label_array);
  if (mesh.num_triangles() == 0) return s;
  s.extent = bounding_box(mesh.points).diagonal();
  // A third of each triangle's area to each corner.
  const size_t nv = mesh.num_vertices();
  std::vector<double> area(nv, 0.0);
  for (size_t t = 0; t < mesh.num_triangles(); ++t) {
    const int32_t* f = &mesh.triangles[3 * t];
    const Vec3 a = at(mesh.points, f[0]);
    const double third = norm(cross(at(mesh.points, f[1]) - a, at(mesh.points, f[2]) - a)) / 6;
    for (int k = 0; k < 3; ++k) area[size_t(f[k])] += third;
  }
  std::vector<int32_t> sample;
  const size_t stride = (nv + kScaleSamples - 1) / kScaleSamples;
  for (size_t v = 0; oriented && v < nv; v += stride)
    if (area[v] > 0) sample.push_back(int32_t(v));
  const std::vector<double> chord =
      sample.empty() ? std::vector<double>{} : half_chords(mesh, sample);
  std::vector<std::pair<double, double>> measured;
  double met = 0, cast = 0;
  bool missed = false;
  for (size_t i = 0; i < sample.size(); ++i) {
    const double a = area[size_t(sample[i])];
    cast += a;
    if (chord[i] > 0) {
      measured.emplace_back(chord[i], a);
      met += a;
    } else if (!missed) {
      missed = true;
      s.open_example = at(mesh.points, sample[i]);
    }
  }
  if (cast > 0) s.enclosed_share = met / cast;
  std::vector<double> openings;
  for (double r : opening_radii)
    if (r > 0) openings.push_back(r);
  std::sort(openings.begin(), openings.end());
  if (!measured.empty()) {
    s.large_radius = weighted_percentile(measured, 0.9);
    s.median_radius = weighted_percentile(measured, 0.5);
    s.small_radius = weighted_percentile(measured, 0.1);
  } else if (!openings.empty()) {
    s.large_radius = openings.back();
    s.median_radius = openings[openings.size() / 2];
    s.small_radius = openings.front();
  }
  for (double r : openings)
    if (r >= 0.1 * s.large_radius) {
      s.smallest_opening = r;
      break;
    }
  return s;
}

namespace {

/// A measure's ranges for human vessels, mm (units.h decide_unit).
struct Range {
  const char* name;
  double typical_lo, typical_hi, possible_lo, possible_hi;
};

constexpr Range kLarge{"largest vessel radius", 1, 20, 0.3, 40};
constexpr Range kMedian{"median vessel radius", 0.5, 15, 0.2, 35};
constexpr Range kSmall{"smallest vessel radius", 0.35, 15, 0.08, 30};
constexpr Range kExtent{"bounding-box diagonal", 10, 700, 3, 2000};

/// How well a value fits its range; a unit fits as its worst measure.
enum Fit { kTypical = 0, kPossible = 1, kImpossible = 2 };

Fit fit(const Range& r, double mm) {
  if (mm >= r.typical_lo && mm <= r.typical_hi) return kTypical;
  if (mm >= r.possible_lo && mm <= r.possible_hi) return kPossible;
  return kImpossible;
}

/// One unit weighed: its fit, its distance to the typical sizes, and the
/// measure that fits worst (the farthest out of its typical range).
struct Weighed {
  LengthUnit unit;
  Fit fit = kTypical;
  double score = 0;
  const Range* worst = nullptr;
  double worst_mm = 0;
};

Weighed weigh(LengthUnit unit, const VesselScale& s) {
  Weighed w{unit};
  const double mm = metres_per_unit(unit) * 1000;
  std::vector<std::pair<const Range*, double>> measures = {{&kExtent, s.extent}};
  if (s.measured())
    measures.insert(
        measures.begin(),
        {{&kLarge, s.large_radius}, {&kMedian, s.median_radius}, {&kSmall, s.smallest()}});
  double worst_out = -1;
  for (const auto& [range, value] : measures) {
    const double x = value * mm;
    const double centre = std::sqrt(range->typical_lo * range->typical_hi);
    w.score += std::pow(std::log(x / centre), 2);
    const double out =
        std::max({std::log(range->typical_lo / x), std::log(x / range->typical_hi), 0.0});
    w.fit = std::max(w.fit, fit(*range, x));
    if (out > worst_out) worst_out = out, w.worst = range, w.worst_mm = x;
  }
  return w;
}

/// "the largest vessel radius would be 0.0025 mm".
std::string worst_text(const Weighed& w) {
  return "the " + std::string(w.worst->name) + " would be " + number_text(w.worst_mm, 3) + " mm";
}

}  // namespace

ModelUnit decide_unit(LengthUnit asked, const VesselScale& scale) {
  ModelUnit u;
  if (asked != LengthUnit::kGuess) {
    u.unit = asked;
    return u;
  }
  u.guessed = true;
  const bool labels = !scale.label_array.empty();
  std::array<Weighed, 3> units = {weigh(LengthUnit::kMm, scale), weigh(LengthUnit::kCm, scale),
                                  weigh(LengthUnit::kM, scale)};
  // The face labels count among units that fit as well, before the score.
  auto rank = [&](const Weighed& w) {
    return std::tuple(int(w.fit), labels && w.unit == LengthUnit::kCm ? 0 : 1, w.score);
  };
  std::sort(units.begin(), units.end(),
            [&](const Weighed& a, const Weighed& b) { return rank(a) < rank(b); });
  const Weighed& best = units[0];
  const Weighed& next = units[1];
  u.unit = best.unit;
  const std::string b(unit_symbol(best.unit)), n(unit_symbol(next.unit));
  std::string verdict;
  if (best.fit == kImpossible) {
    u.confidence = UnitConfidence::kUnsure;
    verdict = "no unit gives human vessel sizes (in " + b + " " + worst_text(best) + "); " + b +
              " comes nearest";
  } else if (next.fit == kImpossible) {
    u.confidence = UnitConfidence::kCertain;
    verdict = "only " + b + " gives human vessel sizes (in " + n + " " + worst_text(next) + ")";
  } else if (next.fit > best.fit) {
    u.confidence = UnitConfidence::kLikely;
    u.alternative = next.unit;
    verdict = b + " gives " + (best.fit == kTypical ? "typical" : "possible") +
              " human vessel sizes, " + n + " unusual ones (" + worst_text(next) + ")";
  } else {
    u.confidence = UnitConfidence::kUnsure;
    u.alternative = next.unit;
    verdict = b + " and " + n + " both give " + (best.fit == kTypical ? "typical" : "unusual") +
              " human vessel sizes; " +
              (labels && best.unit == LengthUnit::kCm ? "the face labels (" + scale.label_array +
                                                            ") hint at cm, SimVascular's usual unit"
                                                      : b + " is nearer the typical sizes");
  }
  u.certain = u.confidence == UnitConfidence::kCertain;
  std::string measures;
  if (scale.measured())
    measures = "vessel radius " + number_text(scale.large_radius, 3) + " largest, " +
               number_text(scale.median_radius, 3) + " median, " +
               number_text(scale.smallest(), 3) + " smallest; ";
  else
    measures = "no vessel radius measured; ";
  u.reason = measures + "bounding-box diagonal " + number_text(scale.extent, 3) + ": " + verdict;
  return u;
}

std::string unit_summary(const ModelUnit& u) {
  const std::string unit(unit_symbol(u.unit));
  if (!u.guessed) return unit + " (given)";
  std::string out =
      unit + " (guessed, " + std::string(confidence_name(u.confidence)) + ": " + u.reason;
  if (u.confidence != UnitConfidence::kCertain) {
    const std::string other(unit_symbol(u.alternative));
    out += other.empty() ? "; say {units}" : "; if it is " + other + ", say {units} " + other;
  }
  return out + ")";
}

}  // namespace vm
