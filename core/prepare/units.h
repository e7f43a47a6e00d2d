// The length unit of a model: the file's numbers carry none, so the user
// says it (--units) or it is guessed from the vessels' size. Vessel radii run
// from about 0.5 mm (coronary, cerebral branches) to 15 mm (aorta): below
// about 0.05 the numbers can only be metres; centimetres (0.05 to 1.5) and
// millimetres (0.5 to 15) overlap, so a guess of millimetres is never
// certain and the page asks the user to confirm it.
#pragma once

#include <string>
#include <string_view>

namespace vm {

enum class LengthUnit { kGuess, kMm, kCm, kM };

/// "mm", "cm", "m" ("" for kGuess).
std::string_view unit_symbol(LengthUnit unit);
/// Metres per unit (0 for kGuess).
double metres_per_unit(LengthUnit unit);
/// kGuess for anything but "mm", "cm", "m".
LengthUnit parse_unit(std::string_view symbol);

/// The unit of a model and how it was decided.
struct ModelUnit {
  LengthUnit unit = LengthUnit::kMm;
  bool guessed = false;  ///< not given by the user
  /// For a guess: what it rests on ("median vessel radius 0.0031"), and
  /// whether it is certain (metres are; millimetres never are).
  std::string reason;
  bool certain = true;
};

/// The user's unit when given, else a guess from the median vessel radius
/// of the model (model units, > 0): below 0.05 metres (certain), else
/// millimetres (uncertain: could be centimetres).
ModelUnit decide_unit(LengthUnit asked, double median_radius);

}  // namespace vm
