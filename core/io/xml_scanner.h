// A purpose-built scanner of XML tags and attributes, enough for VTK XML
// files: it reads tags one by one and leaves the text between them to the
// caller, so that a reader can stop before binary data (VTK's appended raw
// section) that no XML parser accepts.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "core/util/result.h"

namespace vm {

struct XmlAttribute {
  std::string_view name;
  std::string_view value;  ///< raw, between the quotes (see xml_unescape)
};

struct XmlTag {
  enum Kind { kStart, kEnd, kEmpty };  ///< <a ...>, </a>, <a .../>
  Kind kind = kStart;
  std::string_view name;
  std::vector<XmlAttribute> attributes;
  size_t begin = 0;  ///< offset of '<'
  size_t end = 0;    ///< offset one past '>'

  /// The raw value of attribute `name`, or nullptr when absent.
  const std::string_view* attribute(std::string_view name) const {
    for (const XmlAttribute& a : attributes)
      if (a.name == name) return &a.value;
    return nullptr;
  }
};

class XmlScanner {
 public:
  explicit XmlScanner(std::string_view text, size_t pos = 0) : text_(text), pos_(pos) {}

  /// Reads the next tag, skipping text, comments, processing instructions
  /// (<?...?>), <!DOCTYPE ...> and CDATA sections. Returns true with `tag`
  /// filled, false at the end of the text, or an error naming the byte
  /// offset of a malformed tag.
  Result<bool> next(XmlTag& tag);

  size_t pos() const { return pos_; }

 private:
  std::string_view text_;
  size_t pos_;
};

/// Replaces the five predefined entities and numeric character references
/// (&#NN; &#xNN;, ASCII only; others are kept as written).
std::string xml_unescape(std::string_view raw);

}  // namespace vm
