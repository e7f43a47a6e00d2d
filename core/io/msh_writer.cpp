// Gmsh MSH writer (Gmsh reference manual, section "MSH file format":
// version 4.1 with $Entities and entity blocks, ASCII or binary, and the
// legacy 2.2 layout, ASCII). All nodes go in one block on the first entity
// of the highest dimension; each element block is its own entity carrying
// one physical tag.
#include "core/io/msh_writer.h"

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <limits>
#include <set>

#include "core/io/text_out.h"

namespace vm {
namespace {

static_assert(std::endian::native == std::endian::little,
              "the binary MSH writer copies values as little-endian bytes");

// The bytes of `v` as they are in memory (little-endian), for the binary
// sections; TextOut appends them like text.
template <class T>
void put(TextOut& out, T v) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  out.str(std::string_view(b, sizeof(T)));
}

Status validate(const MshModel& m) {
  const size_t nn = m.points.size() / 3;
  std::set<std::pair<int, int>> physicals, entities;
  for (const auto& p : m.physicals) {
    if (p.tag <= 0) return Status::Error("physical group tags must be positive");
    if (!physicals.insert({p.dim, p.tag}).second)
      return Status::Error("duplicate physical group tag " + std::to_string(p.tag));
  }
  for (const auto& b : m.blocks) {
    int dim = element_dimension(b.type);
    if (!physicals.count({dim, b.physical_tag}))
      return Status::Error("element block on entity " + std::to_string(b.entity_tag) +
                           " refers to missing physical group " + std::to_string(b.physical_tag));
    if (!entities.insert({dim, b.entity_tag}).second)
      return Status::Error("duplicate entity tag " + std::to_string(b.entity_tag));
    if (b.nodes.size() % size_t(nodes_per_element(b.type)) != 0)
      return Status::Error("element block node list has a partial element");
    for (int32_t v : b.nodes)
      if (v < 0 || size_t(v) >= nn)
        return Status::Error("element refers to node " + std::to_string(v) + " out of range");
  }
  return Status::Ok();
}

// "$MeshFormat" with the version, the file type (0 ASCII, 1 binary: then
// the int 1 in binary, by which a reader tells the byte order) and
// sizeof(size_t) = 8, then the provenance comment and $PhysicalNames, which
// are text in both file types.
void write_header(TextOut& out, const MshModel& m, const char* version, bool binary) {
  out.str("$MeshFormat\n");
  out.str(version);
  if (binary) {
    out.str(" 1 8\n");
    put<int32_t>(out, 1);
    out.ch('\n');
  } else {
    out.str(" 0 8\n");
  }
  out.str("$EndMeshFormat\n");
  if (!m.comment.empty()) {
    // A section Gmsh and meshio skip (they ignore unknown sections): one
    // line, no '$' that could end it early.
    std::string line = m.comment;
    for (char& c : line)
      if (c == '\n' || c == '\r' || c == '$') c = ' ';
    out.str("$Comments\n");
    out.str(line);
    out.str("\n$EndComments\n");
  }
  out.str("$PhysicalNames\n");
  out.integer(m.physicals.size());
  out.ch('\n');
  for (const auto& p : m.physicals) {
    out.integer(p.dim);
    out.ch(' ');
    out.integer(p.tag);
    out.str(" \"");
    out.str(p.name);
    out.str("\"\n");
  }
  out.str("$EndPhysicalNames\n");
}

size_t element_count(const MshModel& m) {
  size_t n = 0;
  for (const auto& b : m.blocks) n += b.nodes.size() / size_t(nodes_per_element(b.type));
  return n;
}

// An upper bound of the text's size, so that the buffer is allocated
// once: a node line holds its tag and 3 shortest doubles (at most 24
// characters each), an element line its tag, `element_extra` characters
// (MSH 2.2: type, tag count and 2 tags, small integers) and its node tags.
size_t text_size_bound(const MshModel& m, size_t element_extra) {
  const size_t nn = m.points.size() / 3, ne = element_count(m);
  const size_t node_tag = std::to_string(nn).size() + 1, elem_tag = std::to_string(ne).size() + 1;
  size_t refs = 0;
  for (const auto& b : m.blocks) refs += b.nodes.size();
  return 4096 + m.comment.size() + 256 * (m.physicals.size() + m.blocks.size()) +
         nn * (2 * node_tag + 3 * 25) + ne * (elem_tag + element_extra + 1) + refs * node_tag;
}

// " n1 n2 ...\n" with one-based node tags.
void write_element_nodes(TextOut& out, const int32_t* nodes, size_t count) {
  for (size_t k = 0; k < count; ++k) {
    out.ch(' ');
    out.integer(nodes[k] + 1);
  }
  out.ch('\n');
}

void write_point(TextOut& out, const double* p) {
  out.real(p[0]);
  out.ch(' ');
  out.real(p[1]);
  out.ch(' ');
  out.real(p[2]);
}

// The bounding box of a block's nodes (lo, hi: 3 doubles each; zeros for
// an empty block), its entity's in $Entities.
void entity_box(const MshModel& m, const MshBlock& b, double lo[3], double hi[3]) {
  for (int k = 0; k < 3; ++k) {
    lo[k] = b.nodes.empty() ? 0 : std::numeric_limits<double>::max();
    hi[k] = b.nodes.empty() ? 0 : std::numeric_limits<double>::lowest();
  }
  for (int32_t v : b.nodes)
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], m.points[3 * v + k]);
      hi[k] = std::max(hi[k], m.points[3 * v + k]);
    }
}

