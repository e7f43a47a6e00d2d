// Small text-scanning helpers shared by the text surface readers (legacy
// VTK, OBJ, PLY, VTK XML): a token cursor that counts lines, exact number
// parsing, and printable renderings of bytes for error messages.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

namespace vm {

inline bool is_text_space(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v';
}

/// Parses a whole token as a double, correctly rounded: decimal syntax with
/// an optional sign, also "inf" and "nan" (callers check finiteness
/// themselves). False on anything else (hexadecimal floats too) or trailing
/// characters.
bool parse_double(std::string_view token, double& out);

/// Parses a whole token as a decimal integer (optional sign). False on
/// overflow, empty input or trailing characters.
bool parse_int64(std::string_view token, int64_t& out);

/// The token in single quotes for a message, cut to 32 characters, with
/// non-printable bytes as \xNN.
std::string quoted(std::string_view token);

/// The first `max_bytes` bytes as printable text for a message: printable
/// ASCII as is, \r \n \t as escapes, other bytes as \xNN, "..." when cut.
std::string printable_prefix(std::span<const uint8_t> bytes, size_t max_bytes = 16);

/// Whitespace-separated tokens of a byte buffer, with the current line
/// number (1-based). Binary blocks in between are skipped with `skip`, which
/// does not count their newlines.
class TextCursor {
 public:
  explicit TextCursor(std::span<const uint8_t> bytes)
      : p_(reinterpret_cast<const char*>(bytes.data())), n_(bytes.size()) {}

  /// Next token; empty at the end of the input.
  std::string_view next();
  /// Next token without consuming it.
  std::string_view peek();
  /// The rest of the current line (without its end: \n, \r\n or a lone
  /// \r), consuming the line end too.
  std::string_view rest_of_line();
  /// Skips spaces and tabs, then one line end (\n or \r\n) if there is one:
  /// where the binary data after a keyword line starts.
  void skip_line_end();
  bool at_end();  ///< true when only whitespace is left
  size_t line() const { return line_; }
  size_t pos() const { return pos_; }
  size_t size() const { return n_; }
  /// Moves `count` bytes forward (callers check remaining() first; the
  /// cursor never moves past the end).
  void skip(size_t count) { pos_ += count < n_ - pos_ ? count : n_ - pos_; }
  const uint8_t* data_at_pos() const { return reinterpret_cast<const uint8_t*>(p_ + pos_); }
  size_t remaining() const { return n_ - pos_; }

 private:
  void skip_space();
  const char* p_;
  size_t n_;
  size_t pos_ = 0;
  size_t line_ = 1;
};

}  // namespace vm
