// Reading the CLI's input file (see read_input.h).
#include "cli/read_input.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>

#include "core/util/parallel.h"

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

}  // namespace

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
  std::vector<uint8_t> head(std::min<uint64_t>(size, 84));
  in.read(reinterpret_cast<char*>(head.data()), std::streamsize(head.size()));
  if (Status s = check_surface_size(head, size, options); !s.ok()) {
    return fail(path + ": " + s.message());
  }
  std::unique_ptr<uint8_t[]> bytes(new uint8_t[size]);  // not zeroed: every byte is read
  // The body in chunks read side by side (parallel.h): copying from the page
  // cache is a tenth of a second per 400 MB and thread.
  const int fd = open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return fail("cannot open '" + path + "': " + std::strerror(errno));
  constexpr size_t kChunk = size_t(32) << 20;
  std::atomic<bool> short_read{false};
  parallel_for(size_t(size), kChunk, [&](size_t begin, size_t end) {
    for (size_t at = begin; at < end;) {
      const ssize_t got = pread(fd, bytes.get() + at, end - at, off_t(at));
      if (got <= 0) {
        if (got < 0 && errno == EINTR) continue;
        short_read = true;  // the file shrank, or a read error
        return;
      }
      at += size_t(got);
    }
  });
  close(fd);
  if (short_read) return fail("cannot read '" + path + "' (did it change while being read?)");
  return InputBytes(std::move(bytes), size_t(size));
}

}  // namespace vm::cli
