// A growing text buffer for the ASCII writers (MSH, OpenFOAM): strings,
// integers and doubles appended without locale or stream overhead, doubles
// as the shortest text that reads back exactly.
#pragma once

#include <fmt/compile.h>
#include <fmt/format.h>

#include <charconv>
#include <cstddef>
#include <string>
#include <string_view>
#include <utility>

namespace vm {

class TextOut {
 public:
  void str(std::string_view s) { buf_.append(s); }
  void ch(char c) { buf_.push_back(c); }
  template <class Int>
  void integer(Int v) {
    char tmp[24];
    auto r = std::to_chars(tmp, tmp + sizeof(tmp), v);
    buf_.append(tmp, r.ptr);
  }
  /// Shortest text that reads back to exactly v, by {fmt}'s Dragonbox: the
  /// same bytes in every build (native and WebAssembly).
  void real(double v) {
    char tmp[32];
    char* end = fmt::format_to(tmp, FMT_COMPILE("{}"), v);
    buf_.append(tmp, end);
  }
  std::string take() { return std::move(buf_); }
  void reserve(size_t n) { buf_.reserve(n); }

 private:
  std::string buf_;
};

}  // namespace vm
