// Smoothing of raw segmentation surfaces (smooth_surface.h).
#include "core/prepare/smooth_surface.h"

#include <charconv>

namespace vm {

std::optional<Smoothing> parse_smoothing(std::string_view text) {
  Smoothing s;
  if (text == "auto") return s;
  if (text == "off") {
    s.mode = Smoothing::Mode::kOff;
    return s;
  }
  int n = 0;
  auto r = std::from_chars(text.data(), text.data() + text.size(), n);
  if (r.ec != std::errc() || r.ptr != text.data() + text.size() || n < 1 || n > 1000)
    return std::nullopt;
  s.mode = Smoothing::Mode::kPasses;
  s.passes = n;
  return s;
}

}  // namespace vm
