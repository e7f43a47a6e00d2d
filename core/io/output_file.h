// One file of a multi-file output (a `mesh-complete` folder, an OpenFOAM
// case, a ZIP archive's entries): its path relative to the output's root and its contents.
#pragma once

#include <string>

namespace vm {

/// The file formats a mesh can be written in (core/pipeline/write_outputs.h).
enum class OutputFormat {
  kMsh,           ///< Gmsh MSH of the volume (or of the wall, surface only)
  kVtu,           ///< VTK UnstructuredGrid of the volume, ModelRegionID per cell
  kVtp,           ///< VTK PolyData of the boundary faces, ModelFaceID per face
  kStl,           ///< binary STL of the remeshed wall alone
  kMeshComplete,  ///< the mesh-complete folder (VTU, exterior VTP, one VTP a face)
  kFoam,          ///< an OpenFOAM case folder (constant/polyMesh, foam_writer.h)
};

/// path: relative, '/'-separated (e.g. "mesh-surfaces/wall.vtp"); bytes: the
/// file's contents (binary-safe).
struct OutputFile {
  std::string path;
  std::string bytes;
};

}  // namespace vm
