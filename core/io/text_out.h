// A growing text buffer for the ASCII writers (MSH, OpenFOAM): strings,
// integers and doubles appended without locale or stream overhead, doubles
// as the shortest text that reads back exactly.
#pragma once

#include <charconv>
#include <cstddef>
#include <cstdio>
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
  /// Shortest text that reads back to exactly v (to_chars where the
  /// standard library has it for doubles; %.17g, also exact, elsewhere, e.g.
  /// Emscripten's libc++ 14).
  void real(double v) {
    char tmp[32];
#if defined(__cpp_lib_to_chars)
    auto r = std::to_chars(tmp, tmp + sizeof(tmp), v);
    buf_.append(tmp, r.ptr);
#else
    int n = std::snprintf(tmp, sizeof(tmp), "%.17g", v);
    buf_.append(tmp, size_t(n));
#endif
  }
  std::string take() { return std::move(buf_); }
  void reserve(size_t n) { buf_.reserve(n); }

 private:
  std::string buf_;
};

}  // namespace vm
