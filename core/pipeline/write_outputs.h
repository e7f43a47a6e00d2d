// The files of a meshed result, in the format asked: Gmsh MSH (4.1 or 2.2),
// VTK (the volume as VTU, the boundary faces with their ids as VTP), the
// remeshed wall as STL, SimVascular's `mesh-complete` folder for svFSI, or
// an OpenFOAM case (constant/polyMesh).
// Every file records its provenance where the format allows, and may be
// converted to another length unit.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "core/io/msh_writer.h"
#include "core/io/output_file.h"
#include "core/pipeline/mesh_job.h"
#include "core/prepare/units.h"
#include "core/util/result.h"

namespace vm {

/// "msh", "vtu", "vtp", "stl", "mesh-complete", "foam".
std::string_view format_name(OutputFormat format);
/// The format a file name asks for by its extension (.msh, .vtu, .vtp,
/// .stl, .zip: mesh-complete, .foam: OpenFOAM case), case-insensitive. Errors list the extensions.
Result<OutputFormat> format_for_path(std::string_view path);

struct WriteOptions {
  MshVersion msh_version = MshVersion::k41;
  /// MSH in Gmsh's binary layout (version 4.1 only).
  bool msh_binary = false;
  /// The arrays of a VTU or VTP file compressed with zlib in VTK's block
  /// layout (the mesh-complete folder's files stay raw).
  bool vtk_compress = false;
  /// The OpenFOAM case's points, faces, owner and neighbour in binary.
  bool foam_binary = false;
  /// The unit to write in (kGuess: the input's, no conversion).
  LengthUnit units = LengthUnit::kGuess;
  /// One line of provenance (provenance_text), written where the format
  /// has room for it: an MSH $Comments section, an XML comment in VTK
  /// files, the mesh-complete sidecar, the STL header (truncated to 80
  /// bytes).
  std::string provenance;
};

/// The write options of a job's options (MSH version and file type, VTK
/// compression, OpenFOAM binary, unit); no provenance.
WriteOptions write_options(const MeshJobOptions& options);

/// The MSH file type of the options {msh_version} and {msh_binary}: binary
/// is version 4.1 only (a kBadOption naming {msh_binary} with 2.2).
Result<MshEncoding> msh_encoding(MshVersion version, bool binary);

/// Whether `format` holds a volume mesh (VTU, mesh-complete, foam).
bool volume_format(OutputFormat format);

/// The physical tag number of each group of a result's files, unique across
/// dimensions (gmshToFoam names cell zones by number, so a surface group and
/// a volume group must never share one): the named surface tags get 1..k in
/// tag order, then the named regions k+1..k+m in region order; an unnamed
/// ("" = unused) tag or region gets 0. `surface[t]` is the number of surface
/// tag t, `region[r]` of region r. The MSH physical tags, VTK's ModelFaceID
/// and ModelRegionID and mesh-complete's ids are all these numbers.
struct PhysicalTags {
  std::vector<int> surface, region;
};
PhysicalTags physical_tags(const std::vector<std::string>& surface_names,
                           const std::vector<std::string>& region_names);

/// The physical groups a result's files have, with their element counts
/// and tag numbers (physical_tags): one per used surface tag (dimension 2),
/// then one per used region (3); surface only: `wall`.
std::vector<OutputGroup> output_groups(const MeshJobResult& result);

/// The MSH model of a result (the volume with its groups, or the wall as
/// `wall` when surface only), its points scaled by `scale`.
MshModel msh_model(const MeshJobResult& result, double scale = 1);

/// The result's files in `format`: one file named "mesh.<ext>" for the
/// single-file formats, the folder's files (paths relative to it) for
/// mesh-complete and foam (an OpenFOAM case: foam_case_files; write it in
/// metres, `units`, for OpenFOAM's solvers). Errors: a volume format (VTU,
/// mesh-complete, foam) for a
/// surface-only result; a writer's error.
Result<std::vector<OutputFile>> write_outputs(const MeshJobResult& result, OutputFormat format,
                                              const WriteOptions& options = {});

}  // namespace vm
