// The binary number types a file format names (PLY's "uchar", VTK XML's
// "Float32", ...): size and kind, looked up by the format's own names.
#pragma once

#include <cstddef>
#include <span>
#include <string_view>

namespace vm {

enum class ValueKind { kSigned, kUnsigned, kFloat };

/// One type of a format: its name there, its size in bytes, its kind.
struct ValueType {
  std::string_view name;
  size_t size;
  ValueKind kind;
};

/// The type of `types` called `name`, or nullptr.
inline const ValueType* find_value_type(std::span<const ValueType> types, std::string_view name) {
  for (const ValueType& t : types)
    if (t.name == name) return &t;
  return nullptr;
}

}  // namespace vm
