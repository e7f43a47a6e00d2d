// Gmsh MSH ASCII writer (Gmsh reference manual, section "MSH file format":
// version 4.1 with $Entities and entity blocks, and the legacy 2.2 layout).
// All nodes go in one block on the first entity of the highest dimension;
// each element block is its own entity carrying one physical tag.
#include "core/io/msh_writer.h"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <limits>
#include <set>

#include "core/io/text_out.h"

namespace vm {
namespace {

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

void write_header(TextOut& out, const MshModel& m, const char* version) {
  out.str("$MeshFormat\n");
  out.str(version);
  out.str(" 0 8\n$EndMeshFormat\n");
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

std::string write41(const MshModel& m) {
  TextOut out;
  const size_t nn = m.points.size() / 3;
  out.reserve(text_size_bound(m, 0));
  write_header(out, m, "4.1");

  // Entities: bounding box of each block's nodes.
  int counts[4] = {0, 0, 0, 0};
  for (const auto& b : m.blocks) ++counts[element_dimension(b.type)];
  out.str("$Entities\n0 0 ");
  out.integer(counts[2]);
  out.ch(' ');
  out.integer(counts[3]);
  out.ch('\n');
  for (int dim = 2; dim <= 3; ++dim) {
    for (const auto& b : m.blocks) {
      if (element_dimension(b.type) != dim) continue;
      double lo[3], hi[3];
      for (int k = 0; k < 3; ++k) {
        lo[k] = std::numeric_limits<double>::max();
        hi[k] = std::numeric_limits<double>::lowest();
      }
      for (int32_t v : b.nodes)
        for (int k = 0; k < 3; ++k) {
          lo[k] = std::min(lo[k], m.points[3 * v + k]);
          hi[k] = std::max(hi[k], m.points[3 * v + k]);
        }
      if (b.nodes.empty())
        for (int k = 0; k < 3; ++k) lo[k] = hi[k] = 0;
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
  int node_dim = 2, node_entity = 1;
  for (int dim = 3; dim >= 2; --dim) {
    auto it = std::find_if(m.blocks.begin(), m.blocks.end(),
                           [&](const MshBlock& b) { return element_dimension(b.type) == dim; });
    if (it != m.blocks.end()) {
      node_dim = dim;
      node_entity = it->entity_tag;
      break;
    }
  }
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
    out.integer(node_entity);
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

std::string write22(const MshModel& m) {
  TextOut out;
  out.reserve(text_size_bound(m, 24));
  const size_t nn = m.points.size() / 3;
  write_header(out, m, "2.2");
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

Result<std::string> write_msh(const MshModel& model, MshVersion version) {
  Status s = validate(model);
  if (!s.ok()) return s;
  return version == MshVersion::k41 ? write41(model) : write22(model);
}

Result<MshVersion> parse_msh_version(const std::string& text) {
  if (text == "4.1" || text == "4") return MshVersion::k41;
  if (text == "2.2" || text == "2") return MshVersion::k22;
  return Result<MshVersion>::Error("unknown MSH version '" + text + "' (use 4.1 or 2.2)");
}

}  // namespace vm
