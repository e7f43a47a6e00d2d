// A reader of exactly what core/io/vtk_writer writes (tests only): the XML
// header's DataArray tags and the appended raw block, raw or with VTK's
// zlib block layout, decoded independently of the writer's code.
#pragma once

#include <zlib.h>

#include <cstdint>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "core/util/result.h"

namespace vm::testing {

struct VtkArray {
  std::string section;  ///< enclosing element: PointData, CellData, Points, Cells, Polys
  std::string type, name;
  int components = 1;
  std::string bytes;  ///< decoded values
  /// zlib: the block header (count, block size, last partial size).
  uint64_t blocks = 0, block_size = 0, last_size = 0;
};

struct VtkFile {
  std::map<std::string, std::string> file_attributes, piece;
  std::string comment;  ///< text between "<!--" and "-->", if any
  std::string dataset;  ///< UnstructuredGrid / PolyData
  std::vector<VtkArray> arrays;

  const VtkArray* find(const std::string& section, const std::string& name) const {
    for (const auto& a : arrays)
      if (a.section == section && a.name == name) return &a;
    return nullptr;
  }
  template <class T>
  std::vector<T> values(const std::string& section, const std::string& name) const {
    const VtkArray* a = find(section, name);
    if (!a) return {};
    std::vector<T> v(a->bytes.size() / sizeof(T));
    std::memcpy(v.data(), a->bytes.data(), v.size() * sizeof(T));
    return v;
  }
  size_t piece_count(const std::string& key) const {
    auto it = piece.find(key);
    return it == piece.end() ? size_t(-1) : size_t(std::stoull(it->second));
  }
};

/// key="value" pairs of the tag text between '<' and '>'.
inline std::map<std::string, std::string> tag_attributes(const std::string& tag) {
  std::map<std::string, std::string> out;
  size_t p = 0;
  while ((p = tag.find('=', p)) != std::string::npos) {
    size_t k = p;
    while (k > 0 && tag[k - 1] != ' ') --k;
    const size_t q0 = tag.find('"', p), q1 = tag.find('"', q0 + 1);
    out[tag.substr(k, p - k)] = tag.substr(q0 + 1, q1 - q0 - 1);
    p = q1 + 1;
  }
  return out;
}

inline uint64_t u64_at(const std::string& s, size_t at) {
  uint64_t v = 0;
  std::memcpy(&v, s.data() + at, 8);
  return v;
}

inline Result<VtkFile> read_vtk_xml(const std::string& text) {
  using R = Result<VtkFile>;
  VtkFile f;
  const size_t appended = text.find("<AppendedData encoding=\"raw\">");
  if (appended == std::string::npos) return R::Error("no raw AppendedData");
  const size_t underscore = text.find('_', appended);
  if (underscore == std::string::npos) return R::Error("no '_' before the appended data");
  const size_t c0 = text.find("<!--");
  if (c0 != std::string::npos && c0 < appended)
    f.comment = text.substr(c0 + 4, text.find("-->", c0) - c0 - 4);
  const size_t data = underscore + 1;
  std::string section;
  bool zlib = false;
  for (size_t p = text.find('<', text.find("?>")); p < appended; p = text.find('<', p + 1)) {
    if (text.compare(p, 4, "<!--") == 0) {
      p = text.find("-->", p);
      continue;
    }
    const size_t end = text.find('>', p);
    const std::string tag = text.substr(p + 1, end - p - 1);
    const std::string name = tag.substr(0, tag.find_first_of(" />"));
    if (name == "VTKFile") {
      f.file_attributes = tag_attributes(tag);
      zlib = f.file_attributes.count("compressor") > 0;
    } else if (name == "UnstructuredGrid" || name == "PolyData") {
      f.dataset = name;
    } else if (name == "Piece") {
      f.piece = tag_attributes(tag);
    } else if (name == "DataArray") {
      auto at = tag_attributes(tag);
      VtkArray a;
      a.section = section;
      a.type = at["type"];
      a.name = at["Name"];
      if (at.count("NumberOfComponents")) a.components = std::stoi(at["NumberOfComponents"]);
      if (at["format"] != "appended") return R::Error("array not appended");
      size_t o = data + std::stoull(at["offset"]);
      if (!zlib) {
        const uint64_t n = u64_at(text, o);
        a.bytes = text.substr(o + 8, n);
      } else {
        a.blocks = u64_at(text, o);
        a.block_size = u64_at(text, o + 8);
        a.last_size = u64_at(text, o + 16);
        size_t block_at = o + 24 + 8 * a.blocks;
        for (uint64_t b = 0; b < a.blocks; ++b) {
          const uint64_t packed = u64_at(text, o + 24 + 8 * b);
          uLongf size = (b + 1 == a.blocks && a.last_size) ? a.last_size : a.block_size;
          std::string block(size, '\0');
          if (uncompress(reinterpret_cast<Bytef*>(block.data()), &size,
                         reinterpret_cast<const Bytef*>(text.data() + block_at),
                         uLong(packed)) != Z_OK)
            return R::Error("a zlib block does not inflate");
          block.resize(size);
          a.bytes += block;
          block_at += packed;
        }
      }
      f.arrays.push_back(std::move(a));
    } else if (name[0] != '/') {
      section = name;
    }
  }
  return f;
}

}  // namespace vm::testing
