// OpenFOAM polyMesh writer (foam_writer.h): every cell face is found once by
// grouping the faces of all cells and the tagged triangles and quads by
// vertex set (group_faces); a set of two cells is an internal face (owner
// the lower cell), of one a boundary face, which a tagged face in its group
// names the patch of.
#include "core/io/foam_writer.h"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cstdio>
#include <set>
#include <span>

#include "core/io/text_out.h"
#include "core/mesh/face_groups.h"

namespace vm {
namespace {

static_assert(std::endian::native == std::endian::little,
              "the binary OpenFOAM lists are copied as little-endian bytes");

/// The FoamFile header of a file; `note` and `comment` optional. Binary:
/// `format binary` and the arch entry of 32-bit labels and 64-bit scalars.
void header(TextOut& t, std::string_view cls, std::string_view location, std::string_view object,
            const std::string& comment, const std::string& note = "", bool binary = false) {
  t.str("/* OpenFOAM file written by vesselmesh */\n");
  if (!comment.empty()) {
    t.str("// ");
    for (char c : comment) t.ch(c == '\n' || c == '\r' ? ' ' : c);
    t.ch('\n');
  }
  t.str("FoamFile\n{\n    version     2.0;\n    format      ");
  t.str(binary ? "binary" : "ascii");
  t.str(";\n    class       ");
  t.str(cls);
  if (binary) t.str(";\n    arch        \"LSB;label=32;scalar=64\"");
  if (!note.empty()) {
    t.str(";\n    note        \"");
    t.str(note);
    t.ch('"');
  }
  t.str(";\n    location    \"");
  t.str(location);
  t.str("\";\n    object      ");
  t.str(object);
  t.str(";\n}\n\n");
}

/// `values` (int32 labels or doubles) as an OpenFOAM binary list body:
/// "n\n(" then the n values' little-endian bytes, then ")\n"; an empty
/// list is "0\n", as OpenFOAM writes it (no bytes, no brackets).
template <class T>
void binary_list(TextOut& t, std::span<const T> values, size_t n) {
  t.integer(int64_t(n));
  t.ch('\n');
  if (n == 0) return;
  t.ch('(');
  t.str(std::string_view(reinterpret_cast<const char*>(values.data()), values.size_bytes()));
  t.str(")\n");
}

/// `n` labels as an OpenFOAM list body "n\n(\n...\n)\n", ten a line.
template <class Get>
void label_list(TextOut& t, size_t n, Get get) {
  t.integer(int64_t(n));
  t.str("\n(\n");
  for (size_t i = 0; i < n; ++i) {
    t.integer(int64_t(get(i)));
    t.ch(i % 10 == 9 || i + 1 == n ? '\n' : ' ');
  }
  t.str(")\n");
}

/// The indices 0..n-1 as a range (Emscripten's libc++ 14 has no
/// std::views::iota).
struct Indices {
  size_t n;
  struct iterator {
    size_t i;
    size_t operator*() const { return i; }
    iterator& operator++() {
      ++i;
      return *this;
    }
    bool operator!=(const iterator& o) const { return i != o.i; }
  };
  iterator begin() const { return {0}; }
  iterator end() const { return {n}; }
  size_t size() const { return n; }
};

/// The file `location`/`object` of class `cls`: the header, then an
/// OpenFOAM list "n\n(\n...)\n" of the n `items`, each written by
/// `entry(t, item)`.
template <class Items, class Entry>
OutputFile list_file(std::string_view cls, const std::string& location, const std::string& object,
                     const std::string& comment, const Items& items, Entry entry) {
  TextOut t;
  header(t, cls, location, object, comment);
  t.integer(int64_t(items.size()));
  t.str("\n(\n");
  for (const auto& item : items) entry(t, item);
  t.str(")\n");
  return {location + "/" + object, t.take()};
}

/// The dictionary system/`object`: the header, then `body`.
OutputFile system_dictionary(const std::string& object, const std::string& comment,
                             std::string_view body) {
  TextOut t;
  header(t, "dictionary", "system", object, comment);
  t.str(body);
  return {"system/" + object, t.take()};
}

/// An OpenFOAM word we write: letters, digits, '_', '-', '.'.
bool is_word(const std::string& s) {
  if (s.empty()) return false;
  for (char c : s)
    if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
          c == '-' || c == '.'))
      return false;
  return true;
}

