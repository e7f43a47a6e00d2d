// Errors as values: Status and Result<T> carry a message instead of throwing.
// Every fallible core function returns one of these; nothing in core throws
// across a module boundary (see DESIGN.md, "Errors are values").
#pragma once

#include <string>
#include <utility>
#include <variant>

namespace vm {

/// Outcome of an operation without a value. `ok()` or an error message.
class Status {
 public:
  Status() = default;
  static Status Ok() { return Status(); }
  static Status Error(std::string message) {
    Status s;
    s.message_ = std::move(message);
    s.ok_ = false;
    return s;
  }
  bool ok() const { return ok_; }
  const std::string& message() const { return message_; }

 private:
  bool ok_ = true;
  std::string message_;
};

/// A value of type T or an error message.
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

 private:
  std::variant<T, Status> v_;
};

}  // namespace vm
