// Base64 decoding, RFC 4648 section 4 (standard alphabet), one group of four
// characters (24 bits, 3 bytes; 2 or 1 with '=' padding) at a time.
#include "core/io/base64.h"

#include <cstdio>
#include <string>

namespace vm {
namespace {

// 0-63: the value of a base64 digit; 64: '='; 65: whitespace; 66: invalid.
constexpr uint8_t kPad = 64, kSpace = 65, kBad = 66;

struct Table {
  uint8_t v[256];
  constexpr Table() : v() {
    for (int i = 0; i < 256; ++i) v[i] = kBad;
    const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    for (int i = 0; i < 64; ++i) v[uint8_t(digits[i])] = uint8_t(i);
    v[uint8_t('=')] = kPad;
    for (char c : {' ', '\t', '\r', '\n', '\f', '\v'}) v[uint8_t(c)] = kSpace;
  }
};
constexpr Table kTable;

std::string describe(char c) {
  unsigned char u = static_cast<unsigned char>(c);
  char buf[32];
  if (u >= 32 && u < 127)
    std::snprintf(buf, sizeof(buf), "'%c'", c);
  else
    std::snprintf(buf, sizeof(buf), "byte 0x%02x", u);
  return buf;
}

}  // namespace

bool Base64Stream::decode_group() {
  uint32_t digits[4];
  int have = 0, pads = 0;
  size_t group_start = 0;
  while (have < 4) {
    while (pos_ < end_ && kTable.v[uint8_t(text_[pos_])] == kSpace) ++pos_;
    if (pos_ >= end_) {
      if (have == 0) return false;
      error_ = "base64 text ends inside a 4-character group (at position " +
               std::to_string(origin_ + pos_) + ", group starting at position " +
               std::to_string(origin_ + group_start) + ")";
      return false;
    }
    if (have == 0) group_start = pos_;
    uint8_t v = kTable.v[uint8_t(text_[pos_])];
    if (v == kBad) {
      error_ = "bad base64 character " + describe(text_[pos_]) + " at position " +
               std::to_string(origin_ + pos_);
      return false;
    }
    if (v == kPad) {
      if (have < 2) {
        error_ = "misplaced base64 padding '=' at position " + std::to_string(origin_ + pos_);
        return false;
      }
      ++pads;
      v = 0;
    } else if (pads > 0) {
      error_ = "base64 character " + describe(text_[pos_]) + " after padding '=' at position " +
               std::to_string(origin_ + pos_);
      return false;
    }
    digits[have++] = v;
    ++pos_;
  }
  uint32_t bits = digits[0] << 18 | digits[1] << 12 | digits[2] << 6 | digits[3];
  pending_[0] = uint8_t(bits >> 16);
  pending_[1] = uint8_t(bits >> 8);
  pending_[2] = uint8_t(bits);
  pending_pos_ = 0;
  pending_len_ = size_t(3 - pads);
  return true;
}

Status Base64Stream::read(size_t n, std::vector<uint8_t>& out) {
  if (!error_.empty()) return Status::Error(error_);
  if (n > max_remaining()) {
    return Status::Error("base64 data ends at position " + std::to_string(origin_ + end_) +
                         " but " + std::to_string(n) + " more bytes are needed (at most " +
                         std::to_string(max_remaining()) + " are left)");
  }
  out.reserve(out.size() + n);
  while (n > 0) {
    if (pending_pos_ == pending_len_ && !decode_group()) {
      if (!error_.empty()) return Status::Error(error_);
      return Status::Error("base64 data ends at position " + std::to_string(origin_ + end_) +
                           " but " + std::to_string(n) + " more bytes are needed");
    }
    while (n > 0 && pending_pos_ < pending_len_) {
      out.push_back(pending_[pending_pos_++]);
      --n;
    }
  }
  return Status::Ok();
}

Status Base64Stream::read_to_end(std::vector<uint8_t>& out) {
  if (!error_.empty()) return Status::Error(error_);
  out.reserve(out.size() + max_remaining());
  while (true) {
    while (pending_pos_ < pending_len_) out.push_back(pending_[pending_pos_++]);
    if (!decode_group()) break;
  }
  if (!error_.empty()) return Status::Error(error_);
  return Status::Ok();
}

Result<std::vector<uint8_t>> base64_decode(std::string_view text) {
  Base64Stream s(text, 0, text.size());
  std::vector<uint8_t> out;
  Status st = s.read_to_end(out);
  if (!st.ok()) return st;
  return out;
}

}  // namespace vm
