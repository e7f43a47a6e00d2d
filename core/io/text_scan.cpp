// Token cursor and number parsing for the text readers. Decimal numbers are
// converted by fast_float (Debian libfast-float-dev: Lemire's algorithm,
// exact, locale-free, the same bits as a correctly rounded strtod), the same
// natively and in WebAssembly.
#include "core/io/text_scan.h"

#include <fast_float/fast_float.h>

#include <charconv>
#include <cstdio>
#include <cstring>

namespace vm {
namespace {

// A byte as \xNN (two lowercase hex digits).
void append_hex_escape(std::string& s, unsigned char c) {
  char buf[8];
  std::snprintf(buf, sizeof(buf), "\\x%02x", c);
  s += buf;
}

}  // namespace

bool parse_double(std::string_view tok, double& out) {
  // One leading '+' as the formats write it (from_chars takes none).
  if (!tok.empty() && tok[0] == '+') tok.remove_prefix(1);
  if (tok.empty() || tok[0] == '+') return false;
  const auto r = fast_float::from_chars(tok.data(), tok.data() + tok.size(), out);
  return r.ec == std::errc() && r.ptr == tok.data() + tok.size();
}

bool parse_int64(std::string_view tok, int64_t& out) {
  if (!tok.empty() && tok[0] == '+') tok.remove_prefix(1);
  if (tok.empty()) return false;
  auto r = std::from_chars(tok.data(), tok.data() + tok.size(), out);
  return r.ec == std::errc() && r.ptr == tok.data() + tok.size();
}

std::string quoted(std::string_view tok) {
  std::string s = "'";
  size_t n = std::min<size_t>(tok.size(), 32);
  for (size_t i = 0; i < n; ++i) {
    unsigned char c = static_cast<unsigned char>(tok[i]);
    if (c >= 32 && c < 127) {
      s += char(c);
    } else {
      append_hex_escape(s, c);
    }
  }
  if (tok.size() > n) s += "...";
  return s + "'";
}

std::string printable_prefix(std::span<const uint8_t> bytes, size_t max_bytes) {
  std::string s;
  size_t n = std::min(bytes.size(), max_bytes);
  for (size_t i = 0; i < n; ++i) {
    uint8_t c = bytes[i];
    if (c == '\n') {
      s += "\\n";
    } else if (c == '\r') {
      s += "\\r";
    } else if (c == '\t') {
      s += "\\t";
    } else if (c >= 32 && c < 127 && c != '\\') {
      s += char(c);
    } else {
      append_hex_escape(s, c);
    }
  }
  if (bytes.size() > n) s += "...";
  return s;
}

void TextCursor::skip_space() {
  while (pos_ < n_ && is_text_space(p_[pos_])) {
    // A line ends at \n, \r\n or a lone \r (classic Mac line ends).
    if (p_[pos_] == '\n' || (p_[pos_] == '\r' && (pos_ + 1 == n_ || p_[pos_ + 1] != '\n'))) {
      ++line_;
    }
    ++pos_;
  }
}

std::string_view TextCursor::next() {
  skip_space();
  size_t b = pos_;
  while (pos_ < n_ && !is_text_space(p_[pos_])) ++pos_;
  return std::string_view(p_ + b, pos_ - b);
}

std::string_view TextCursor::peek() {
  size_t pos = pos_, line = line_;
  std::string_view t = next();
  pos_ = pos;
  line_ = line;
  return t;
}

std::string_view TextCursor::rest_of_line() {
  size_t b = pos_;
  while (pos_ < n_ && p_[pos_] != '\n' && p_[pos_] != '\r') ++pos_;
  size_t e = pos_;
  if (pos_ < n_) {
    if (p_[pos_] == '\r' && pos_ + 1 < n_ && p_[pos_ + 1] == '\n') ++pos_;
    ++pos_;
    ++line_;
  }
  return std::string_view(p_ + b, e - b);
}

void TextCursor::skip_line_end() {
  while (pos_ < n_ && (p_[pos_] == ' ' || p_[pos_] == '\t')) ++pos_;
  if (pos_ < n_ && p_[pos_] == '\r') ++pos_;
  if (pos_ < n_ && p_[pos_] == '\n') {
    ++pos_;
    ++line_;
  }
}

bool TextCursor::at_end() {
  skip_space();
  return pos_ >= n_;
}

}  // namespace vm
