// XML tag scanner (see xml_scanner.h): a tag is '<' name (attribute="value"
// | attribute='value')* ('>' | '/>'), or '</' name '>'. Comments, processing
// instructions, declarations and CDATA are skipped whole.
#include "core/io/xml_scanner.h"

#include <cstdint>

namespace vm {
namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

bool is_name_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
         c == '-' || c == '.' || c == ':' || static_cast<unsigned char>(c) >= 0x80;
}

}  // namespace

Result<bool> XmlScanner::next(XmlTag& tag) {
  const size_t n = text_.size();
  auto error = [&](const std::string& what, size_t at) {
    return Result<bool>::Error("malformed XML at byte " + std::to_string(at) + ": " + what);
  };
  while (true) {
    size_t lt = text_.find('<', pos_);
    if (lt == std::string_view::npos) {
      pos_ = n;
      return false;
    }
    std::string_view rest = text_.substr(lt);
    auto skip_to = [&](std::string_view terminator) -> bool {
      size_t e = text_.find(terminator, lt);
      if (e == std::string_view::npos) return false;
      pos_ = e + terminator.size();
      return true;
    };
    if (rest.starts_with("<!--")) {
      if (!skip_to("-->")) return error("unterminated comment", lt);
      continue;
    }
    if (rest.starts_with("<![CDATA[")) {
      if (!skip_to("]]>")) return error("unterminated CDATA section", lt);
      continue;
    }
    if (rest.starts_with("<?")) {
      if (!skip_to("?>")) {
        return error("unterminated processing instruction", lt);
      }
      continue;
    }
    if (rest.starts_with("<!")) {
      if (!skip_to(">")) return error("unterminated declaration", lt);
      continue;
    }
    tag = XmlTag{};
    tag.begin = lt;
    size_t p = lt + 1;
    if (p < n && text_[p] == '/') {
      tag.kind = XmlTag::kEnd;
      ++p;
    }
    size_t name_begin = p;
    while (p < n && is_name_char(text_[p])) ++p;
    if (p == name_begin) return error("'<' not followed by a tag name", lt);
    tag.name = text_.substr(name_begin, p - name_begin);
    while (true) {
      while (p < n && is_space(text_[p])) ++p;
      if (p >= n) return error("tag <" + std::string(tag.name) + "> is not closed", lt);
      char c = text_[p];
      if (c == '>') {
        ++p;
        break;
      }
      if (c == '/' && p + 1 < n && text_[p + 1] == '>' && tag.kind == XmlTag::kStart) {
        tag.kind = XmlTag::kEmpty;
        p += 2;
        break;
      }
      if (tag.kind == XmlTag::kEnd) {
        return error("unexpected character in closing tag </" + std::string(tag.name) + ">", p);
      }
      size_t an = p;
      while (p < n && is_name_char(text_[p])) ++p;
      if (p == an) {
        return error("unexpected character in tag <" + std::string(tag.name) + ">", p);
      }
      XmlAttribute a;
      a.name = text_.substr(an, p - an);
      while (p < n && is_space(text_[p])) ++p;
      if (p >= n || text_[p] != '=') {
        return error(
            "attribute " + std::string(a.name) + " of <" + std::string(tag.name) + "> has no value",
            p);
      }
      ++p;
      while (p < n && is_space(text_[p])) ++p;
      if (p >= n || (text_[p] != '"' && text_[p] != '\'')) {
        return error("value of attribute " + std::string(a.name) + " is not quoted", p);
      }
      char quote = text_[p++];
      size_t close = text_.find(quote, p);
      if (close == std::string_view::npos) {
        return error("value of attribute " + std::string(a.name) + " is not closed", p);
      }
      a.value = text_.substr(p, close - p);
      tag.attributes.push_back(a);
      p = close + 1;
    }
    tag.end = p;
    pos_ = p;
    return true;
  }
}

std::string xml_unescape(std::string_view raw) {
  std::string s;
  s.reserve(raw.size());
  for (size_t i = 0; i < raw.size(); ++i) {
    if (raw[i] != '&') {
      s += raw[i];
      continue;
    }
    size_t semi = raw.find(';', i);
    if (semi == std::string_view::npos || semi - i > 10) {
      s += raw[i];
      continue;
    }
    std::string_view e = raw.substr(i + 1, semi - i - 1);
    char c = 0;
    if (e == "lt") {
      c = '<';
    } else if (e == "gt") {
      c = '>';
    } else if (e == "amp") {
      c = '&';
    } else if (e == "quot") {
      c = '"';
    } else if (e == "apos") {
      c = '\'';
    } else if (e.size() >= 2 && e[0] == '#') {
      bool hex = e[1] == 'x' || e[1] == 'X';
      uint32_t v = 0;
      bool ok = e.size() > (hex ? 2u : 1u);
      for (size_t k = hex ? 2 : 1; k < e.size() && ok; ++k) {
        char d = e[k];
        int digit = d >= '0' && d <= '9'          ? d - '0'
                    : hex && d >= 'a' && d <= 'f' ? d - 'a' + 10
                    : hex && d >= 'A' && d <= 'F' ? d - 'A' + 10
                                                  : -1;
        if (digit < 0) ok = false;
        v = v * (hex ? 16 : 10) + uint32_t(digit);
        if (v > 0x10FFFF) ok = false;
      }
      if (ok && v > 0 && v < 128) c = char(v);
    }
    if (c) {
      s += c;
      i = semi;
    } else {
      s += raw[i];
    }
  }
  return s;
}

}  // namespace vm