// The entity the one node block is on: {dim, tag} of the first block of
// the highest dimension ({2, 1} without blocks).
std::pair<int, int> node_entity(const MshModel& m) {
  for (int dim = 3; dim >= 2; --dim)
    for (const auto& b : m.blocks)
      if (element_dimension(b.type) == dim) return {dim, b.entity_tag};
  return {2, 1};
}

// The number of entities of dimensions 0..3 (the blocks': 2 and 3).
std::array<size_t, 4> entity_counts(const MshModel& m) {
  std::array<size_t, 4> counts{};
  for (const auto& b : m.blocks) ++counts[size_t(element_dimension(b.type))];
  return counts;
}

std::string write41(const MshModel& m) {
  TextOut out;
  const size_t nn = m.points.size() / 3;
  out.reserve(text_size_bound(m, 0));
  write_header(out, m, "4.1", false);

  // Entities: bounding box of each block's nodes.
  const auto counts = entity_counts(m);
  out.str("$Entities\n0 0 ");
  out.integer(counts[2]);
  out.ch(' ');
  out.integer(counts[3]);
  out.ch('\n');
  for (int dim = 2; dim <= 3; ++dim) {
    for (const auto& b : m.blocks) {
      if (element_dimension(b.type) != dim) continue;
      double lo[3], hi[3];
      entity_box(m, b, lo, hi);
      out.integer(b.entity_tag);
      out.ch(' ');
      write_point(out, lo);
      out.ch(' ');
      write_point(out, hi);
      out.str(" 1 ");
      out.integer(b.physical_tag);
      out.str(" 0\n");
    }
  }
  out.str("$EndEntities\n");

  // Nodes: one block on the first entity of the highest dimension.
  const auto [node_dim, node_tag] = node_entity(m);
  out.str("$Nodes\n");
  out.integer(nn > 0 ? 1 : 0);
  out.ch(' ');
  out.integer(nn);
  out.str(" 1 ");
  out.integer(nn);
  out.ch('\n');
  if (nn > 0) {
    out.integer(node_dim);
    out.ch(' ');
    out.integer(node_tag);
    out.str(" 0 ");
    out.integer(nn);
    out.ch('\n');
    for (size_t i = 1; i <= nn; ++i) {
      out.integer(i);
      out.ch('\n');
    }
    for (size_t i = 0; i < nn; ++i) {
      write_point(out, &m.points[3 * i]);
      out.ch('\n');
    }
  }
  out.str("$EndNodes\n");

  const size_t ne = element_count(m);
  out.str("$Elements\n");
  out.integer(m.blocks.size());
  out.ch(' ');
  out.integer(ne);
  out.str(" 1 ");
  out.integer(ne);
  out.ch('\n');
  size_t tag = 1;
  for (const auto& b : m.blocks) {
    const size_t npe = size_t(nodes_per_element(b.type));
    out.integer(element_dimension(b.type));
    out.ch(' ');
    out.integer(b.entity_tag);
    out.ch(' ');
    out.integer(int(b.type));
    out.ch(' ');
    out.integer(b.nodes.size() / npe);
    out.ch('\n');
    for (size_t e = 0; e < b.nodes.size(); e += npe) {
      out.integer(tag++);
      write_element_nodes(out, &b.nodes[e], npe);
    }
  }
  out.str("$EndElements\n");
  return out.take();
}

