// Reading the CLI's input file: a path, or '-' for standard input (a pipe
// or a redirected file); directories and devices are refused as such, and
// sizes beyond the readers' limits before the file is read.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "core/io/read_surface.h"
#include "core/util/result.h"

namespace vm::cli {

/// An input file's bytes: a regular file read into memory that is not
/// zeroed first (no page to fault in twice), or a stream's bytes.
class InputBytes {
 public:
  explicit InputBytes(std::vector<uint8_t> bytes) : read_(std::move(bytes)) {}
  /// Takes over `size` bytes at `buffer`.
  InputBytes(std::unique_ptr<uint8_t[]> buffer, size_t size)
      : buffer_(std::move(buffer)), size_(size) {}

  std::span<const uint8_t> span() const {
    return buffer_ ? std::span<const uint8_t>(buffer_.get(), size_)
                   : std::span<const uint8_t>(read_);
  }
  operator std::span<const uint8_t>() const { return span(); }  // NOLINT: a view of the bytes

 private:
  std::vector<uint8_t> read_;
  std::unique_ptr<uint8_t[]> buffer_;
  size_t size_ = 0;
};

/// The bytes of `path` ('-': standard input). Errors name the path and say
/// what it is ("a directory", "a device", "a terminal") or why it cannot be
/// read; a regular file is checked with check_surface_size first, then
/// read whole; a stream is read in chunks up to options.max_file_bytes.
Result<InputBytes> read_input(const std::string& path, const SurfaceReadOptions& options = {});

}  // namespace vm::cli
