// The length unit of a model (units.h).
#include "core/prepare/units.h"

#include <cstdio>

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

LengthUnit parse_unit(std::string_view s) {
  if (s == "mm") return LengthUnit::kMm;
  if (s == "cm") return LengthUnit::kCm;
  if (s == "m") return LengthUnit::kM;
  return LengthUnit::kGuess;
}

ModelUnit decide_unit(LengthUnit asked, double median_radius) {
  ModelUnit u;
  if (asked != LengthUnit::kGuess) {
    u.unit = asked;
    return u;
  }
  char buf[96];
  std::snprintf(buf, sizeof buf, "median vessel radius %.3g", median_radius);
  u.guessed = true;
  u.reason = buf;
  if (median_radius > 0 && median_radius < 0.05) {
    u.unit = LengthUnit::kM;
  } else {
    u.unit = LengthUnit::kMm;
    u.certain = false;
  }
  return u;
}

}  // namespace vm
