// Errors are values: Status and Result<T> carry a kind and a message instead
// of throwing. Every fallible core function returns one of these; nothing in
// core throws across a module boundary (docs/ARCHITECTURE.md, "Errors").
#pragma once

#include <array>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace vm {

/// What went wrong, so that each caller (CLI, WebAssembly API, page) can
/// answer in its own way (exit status, `cancelled: true`, ...).
enum class ErrorKind {
  kNone,       ///< not an error
  kBadInput,   ///< the input cannot be meshed as asked, or a stage failed on it
  kBadOption,  ///< an option's value is unusable; option() names it
  kCancelled,  ///< the progress callback asked to stop
  kInternal,   ///< a broken invariant: a bug, never the user's fault
};

/// What the user can do about a refusal, in a form each interface can offer
/// as a control (the page: a button that applies it; the CLI: the message
/// already says it in words). `action` is one word of a fixed vocabulary:
///   "trim_end"   cut the vessel back across it at `where` (a damaged end);
///   "cut_here"   cut across the vessel at `where` (clip_at);
///   "coarser"    larger elements: `value` is the value of the refused
///                option (Status::option(): {size} or {core_size} in model
///                units, {per_circumference} a count) that fits;
///   "no_layers"  mesh without a boundary layer;
///   "smooth"     smooth the surface (`value` passes);
///   "repair"     turn the repairs on;
///   "largest_component"  keep the largest piece;
///   "units"      confirm or give the unit.
/// `places` are points (model unit) the message names, for the view to mark.
struct Remedy {
  std::string action;
  std::vector<std::array<double, 3>> places;
  double value = 0;
};

/// Outcome of an operation without a value: `ok()` or an error with a kind
/// and a message. Messages may name options as `{option_id}` (ids of the
/// option table, core/pipeline/option_table.h); each interface phrases them
/// in its own vocabulary (phrase_options).
class Status {
 public:
  Status() = default;
  static Status Ok() { return Status(); }
  /// A failure on this input (ErrorKind::kBadInput).
  static Status Error(std::string message) {
    return Make(ErrorKind::kBadInput, std::move(message));
  }
  /// An unusable value of option `option_id`; the message says what it
  /// needs, without the option's name ("needs a positive length").
  static Status BadOption(std::string option_id, std::string message) {
    Status s = Make(ErrorKind::kBadOption, std::move(message));
    s.option_ = std::move(option_id);
    return s;
  }
  static Status Cancelled() { return Make(ErrorKind::kCancelled, "cancelled"); }
  static Status Internal(std::string message) {
    return Make(ErrorKind::kInternal, "internal error: " + std::move(message));
  }
  bool ok() const { return kind_ == ErrorKind::kNone; }
  bool cancelled() const { return kind_ == ErrorKind::kCancelled; }
  ErrorKind kind() const { return kind_; }
  const std::string& message() const { return message_; }
  /// The option id of a kBadOption error, else empty.
  const std::string& option() const { return option_; }
  /// The same error with `prefix` before its message (kind, option and
  /// remedy kept).
  Status Prefixed(const std::string& prefix) const {
    Status s = *this;
    if (!ok()) s.message_ = prefix + s.message_;
    return s;
  }
  /// The same error with a remedy the interfaces can offer (remedy()).
  Status WithRemedy(Remedy remedy) const {
    Status s = *this;
    if (!ok()) s.remedy_ = std::move(remedy);
    return s;
  }
  /// The remedy; empty action when none is known.
  const Remedy& remedy() const { return remedy_; }

 private:
  static Status Make(ErrorKind kind, std::string message) {
    Status s;
    s.kind_ = kind;
    s.message_ = std::move(message);
    return s;
  }
  ErrorKind kind_ = ErrorKind::kNone;
  std::string message_;
  std::string option_;
  Remedy remedy_;
};

/// A value of type T or an error Status.
template <class T>
class Result {
 public:
  Result(T value) : v_(std::move(value)) {}       // NOLINT: implicit by design
  Result(Status error) : v_(std::move(error)) {}  // NOLINT: must be an error
  static Result Error(std::string message) { return Result(Status::Error(std::move(message))); }
  bool ok() const { return std::holds_alternative<T>(v_); }
  /// Precondition: ok().
  T& value() & { return std::get<T>(v_); }
  const T& value() const& { return std::get<T>(v_); }
  T&& value() && { return std::get<T>(std::move(v_)); }
  /// Empty when ok().
  const std::string& message() const {
    static const std::string kEmpty;
    return ok() ? kEmpty : std::get<Status>(v_).message();
  }
  Status status() const { return ok() ? Status::Ok() : std::get<Status>(v_); }
  bool cancelled() const { return !ok() && std::get<Status>(v_).cancelled(); }

 private:
  std::variant<T, Status> v_;
};

}  // namespace vm
