// Strict base64 decoding (RFC 4648 standard alphabet, '=' padding), as VTK
// XML files use it for inline "binary" arrays and base64-encoded appended
// data.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "core/util/result.h"

namespace vm {

/// Decodes base64 text incrementally. Whitespace (space, tab, CR, LF, FF,
/// VT) between characters is skipped. Several independently padded base64
/// strings written back to back decode as the concatenation of their bytes
/// (VTK encodes a compressed array's header and its data separately).
/// Strict otherwise: any other character outside the alphabet, '=' anywhere
/// but at the end of a 4-character group, and text ending inside a group are
/// errors naming the position.
class Base64Stream {
 public:
  /// Decodes text[begin, end). `origin` is added to positions in messages so
  /// that they are positions in the file the text came from.
  /// Precondition: begin <= end <= text.size().
  Base64Stream(std::string_view text, size_t begin, size_t end, size_t origin = 0)
      : text_(text), pos_(begin), end_(end), origin_(origin) {}

  /// Appends the next `n` decoded bytes to `out`. Fails, before allocating,
  /// when the text cannot hold n more bytes, and on a bad character or a text
  /// ending inside a group.
  Status read(size_t n, std::vector<uint8_t>& out);

  /// Appends every byte left (until the end of the text) to `out`.
  Status read_to_end(std::vector<uint8_t>& out);

  /// An upper bound of the bytes still decodable (3 per 4 characters left).
  size_t max_remaining() const { return (pending_len_ - pending_pos_) + (end_ - pos_) / 4 * 3; }

  /// Position (in the file, see `origin`) of the next character to decode.
  size_t position() const { return origin_ + pos_; }

 private:
  // Decodes the next group of 4 characters into pending_. Returns false with
  // an empty error_ at the end of the text, false with error_ on bad input.
  bool decode_group();

  std::string_view text_;
  size_t pos_, end_, origin_;
  uint8_t pending_[3] = {0, 0, 0};
  size_t pending_pos_ = 0, pending_len_ = 0;
  std::string error_;
};

/// Decodes a whole base64 text (see Base64Stream for the rules). Errors name
/// the position (0-based character index) and the bad character.
Result<std::vector<uint8_t>> base64_decode(std::string_view text);

}  // namespace vm
