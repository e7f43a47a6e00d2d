// Gmsh MSH writer: format 4.1 (default), ASCII or binary, and 2.2 (ASCII).
// Format reference: Gmsh reference manual, "MSH file format".
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/util/result.h"

namespace vm {

enum class MshVersion { k41, k22 };

/// The file type: text, or Gmsh's binary layout (version 4.1 only:
/// little-endian, size_t of 8 bytes; $PhysicalNames and the $Comments
/// stay text). Both hold the same nodes, elements and tags.
enum class MshEncoding { kAscii, kBinary };

/// Gmsh element type codes used by vesselmesh.
enum class MshElementType : int { kTriangle = 2, kQuad = 3, kTetrahedron = 4, kPrism = 6 };

/// A named physical group. Tags are positive and unique per dimension (the
/// pipeline makes them unique across dimensions too: write_outputs.h
/// physical_tags).
struct MshPhysical {
  int dim = 2;  ///< 2 surface, 3 volume
  int tag = 1;
  std::string name;
};

/// Elements of one type on one geometric entity, which belongs to exactly one
/// physical group (so every element is in a physical group).
/// nodes: nodes_per_element(type) * count zero-based point indices.
struct MshBlock {
  MshElementType type = MshElementType::kTriangle;
  int entity_tag = 1;    ///< unique per dimension among blocks
  int physical_tag = 1;  ///< tag of an MshPhysical of the block's dimension
  std::vector<int32_t> nodes;
};

/// Everything written to a file. points: 3 doubles per node; node i is
/// written with tag i + 1.
struct MshModel {
  /// Provenance (one line), written in a $Comments section after the
  /// header when not empty; readers skip sections they do not know.
  std::string comment;
  std::vector<double> points;
  std::vector<MshPhysical> physicals;
  std::vector<MshBlock> blocks;
};

int nodes_per_element(MshElementType type);
int element_dimension(MshElementType type);

/// Serializes `model` (binary: the file's bytes in the string). Errors: a
/// block referring to a missing physical group, a node index out of range,
/// duplicate entity tags in one dimension, binary with version 2.2. Nodes
/// no element uses are still written (Gmsh accepts them).
Result<std::string> write_msh(const MshModel& model, MshVersion version = MshVersion::k41,
                              MshEncoding encoding = MshEncoding::kAscii);

/// Parses "4.1" / "2.2"; error for anything else.
Result<MshVersion> parse_msh_version(const std::string& text);

}  // namespace vm
