// Reading the CLI's input file: a path, or '-' for standard input (a pipe
// or a redirected file); directories and devices are refused as such, and
// sizes beyond the readers' limits before the file is read.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/io/read_surface.h"
#include "core/util/result.h"

namespace vm::cli {

/// An input file's bytes: a regular file mapped read-only (no copy, and no
/// zeroed memory to fault in first), else the bytes read into memory.
/// Move-only; the mapping ends with the object.
class InputBytes {
 public:
  explicit InputBytes(std::vector<uint8_t> bytes) : read_(std::move(bytes)) {}
  /// Takes over a mapping of `size` bytes at `mapped` (from mmap).
  InputBytes(const void* mapped, size_t size)
      : mapped_(static_cast<const uint8_t*>(mapped)), size_(size) {}
  InputBytes(InputBytes&& other) noexcept;
  InputBytes& operator=(InputBytes&& other) noexcept;
  ~InputBytes();

  std::span<const uint8_t> span() const {
    return mapped_ ? std::span<const uint8_t>(mapped_, size_) : std::span<const uint8_t>(read_);
  }
  operator std::span<const uint8_t>() const { return span(); }  // NOLINT: a view of the bytes

 private:
  std::vector<uint8_t> read_;
  const uint8_t* mapped_ = nullptr;
  size_t size_ = 0;
};

/// The bytes of `path` ('-': standard input). Errors name the path and say
/// what it is ("a directory", "a device", "a terminal") or why it cannot be
/// read; a regular file is checked with check_surface_size first (then
/// mapped, or read if it cannot be), a stream is read in chunks up to
/// options.max_file_bytes.
Result<InputBytes> read_input(const std::string& path, const SurfaceReadOptions& options = {});

}  // namespace vm::cli
