// Wall-clock seconds of the pipeline's stages, for the timings the report
// gives (one clock for all of them).
#pragma once

#include <chrono>

namespace vm {

using StageClock = std::chrono::steady_clock;

/// Seconds from `start` to now.
inline double seconds_since(StageClock::time_point start) {
  return std::chrono::duration<double>(StageClock::now() - start).count();
}

/// Times consecutive stages: lap() gives the seconds since the timer was
/// made or since the previous lap, and starts the next.
class StageTimer {
 public:
  double lap() {
    const auto now = StageClock::now();
    const double s = std::chrono::duration<double>(now - start_).count();
    start_ = now;
    return s;
  }

 private:
  StageClock::time_point start_ = StageClock::now();
};

}  // namespace vm
