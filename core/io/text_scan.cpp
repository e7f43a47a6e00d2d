// Token cursor and number parsing for the text readers. Decimals with at
// most 15 significant digits and a power-of-ten exponent within +-22 are
// converted by one exact division or multiplication (Clinger's fast path:
// both operands are exact doubles, so the result is correctly rounded);
// anything else goes to strtod.
#include "core/io/text_scan.h"

#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace vm {
namespace {

bool parse_decimal_fast(std::string_view tok, double& out) {
  static constexpr double kPow10[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                      1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                      1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
  size_t i = 0, n = tok.size();
  bool negative = false;
  if (i < n && (tok[i] == '-' || tok[i] == '+')) negative = tok[i++] == '-';
  uint64_t mantissa = 0;
  int digits = 0, scale = 0;
  bool any = false;
  for (; i < n && tok[i] >= '0' && tok[i] <= '9'; ++i, any = true) {
    if (mantissa == 0 && tok[i] == '0') continue;
    if (++digits > 15) return false;
    mantissa = mantissa * 10 + uint64_t(tok[i] - '0');
  }
  if (i < n && tok[i] == '.') {
    for (++i; i < n && tok[i] >= '0' && tok[i] <= '9'; ++i, any = true) {
      --scale;
      if (mantissa == 0 && tok[i] == '0') continue;
      if (++digits > 15) return false;
      mantissa = mantissa * 10 + uint64_t(tok[i] - '0');
    }
  }
  if (!any) return false;
  if (i < n && (tok[i] == 'e' || tok[i] == 'E')) {
    ++i;
    bool eneg = false;
    if (i < n && (tok[i] == '-' || tok[i] == '+')) eneg = tok[i++] == '-';
    if (i == n) return false;
    int e = 0;
    for (; i < n && tok[i] >= '0' && tok[i] <= '9'; ++i) {
      if (e > 1000) return false;
      e = e * 10 + (tok[i] - '0');
    }
    scale += eneg ? -e : e;
  }
  if (i != n || scale < -22 || scale > 22) return false;
  double v = double(mantissa);  // exact: < 10^15 < 2^53
  v = scale < 0 ? v / kPow10[-scale] : v * kPow10[scale];
  out = negative ? -v : v;
  return true;
}

// A byte as \xNN (two lowercase hex digits).
void append_hex_escape(std::string& s, unsigned char c) {
  char buf[8];
  std::snprintf(buf, sizeof(buf), "\\x%02x", c);
  s += buf;
}

}  // namespace

bool parse_double(std::string_view tok, double& out) {
  if (parse_decimal_fast(tok, out)) return true;
  char buf[128];
  if (tok.empty() || tok.size() >= sizeof(buf)) return false;
  std::memcpy(buf, tok.data(), tok.size());
  buf[tok.size()] = '\0';
  char* end = nullptr;
  out = std::strtod(buf, &end);
  return end == buf + tok.size();
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
