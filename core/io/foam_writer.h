// OpenFOAM's native mesh, `constant/polyMesh` (FoamFile dictionaries, as
// OpenFOAM v1912 and later read them; the large lists as text or binary):
// the cells of a mixed volume mesh (tetrahedra and prisms) as faces with an
// owner and a neighbour, the surface groups as boundary patches and the
// volume groups as cell zones.
#pragma once

#include <string>
#include <vector>

#include "core/io/output_file.h"
#include "core/mesh/volume_mesh.h"
#include "core/util/result.h"

namespace vm {

/// How the mesh's lists are written: as text, or `format binary` with
/// 32-bit labels and 64-bit scalars, little-endian (arch
/// "LSB;label=32;scalar=64").
enum class FoamFormat { kAscii, kBinary };

/// The files of an OpenFOAM case holding `mesh`, paths relative to the case:
/// - "constant/polyMesh/points": the vertices (mesh.points, in the model's
///   unit as given: OpenFOAM works in metres, so scale them before).
/// - "constant/polyMesh/faces", "owner", "neighbour": every face of the
///   cells once. Cells are the tetrahedra (0 .. num_tets()-1) then the
///   prisms. Internal faces first, ordered by owner then neighbour, with
///   owner < neighbour (OpenFOAM's upper-triangular order); then the
///   boundary faces grouped by patch, patches in surface tag order. Every
///   face's vertex cycle makes its normal (right-hand rule) point out of its
///   owner.
/// - "constant/polyMesh/boundary": one patch per surface tag that has
///   exterior faces (faces of one cell). A tag named "wall" or
///   "outer_wall" is of type `wall` (group `wall`), every other one of type
///   `patch` (openings such as inlet, outlet_N, and wall_<cap>).
/// - "constant/polyMesh/cellZones": one zone per region with cells, named
///   region_names[region].
/// - "constant/polyMesh/faceZones": only when a surface tag has faces between
///   two cells (an interface, e.g. `wall` under a vessel wall): one zone per
///   such tag with those internal faces (no baffle), flipMap 1 where the
///   face's owner-outward normal is opposite to the tagged face's.
/// - "system/controlDict", "system/fvSchemes", "system/fvSolution":
///   minimal ones (no solver settings), so that OpenFOAM's tools (checkMesh,
///   foamToVTK, splitMeshRegions) run on the case as written; a solver run
///   replaces them.
/// - "case.foam": empty; the file ParaView opens the case by.
/// `format` kBinary: points, faces, owner and neighbour in OpenFOAM's binary
/// layout (each list "n\n(" + n raw values + ")", an empty one "0"; points
/// as 3n doubles; faces as a faceCompactList: the n + 1 offsets, then the
/// faces' vertices in one list), controlDict's writeFormat binary; the
/// boundary and zone dictionaries stay text.
/// `surface_names[tag]` / `region_names[region]` name the tags ("" or
/// missing = "patch_<tag+1>" / "zone_<region+1>"). `comment` (e.g.
/// provenance_text) goes into each file's header as a note.
/// Errors: tag arrays not one per face or element, a tag or vertex index
/// out of range, a face shared by more than two cells, a boundary face of a
/// cell that no tagged triangle or quad covers, a tagged face that is no
/// cell's face, a name that is not an OpenFOAM word (letters, digits, '_',
/// '-', '.') or is used twice, in binary more than 2^31 face vertices in all.
Result<std::vector<OutputFile>> foam_case_files(const VolumeMesh& mesh,
                                                const std::vector<std::string>& surface_names,
                                                const std::vector<std::string>& region_names,
                                                const std::string& comment,
                                                FoamFormat format = FoamFormat::kAscii);

}  // namespace vm
