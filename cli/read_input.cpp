// Reading the CLI's input file (see read_input.h).
#include "cli/read_input.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>

namespace vm::cli {
namespace {

namespace fs = std::filesystem;

Result<InputBytes> fail(const std::string& message) { return Result<InputBytes>::Error(message); }

/// A stream read to its end in chunks, refused beyond `max_bytes`.
Result<InputBytes> read_stream(std::istream& in, const std::string& name, uint64_t max_bytes) {
  std::vector<uint8_t> bytes;
  std::vector<char> chunk(size_t(1) << 20);
  while (in) {
    in.read(chunk.data(), std::streamsize(chunk.size()));
    const size_t got = size_t(in.gcount());
    if (bytes.size() + got > max_bytes) {
      return fail(name + ": file too large: more than " + std::to_string(max_bytes >> 30) +
                  " GiB, the limit of this build");
    }
    bytes.insert(bytes.end(), chunk.begin(), chunk.begin() + std::ptrdiff_t(got));
  }
  if (in.bad()) return fail("cannot read " + name);
  return InputBytes(std::move(bytes));
}

/// The regular file `path` of `size` bytes (> 0) mapped read-only and
/// populated, or nothing when it cannot be mapped.
std::optional<InputBytes> map_file(const std::string& path, uint64_t size) {
  const int fd = open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return std::nullopt;
#ifdef MAP_POPULATE
  constexpr int kPopulate = MAP_POPULATE;  // Linux: all pages at once, not a fault each
#else
  constexpr int kPopulate = 0;
#endif
  void* p = mmap(nullptr, size_t(size), PROT_READ, MAP_PRIVATE | kPopulate, fd, 0);
  close(fd);  // the mapping stays
  if (p == MAP_FAILED) return std::nullopt;
  return InputBytes(p, size_t(size));
}

}  // namespace

InputBytes::InputBytes(InputBytes&& other) noexcept
    : read_(std::move(other.read_)), mapped_(other.mapped_), size_(other.size_) {
  other.mapped_ = nullptr;
  other.size_ = 0;
}

InputBytes& InputBytes::operator=(InputBytes&& other) noexcept {
  if (this != &other) {
    if (mapped_) munmap(const_cast<uint8_t*>(mapped_), size_);
    read_ = std::move(other.read_);
    mapped_ = other.mapped_;
    size_ = other.size_;
    other.mapped_ = nullptr;
    other.size_ = 0;
  }
  return *this;
}

InputBytes::~InputBytes() {
  if (mapped_) munmap(const_cast<uint8_t*>(mapped_), size_);
}

Result<InputBytes> read_input(const std::string& path, const SurfaceReadOptions& options) {
  if (path == "-") {
    if (isatty(STDIN_FILENO)) {
      return fail("standard input is a terminal: pipe or redirect a surface file into it (< FILE)");
    }
    return read_stream(std::cin, "standard input", options.max_file_bytes);
  }
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (ec || !fs::exists(status)) {
    return fail("cannot open '" + path + "': " + (ec ? ec.message() : "no such file"));
  }
  if (fs::is_directory(status)) {
    return fail("'" + path + "' is a directory: give a surface file (STL, VTP, VTK, OBJ, PLY)");
  }
  if (fs::is_character_file(status) || fs::is_block_file(status)) {
    return fail("'" + path + "' is a device, not a surface file");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) return fail("cannot open '" + path + "': " + std::strerror(errno));
  if (!fs::is_regular_file(status)) {
    return read_stream(in, "'" + path + "'", options.max_file_bytes);  // a pipe, a socket
  }
  const uint64_t size = fs::file_size(path, ec);
  if (ec) return fail("cannot read '" + path + "': " + ec.message());
  std::vector<uint8_t> bytes(std::min<uint64_t>(size, 84));
  in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(bytes.size()));
  if (Status s = check_surface_size(bytes, size, options); !s.ok()) {
    return fail(path + ": " + s.message());
  }
  if (size > 84) {
    if (std::optional<InputBytes> mapped = map_file(path, size)) return std::move(*mapped);
  }
  bytes.resize(size);
  if (size > 84 &&
      !in.read(reinterpret_cast<char*>(bytes.data() + 84), std::streamsize(size - 84))) {
    return fail("cannot read '" + path + "'");
  }
  return InputBytes(std::move(bytes));
}

}  // namespace vm::cli