std::string name_or(const std::vector<std::string>& names, size_t i, const char* prefix) {
  if (i < names.size() && !names[i].empty()) return names[i];
  return prefix + std::to_string(i + 1);
}

/// Whether cycles a and b (same n vertices) run the same way round.
bool same_turn(const int32_t* a, const int32_t* b, int n) {
  for (int i = 0; i < n; ++i)
    if (b[i] == a[0]) return b[(i + 1) % n] == a[1];
  return false;
}

}  // namespace

Result<std::vector<OutputFile>> foam_case_files(const VolumeMesh& mesh,
                                                const std::vector<std::string>& surface_names,
                                                const std::vector<std::string>& region_names,
                                                const std::string& comment, FoamFormat format) {
  using R = Result<std::vector<OutputFile>>;
  const size_t nt = mesh.num_tets(), np = mesh.num_prisms(), ncells = nt + np;
  const size_t ntri = mesh.num_triangles(), nq = mesh.num_quads();
  const size_t nv = mesh.num_vertices();
  if (mesh.tet_region.size() != nt || mesh.prism_region.size() != np)
    return R::Error("OpenFOAM: region tags are not one per tetrahedron and prism");
  if (mesh.triangle_tag.size() != ntri || mesh.quad_tag.size() != nq)
    return R::Error("OpenFOAM: surface tags are not one per triangle and quad");
  if (ncells == 0 || ncells > size_t(INT32_MAX) / 5)
    return R::Error("OpenFOAM: the mesh has " + std::to_string(ncells) +
                    " cells; it needs at least one and fewer than 429 million");
  for (const auto* a : {&mesh.tets, &mesh.prisms, &mesh.triangles, &mesh.quads})
    for (int32_t v : *a)
      if (v < 0 || size_t(v) >= nv)
        return R::Error("OpenFOAM: vertex index " + std::to_string(v) + " out of range (" +
                        std::to_string(nv) + " vertices)");
  for (const auto* a : {&mesh.tet_region, &mesh.prism_region, &mesh.triangle_tag, &mesh.quad_tag})
    for (int32_t tag : *a)
      if (tag < 0 || tag > 1000000)
        return R::Error("OpenFOAM: tag " + std::to_string(tag) + " out of range");

  auto where = [&](int32_t vertex) {
    const double* p = &mesh.points[3 * size_t(vertex)];
    char tmp[96];
    std::snprintf(tmp, sizeof(tmp), "(%.6g, %.6g, %.6g)", p[0], p[1], p[2]);
    return std::string(tmp);
  };

  // Phase 1: the cells' faces (4 a tetrahedron, 5 a prism, each an outward
  // cycle), then the tagged triangles and quads, grouped by vertex set:
  // in each group its cells' faces first, by cell.
  const std::vector<int32_t> faces = volume_mesh_faces(mesh);
  const size_t ncf = 4 * nt + 5 * np;  // the cells' faces
  const FaceGroups groups = group_faces(faces.data(), faces.size() / 4, nv);
  auto size_of = [&](size_t f) { return faces[4 * f + 3] == kNoFourthVertex ? 3 : 4; };
  auto smallest = [&](size_t f) {
    return *std::min_element(&faces[4 * f], &faces[4 * f] + size_of(f));
  };
  auto cell_of = [&](size_t f) { return int32_t(face_element(f, nt)); };

  // Phase 2: the faces of the mesh, the groups with cells: internal faces
  // (two cells) and boundary faces (one). Face g is face owner_face[g] of
  // the list, of cell owner[g] (the lower cell); neighbour[g] is the other
  // cell, -1 on the boundary. group_of[f]: the face of tagged face f, -1
  // when none.
  std::vector<int32_t> owner_face, owner, neighbour;
  std::vector<int32_t> group_of(ntri + nq, -1);
  for (size_t g = 0; g < groups.num_groups(); ++g) {
    const size_t n = groups.size(g);
    size_t cells = 0;
    while (cells < n && groups.face(g, cells) < ncf) ++cells;
    if (cells > 2)
      return R::Error("OpenFOAM: a face at " + where(smallest(groups.face(g, 0))) +
                      " is shared by " + std::to_string(cells) +
                      " cells; the volume mesh is not conforming");
    if (cells == 0) continue;
    for (size_t k = cells; k < n; ++k) group_of[groups.face(g, k) - ncf] = int32_t(owner.size());
    owner_face.push_back(int32_t(groups.face(g, 0)));
    owner.push_back(cell_of(groups.face(g, 0)));
    neighbour.push_back(cells == 2 ? cell_of(groups.face(g, 1)) : -1);
  }
  const size_t ngroups = owner.size();

  // Phase 3: the tagged faces name the patch of a boundary face, or put an
  // internal face in a face zone.
  std::vector<int32_t> group_tag(ngroups, -1);
  struct ZoneFace {
    int32_t tag;
    size_t group;
    bool flip;
  };
  std::vector<ZoneFace> zone_faces;
  size_t ntags = 0;
  for (size_t f = 0; f < ntri + nq; ++f) {
    const bool tri = f < ntri;
    const int32_t* v = &faces[4 * (ncf + f)];
    const int n = tri ? 3 : 4;
    const int32_t tag = tri ? mesh.triangle_tag[f] : mesh.quad_tag[f - ntri];
    ntags = std::max(ntags, size_t(tag) + 1);
    const int32_t g = group_of[f];
    if (g < 0)
      return R::Error("OpenFOAM: a face of " + name_or(surface_names, size_t(tag), "patch_") +
                      " at " + where(v[0]) + " is no cell's face");
    if (neighbour[size_t(g)] < 0)
      group_tag[size_t(g)] = tag;
    else
      zone_faces.push_back(
          {tag, size_t(g), !same_turn(v, &faces[4 * size_t(owner_face[size_t(g)])], n)});
  }
  for (size_t g = 0; g < ngroups; ++g)
    if (neighbour[g] < 0 && group_tag[g] < 0)
      return R::Error("OpenFOAM: a boundary face at " + where(smallest(size_t(owner_face[g]))) +
                      " has no surface tag (no triangle or quad of the mesh covers it)");

  // Phase 4: face order. Internal faces by (owner, neighbour); boundary
  // faces by (tag, owner); the order of groups in `order`.
  std::vector<size_t> order;
  order.reserve(ngroups);
  size_t ninternal = 0;
  for (size_t g = 0; g < ngroups; ++g)
    if (neighbour[g] >= 0) order.push_back(g);
  ninternal = order.size();
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    if (owner[a] != owner[b]) return owner[a] < owner[b];
    return neighbour[a] < neighbour[b];
  });
  for (size_t g = 0; g < ngroups; ++g)
    if (neighbour[g] < 0) order.push_back(g);
  std::stable_sort(order.begin() + long(ninternal), order.end(), [&](size_t a, size_t b) {
    if (group_tag[a] != group_tag[b]) return group_tag[a] < group_tag[b];
    return owner[a] < owner[b];
  });
  std::vector<size_t> patch_start(ntags + 1, ngroups), patch_size(ntags, 0);
  for (size_t i = order.size(); i-- > ninternal;) {
    patch_start[size_t(group_tag[order[i]])] = i;
    ++patch_size[size_t(group_tag[order[i]])];
  }
  std::vector<int32_t> face_of_group(ngroups);
  for (size_t i = 0; i < order.size(); ++i) face_of_group[order[i]] = int32_t(i);

  // Names: patches and zones, each an OpenFOAM word, unique among its kind.
  auto check_names = [&](const std::vector<size_t>& used, const std::vector<std::string>& names,
                         const char* prefix, const char* what) -> Status {
    std::set<std::string> seen;
    for (size_t i : used) {
      const std::string name = name_or(names, i, prefix);
      if (!is_word(name))
        return Status::Error("OpenFOAM: the " + std::string(what) + " name \"" + name +
                             "\" is not a word (letters, digits, '_', '-' and '.' only)");
      if (!seen.insert(name).second)
        return Status::Error("OpenFOAM: two " + std::string(what) + "s are named \"" + name + "\"");
    }
    return Status::Ok();
  };
  std::vector<size_t> patches, zones_used, face_zones;
  for (size_t tag = 0; tag < ntags; ++tag)
    if (patch_size[tag] > 0) patches.push_back(tag);
  std::vector<std::vector<int32_t>> cells_of(1);  // per region, its cells
  for (size_t c = 0; c < ncells; ++c) {
    const size_t r = size_t(c < nt ? mesh.tet_region[c] : mesh.prism_region[c - nt]);
    if (r >= cells_of.size()) cells_of.resize(r + 1);
    cells_of[r].push_back(int32_t(c));
  }
  for (size_t r = 0; r < cells_of.size(); ++r)
    if (!cells_of[r].empty()) zones_used.push_back(r);
  std::stable_sort(zone_faces.begin(), zone_faces.end(), [&](const ZoneFace& a, const ZoneFace& b) {
    return a.tag != b.tag ? a.tag < b.tag : face_of_group[a.group] < face_of_group[b.group];
  });
  for (const ZoneFace& z : zone_faces)
    if (face_zones.empty() || face_zones.back() != size_t(z.tag))
      face_zones.push_back(size_t(z.tag));
  if (Status st = check_names(patches, surface_names, "patch_", "patch"); !st.ok()) return st;
  if (Status st = check_names(zones_used, region_names, "zone_", "cell zone"); !st.ok()) return st;
  if (Status st = check_names(face_zones, surface_names, "patch_", "face zone"); !st.ok())
    return st;

  // Phase 5: the files. Points, faces, owner and neighbour in binary when
  // asked (faces as a faceCompactList: the n + 1 offsets into the flat
  // vertex list, then that list); the dictionaries stay text.
  const std::string poly = "constant/polyMesh";
  const std::string note = "nPoints:" + std::to_string(nv) + "  nCells:" + std::to_string(ncells) +
                           "  nFaces:" + std::to_string(ngroups) +
                           "  nInternalFaces:" + std::to_string(ninternal);
  std::vector<int32_t> face_owner(ngroups), face_neighbour(ninternal);
  for (size_t i = 0; i < ngroups; ++i) face_owner[i] = owner[order[i]];
  for (size_t i = 0; i < ninternal; ++i) face_neighbour[i] = neighbour[order[i]];
  std::vector<OutputFile> files;
  if (format == FoamFormat::kBinary) {
    std::vector<int32_t> offsets(ngroups + 1, 0), vertices;
    vertices.reserve(4 * ngroups);
    for (size_t i = 0; i < ngroups; ++i) {
      const int32_t* v = &faces[4 * size_t(owner_face[order[i]])];
      vertices.insert(vertices.end(), v, v + size_of(size_t(owner_face[order[i]])));
      if (vertices.size() > size_t(INT32_MAX))
        return R::Error(
            "OpenFOAM: the faces have more than 2^31 vertices in all, beyond "
            "32-bit labels; write the case as text");
      offsets[i + 1] = int32_t(vertices.size());
    }
    auto add = [&](std::string_view cls, const char* object, const std::string& file_note,
                   auto body) {
      TextOut t;
      header(t, cls, poly, object, comment, file_note, true);
      body(t);
      files.push_back({poly + "/" + object, t.take()});
    };
    add("vectorField", "points", "",
        [&](TextOut& t) { binary_list(t, std::span<const double>(mesh.points), nv); });
    add("faceCompactList", "faces", "", [&](TextOut& t) {
      binary_list(t, std::span<const int32_t>(offsets), offsets.size());
      binary_list(t, std::span<const int32_t>(vertices), vertices.size());
    });
    add("labelList", "owner", note,
        [&](TextOut& t) { binary_list(t, std::span<const int32_t>(face_owner), ngroups); });
    add("labelList", "neighbour", note,
        [&](TextOut& t) { binary_list(t, std::span<const int32_t>(face_neighbour), ninternal); });
  } else {
    files.push_back(
        list_file("vectorField", poly, "points", comment, Indices{nv}, [&](TextOut& t, size_t v) {
          t.ch('(');
          for (int k = 0; k < 3; ++k) {
            if (k) t.ch(' ');
            t.real(mesh.points[3 * v + size_t(k)]);
          }
          t.str(")\n");
        }));
    files.push_back(list_file("faceList", poly, "faces", comment, order, [&](TextOut& t, size_t g) {
      const int32_t* v = &faces[4 * size_t(owner_face[g])];
      const int n = size_of(size_t(owner_face[g]));
      t.ch(char('0' + n));  // 3 or 4
      t.ch('(');
      for (int k = 0; k < n; ++k) {
        if (k) t.ch(' ');
        t.integer(v[k]);
      }
      t.str(")\n");
    }));
    // (No structured binding: Emscripten's clang 14 cannot capture one.)
    for (const auto& list :
         {std::pair{"owner", &face_owner}, std::pair{"neighbour", &face_neighbour}}) {
      const std::vector<int32_t>& labels = *list.second;
      TextOut t;
      header(t, "labelList", poly, list.first, comment, note);
      label_list(t, labels.size(), [&](size_t i) { return labels[i]; });
      files.push_back({poly + "/" + list.first, t.take()});
    }
  }
  files.push_back(list_file(
      "polyBoundaryMesh", poly, "boundary", comment, patches, [&](TextOut& t, size_t tag) {
        const std::string name = name_or(surface_names, tag, "patch_");
        const bool wall = name == "wall" || name == "outer_wall";
        t.str("    " + name + "\n    {\n        type            ");
        t.str(wall ? "wall;\n        inGroups        List<word> 1(wall);\n" : "patch;\n");
        t.str("        nFaces          ");
        t.integer(int64_t(patch_size[tag]));
        t.str(";\n        startFace       ");
        t.integer(int64_t(patch_start[tag]));
        t.str(";\n    }\n");
      }));
  files.push_back(
      list_file("regIOobject", poly, "cellZones", comment, zones_used, [&](TextOut& t, size_t r) {
        t.str(name_or(region_names, r, "zone_") +
              "\n{\n    type cellZone;\n    cellLabels List<label> ");
        label_list(t, cells_of[r].size(), [&](size_t i) { return cells_of[r][i]; });
        t.str(";\n}\n");
      }));
  if (!face_zones.empty()) {
    files.push_back(list_file(
        "regIOobject", poly, "faceZones", comment, face_zones, [&](TextOut& t, size_t tag) {
          size_t first = 0;
          while (size_t(zone_faces[first].tag) != tag) ++first;
          size_t last = first;
          while (last < zone_faces.size() && size_t(zone_faces[last].tag) == tag) ++last;
          t.str(name_or(surface_names, tag, "patch_") +
                "\n{\n    type faceZone;\n    faceLabels List<label> ");
          label_list(t, last - first,
                     [&](size_t i) { return face_of_group[zone_faces[first + i].group]; });
          t.str(";\n    flipMap List<bool> ");
          label_list(t, last - first, [&](size_t i) { return zone_faces[first + i].flip ? 1 : 0; });
          t.str(";\n}\n");
        }));
  }
  files.push_back(system_dictionary(
      "controlDict", comment,
      std::string("startFrom       startTime;\nstartTime       0;\nstopAt          endTime;\n"
                  "endTime         1;\ndeltaT          1;\nwriteControl    timeStep;\n"
                  "writeInterval   1;\nwriteFormat     ") +
          (format == FoamFormat::kBinary ? "binary" : "ascii") +
          ";\nwritePrecision  12;\ntimeFormat      general;\ntimePrecision   6;\n"
          "runTimeModifiable false;\n"));
  files.push_back(system_dictionary(
      "fvSchemes", comment,
      "ddtSchemes { default steadyState; }\ngradSchemes { default Gauss linear; }\n"
      "divSchemes { default none; }\nlaplacianSchemes { default Gauss linear corrected; }\n"
      "interpolationSchemes { default linear; }\nsnGradSchemes { default corrected; }\n"));
  files.push_back(system_dictionary("fvSolution", comment, ""));
  files.push_back({"case.foam", ""});
  return files;
}

}  // namespace vm
