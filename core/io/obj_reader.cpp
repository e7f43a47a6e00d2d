// Wavefront OBJ reader (polygonal subset of the OBJ specification, Wavefront
// Advanced Visualizer manual, appendix B1). Two passes over the lines: the
// first counts the vertices (positive indices may refer to vertices defined
// later in the file), the second reads vertices and faces.
#include "core/io/obj_reader.h"

#include <cmath>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "core/io/cells_to_triangles.h"
#include "core/io/text_scan.h"

namespace vm {
namespace {

std::string num(uint64_t n) { return std::to_string(n); }

// Splits a line into whitespace-separated tokens; a token starting with '#'
// ends the line (comment).
size_t tokenize(std::string_view line, std::vector<std::string_view>& tokens) {
  tokens.clear();
  size_t i = 0, n = line.size();
  while (true) {
    while (i < n && is_text_space(line[i])) ++i;
    if (i >= n || line[i] == '#') break;
    size_t b = i;
    while (i < n && !is_text_space(line[i])) ++i;
    tokens.push_back(line.substr(b, i - b));
  }
  return tokens.size();
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && is_text_space(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_text_space(s.back())) s.remove_suffix(1);
  return s;
}

// Iterates over the lines of a buffer (without their line ends: \n, \r\n
// or a lone \r).
class Lines {
 public:
  explicit Lines(std::span<const uint8_t> bytes) : cur_(bytes) {}
  bool next(std::string_view& line) {
    if (cur_.remaining() == 0) return false;
    line = cur_.rest_of_line();
    ++number_;
    return true;
  }
  size_t number() const { return number_; }

 private:
  TextCursor cur_;
  size_t number_ = 0;
};

bool is_vertex_line(std::string_view line) {
  size_t i = 0;
  while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
  return i + 1 < line.size() && line[i] == 'v' && (line[i + 1] == ' ' || line[i + 1] == '\t');
}

}  // namespace

Result<SurfaceFile> read_obj(std::span<const uint8_t> bytes, const SurfaceReadOptions& options) {
  // Pass 1: vertex count.
  uint64_t total_vertices = 0;
  {
    Lines lines(bytes);
    std::string_view line;
    while (lines.next(line)) total_vertices += is_vertex_line(line);
  }
  if (total_vertices > uint64_t(std::numeric_limits<int32_t>::max())) {
    return Status::Error("file too large: " + num(total_vertices) + " vertices");
  }

  SurfaceFile file;
  file.points.reserve(3 * total_vertices);
  Lines lines(bytes);
  std::string_view line;
  std::vector<std::string_view> tok;
  std::vector<int64_t> corners;
  auto fail = [&](const std::string& what) {
    return Result<SurfaceFile>::Error("OBJ line " + num(lines.number()) + ": " + what);
  };
  bool any_group = false;
  std::string group = "default";
  int32_t group_label = 0;         // 0: not yet given to the current group
  std::vector<std::string> names;  // label - 1 -> name
  std::vector<int32_t> face_labels;
  size_t small_faces = 0, unknown_lines = 0;
  std::string unknown_example;
  while (lines.next(line)) {
    if (tokenize(line, tok) == 0) continue;
    std::string_view kw = tok[0];
    if (kw == "v") {
      if (tok.size() < 4) return fail("a vertex needs 3 coordinates (v x y z)");
      for (int k = 1; k <= 3; ++k) {
        double x;
        if (!parse_double(tok[k], x))
          return fail("vertex coordinate " + quoted(tok[k]) + " is not a number");
        if (!std::isfinite(x)) {
          return fail("vertex " + num(file.points.size() / 3 + 1) +
                      " has a non-finite coordinate (" + (std::isnan(x) ? "NaN" : "Inf") + ")");
        }
        file.points.push_back(x);
      }
    } else if (kw == "f" || kw == "fo") {
      corners.clear();
      const int64_t defined = int64_t(file.points.size() / 3);
      for (size_t k = 1; k < tok.size(); ++k) {
        std::string_view c = tok[k];
        size_t slash = c.find('/');
        std::string_view first = slash == std::string_view::npos ? c : c.substr(0, slash);
        int64_t index;
        if (!parse_int64(first, index)) {
          return fail("face corner " + quoted(c) + " is not a vertex index");
        }
        if (index == 0) return fail("face index 0 (OBJ indices start at 1)");
        int64_t resolved;
        if (index < 0) {
          resolved = defined + index;
          if (resolved < 0) {
            return fail("relative face index " + std::to_string(index) + " is out of range: only " +
                        num(uint64_t(defined)) + " vertices are defined before this line");
          }
        } else {
          if (uint64_t(index) > total_vertices) {
            return fail("face index " + std::to_string(index) + " is out of range: the file has " +
                        num(total_vertices) + " vertices");
          }
          resolved = index - 1;
        }
        corners.push_back(resolved);
      }
      if (corners.size() < 3) {
        ++small_faces;
        continue;
      }
      if (polygon_triangles(corners.size()) > options.max_triangles - file.triangles.size() / 3) {
        return Result<SurfaceFile>::Error("file too large: more than " +
                                          num(options.max_triangles) +
                                          " triangles (the limit of this build)");
      }
      if (group_label == 0) {
        names.push_back(group);
        group_label = int32_t(names.size());
      }
      append_fan(corners.data(), corners.size(), file.triangles);
      face_labels.resize(file.triangles.size() / 3, group_label);
    } else if (kw == "g" || kw == "o") {
      any_group = true;
      std::string_view rest = trim(line.substr(size_t(kw.data() - line.data()) + kw.size()));
      size_t hash = rest.find('#');
      if (hash != std::string_view::npos) rest = trim(rest.substr(0, hash));
      std::string name = rest.empty() ? "default" : std::string(rest);
      if (name != group) {
        group = name;
        group_label = 0;
        for (size_t i = 0; i < names.size(); ++i)
          if (names[i] == name) group_label = int32_t(i + 1);
      }
    } else if (kw == "vn" || kw == "vt" || kw == "vp" || kw == "usemtl" || kw == "mtllib" ||
               kw == "s" || kw == "l" || kw == "p" || kw == "mg" || kw == "usemap" ||
               kw == "maplib" || kw == "lod" || kw == "shadow_obj" || kw == "trace_obj") {
      continue;
    } else {
      if (unknown_lines++ == 0) unknown_example = std::string(kw.substr(0, 32));
    }
  }
  if (file.triangles.empty()) {
    return Result<SurfaceFile>::Error("OBJ file without any face (f) of 3 or more vertices");
  }
  if (any_group) {
    file.face_labels = std::move(face_labels);
    file.label_array = "obj groups";
    for (size_t i = 0; i < names.size(); ++i)
      file.face_names.emplace_back(int32_t(i + 1), names[i]);
  }
  if (small_faces > 0) {
    file.warnings.push_back(num(small_faces) + " faces with fewer than 3 vertices were skipped");
  }
  if (unknown_lines > 0) {
    file.warnings.push_back(num(unknown_lines) + " lines with unsupported OBJ statements (e.g. " +
                            quoted(unknown_example) + ") were ignored");
  }
  file.format = "Wavefront OBJ";
  file.format_id = "obj";
  return file;
}

}  // namespace vm
