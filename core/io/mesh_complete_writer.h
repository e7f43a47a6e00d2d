// SimVascular's `mesh-complete` folder, the layout svFSI (and svSolver's
// presolver) read a mesh from: the volume, its exterior boundary, one file
// per named face, and a sidecar naming the ids.
#pragma once

#include <string>
#include <vector>

#include "core/io/output_file.h"
#include "core/mesh/volume_mesh.h"
#include "core/util/result.h"

namespace vm {

/// The files of a `mesh-complete` folder, paths relative to it, in order:
/// - "mesh-complete.mesh.vtu": the volume (write_vtu: ModelRegionID,
///   GlobalElementID, GlobalNodeID).
/// - "mesh-complete.exterior.vtp": the exterior boundary, i.e. the
///   triangles and quads of `mesh` that are a face of exactly one element
///   (an interface such as `wall` under a vessel wall is not exterior).
/// - "mesh-surfaces/<name>.vtp": one per surface tag that has faces,
///   interfaces included.
/// - "mesh-complete.names.json": {"faces": [{"id", "name", "file",
///   "triangles", "quads", "exterior"}...], "regions": [{"id", "name",
///   "elements", "tetrahedra", "prisms"}...], "provenance": comment}, with
///   "exterior" true when every face of the tag is exterior.
/// The VTPs keep only their own points, with cell data ModelFaceID (surface
/// tag + 1), GlobalElementID (1-based number of the element the face is
/// oriented outward of, else of the one it bounds: the VTU's
/// GlobalElementID) and point data GlobalNodeID (the VTU's numbering).
/// `surface_names[tag]` / `region_names[tag]` name the tags ("" = unused);
/// a used tag with no name is called "face_<id>" / "region_<id>".
/// `comment` (e.g. provenance_text) goes into every VTK file as an XML
/// comment and into the sidecar. Errors: those of write_vtu, tag arrays not
/// one per face, a negative tag, a face that is no element's face or is
/// shared by more than two, a surface name that is not a file name
/// (letters, digits, '_', '-') or is used by two tags.
Result<std::vector<OutputFile>> mesh_complete_files(const VolumeMesh& mesh,
                                                    const std::vector<std::string>& surface_names,
                                                    const std::vector<std::string>& region_names,
                                                    const std::string& comment);

}  // namespace vm
