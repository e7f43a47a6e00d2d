// Progress reporting and cooperative cancellation for long-running stages.
#pragma once

#include <functional>
#include <string_view>

namespace vm {

/// Called with a fraction in [0, 1] of the current job and the name of the
/// stage running. Returning false asks the job to stop as soon as it can; the
/// job then returns Status::Cancelled() (ErrorKind::kCancelled).
using ProgressFn = std::function<bool(double fraction, std::string_view stage)>;

/// Calls `fn` if set; returns false when the caller asked to cancel.
inline bool report_progress(const ProgressFn& fn, double fraction, std::string_view stage) {
  return !fn || fn(fraction, stage);
}

}  // namespace vm