// The same sections in Gmsh's binary layout (file type 1, data size 8):
// counts and tags as size_t (uint64), entity dimensions, tags and types
// as int (int32), coordinates as double; each section's binary data ends
// with a newline before its $End line.
std::string write41_binary(const MshModel& m) {
  TextOut out;
  const size_t nn = m.points.size() / 3, ne = element_count(m);
  size_t refs = 0;
  for (const auto& b : m.blocks) refs += b.nodes.size();
  out.reserve(4096 + m.comment.size() + 256 * m.physicals.size() + 96 * m.blocks.size() + 32 * nn +
              8 * (ne + refs));
  write_header(out, m, "4.1", true);

  // Entities: 4 counts, then per surface / volume: tag, box, its physical
  // tag, no bounding entities.
  out.str("$Entities\n");
  for (size_t count : entity_counts(m)) put<uint64_t>(out, count);
  for (int dim = 2; dim <= 3; ++dim) {
    for (const auto& b : m.blocks) {
      if (element_dimension(b.type) != dim) continue;
      double box[6];
      entity_box(m, b, box, box + 3);
      put<int32_t>(out, b.entity_tag);
      for (double x : box) put<double>(out, x);
      put<uint64_t>(out, 1);
      put<int32_t>(out, b.physical_tag);
      put<uint64_t>(out, 0);
    }
  }
  out.str("\n$EndEntities\n");

  // Nodes: one block, its tags 1..nn, then the coordinates.
  const auto [node_dim, node_tag] = node_entity(m);
  out.str("$Nodes\n");
  for (size_t x : {nn > 0 ? size_t(1) : size_t(0), nn, size_t(1), nn}) put<uint64_t>(out, x);
  if (nn > 0) {
    put<int32_t>(out, node_dim);
    put<int32_t>(out, node_tag);
    put<int32_t>(out, 0);
    put<uint64_t>(out, nn);
    for (size_t i = 1; i <= nn; ++i) put<uint64_t>(out, i);
    for (size_t i = 0; i < 3 * nn; ++i) put<double>(out, m.points[i]);
  }
  out.str("\n$EndNodes\n");

  // Elements: per block its entity, type and count, then each element's
  // tag and one-based node tags.
  out.str("$Elements\n");
  for (size_t x : {m.blocks.size(), ne, size_t(1), ne}) put<uint64_t>(out, x);
  uint64_t tag = 1;
  for (const auto& b : m.blocks) {
    const size_t npe = size_t(nodes_per_element(b.type));
    put<int32_t>(out, element_dimension(b.type));
    put<int32_t>(out, b.entity_tag);
    put<int32_t>(out, int32_t(b.type));
    put<uint64_t>(out, b.nodes.size() / npe);
    for (size_t e = 0; e < b.nodes.size(); e += npe) {
      put<uint64_t>(out, tag++);
      for (size_t k = 0; k < npe; ++k) put<uint64_t>(out, uint64_t(b.nodes[e + k]) + 1);
    }
  }
  out.str("\n$EndElements\n");
  return out.take();
}

std::string write22(const MshModel& m) {
  TextOut out;
  out.reserve(text_size_bound(m, 24));
  const size_t nn = m.points.size() / 3;
  write_header(out, m, "2.2", false);
  out.str("$Nodes\n");
  out.integer(nn);
  out.ch('\n');
  for (size_t i = 0; i < nn; ++i) {
    out.integer(i + 1);
    out.ch(' ');
    write_point(out, &m.points[3 * i]);
    out.ch('\n');
  }
  out.str("$EndNodes\n");
  const size_t ne = element_count(m);
  out.str("$Elements\n");
  out.integer(ne);
  out.ch('\n');
  size_t tag = 1;
  for (const auto& b : m.blocks) {
    const size_t npe = size_t(nodes_per_element(b.type));
    for (size_t e = 0; e < b.nodes.size(); e += npe) {
      out.integer(tag++);
      out.ch(' ');
      out.integer(int(b.type));
      out.str(" 2 ");
      out.integer(b.physical_tag);
      out.ch(' ');
      out.integer(b.entity_tag);
      write_element_nodes(out, &b.nodes[e], npe);
    }
  }
  out.str("$EndElements\n");
  return out.take();
}

}  // namespace

int nodes_per_element(MshElementType type) {
  switch (type) {
    case MshElementType::kTriangle:
      return 3;
    case MshElementType::kQuad:
      return 4;
    case MshElementType::kTetrahedron:
      return 4;
    case MshElementType::kPrism:
      return 6;
  }
  return 0;
}

int element_dimension(MshElementType type) {
  return type == MshElementType::kTriangle || type == MshElementType::kQuad ? 2 : 3;
}

Result<std::string> write_msh(const MshModel& model, MshVersion version, MshEncoding encoding) {
  if (encoding == MshEncoding::kBinary && version != MshVersion::k41)
    return Status::Error("binary MSH is written in version 4.1 only: ask for 4.1, or text for 2.2");
  Status s = validate(model);
  if (!s.ok()) return s;
  if (version == MshVersion::k22) return write22(model);
  return encoding == MshEncoding::kBinary ? write41_binary(model) : write41(model);
}

Result<MshVersion> parse_msh_version(const std::string& text) {
  if (text == "4.1" || text == "4") return MshVersion::k41;
  if (text == "2.2" || text == "2") return MshVersion::k22;
  return Result<MshVersion>::Error("unknown MSH version '" + text + "' (use 4.1 or 2.2)");
}

}  // namespace vm
