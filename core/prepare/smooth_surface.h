// Smoothing of raw segmentation surfaces before remeshing: voxel staircases
// (marching cubes on a binary mask) are detected and smoothed without
// shrinking, and any surface may be smoothed on request.
//
// Detection: the facets of a staircase face a few directions only (the axes
// of the voxel grid, their face diagonals and body diagonals, in the
// proportions of the voxel's sides), its terraces lie on planes one voxel
// apart, and its vertices on the half-voxel lattice (the middles of the grid
// edges). The voxel is measured from the spacing of that lattice.
//
// Smoothing: Taubin's lambda|mu filter (G. Taubin, "A signal processing
// approach to fair surface design", SIGGRAPH 1995) with umbrella weights,
// which removes the voxel-scale frequencies without the shrinking of plain
// Laplacian smoothing; after each pass a global offset along the vertex
// normals restores the enclosed volume (as the volume constraint of Desbrun,
// Meyer, Schroeder and Barr, "Implicit fairing of irregular meshes using
// diffusion and curvature flow", SIGGRAPH 1999), and every vertex is kept
// within half a voxel of where it was (its displacement clamped to the
// ellipsoid of half-voxel radii). Rims of openings move only along their
// loop, in their plane, so openings stay where they were; flat regions
// (planar caps) keep their plane and their rims.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string_view>

#include "core/mesh/adjacency.h"
#include "core/mesh/surface_mesh.h"
#include "core/mesh/triangle_normals.h"

namespace vm {

/// How a surface is smoothed in preparation.
struct Smoothing {
  enum class Mode { kAuto, kOff, kPasses } mode = Mode::kAuto;
  int passes = 0;  ///< kPasses: the number of passes (1..1000)
};

/// "auto", "off" or "passes".
const char* smoothing_mode_name(Smoothing::Mode mode);

struct StaircaseOptions {
  /// A facet faces a grid direction when its normal is within this angle
  /// of it (degrees).
  double direction_tolerance_degrees = 5;
  /// A facet is a terrace (faces an axis) within this angle (degrees).
  double terrace_tolerance_degrees = 1;
  /// A coordinate is on the half-voxel lattice within this fraction of the
  /// half voxel.
  double lattice_tolerance = 0.1;
  /// A staircase has at least these shares of its area on grid directions
  /// and of its vertices on the lattice ...
  double min_direction_fraction = 0.6;
  double min_lattice_fraction = 0.6;
  /// ... and at least this many terrace planes (all axes together).
  int min_terraces = 6;
};

/// What detect_staircase found. The grid is taken in the model's axes (an
/// image volume whose axes are oblique to the model's is not recognised).
struct StaircaseReport {
  bool staircase = false;
  /// Share of the surface's area whose facet normals lie within the
  /// tolerance of a grid direction (axis, face or body diagonal), in [0, 1].
  double direction_fraction = 0;
  /// Share of the vertices whose three coordinates lie on the half-voxel
  /// lattice, in [0, 1] (0 when the coordinates show no lattice).
  double lattice_fraction = 0;
  /// The voxel's side along x, y and z (model units), from the lattice of
  /// the vertices' coordinates; zeros when not a staircase.
  std::array<double, 3> spacing{};
  /// The largest side of the voxel (model units; 0 when not a staircase).
  double voxel = 0;
  /// Terrace planes found (distinct planes of axis-facing facets, all axes).
  int terraces = 0;
};

/// Decides whether `mesh` is the raw staircase of a binary voxel mask and
/// measures its voxel. Cost: O(n log n) in the triangles. Any mesh is
/// accepted (an empty one is not a staircase). `normals`:
/// triangle_normals(mesh) when already known (else computed here).
StaircaseReport detect_staircase(const SurfaceMesh& mesh, const StaircaseOptions& options = {},
                                 const TriangleNormals* normals = nullptr);

struct SmoothOptions {
  int passes = 10;  ///< lambda|mu passes (0: none)
  /// Taubin's factors: pass-band 1 / lambda + 1 / mu ~ 0.11 (lambda > 0 >
  /// mu, |mu| slightly above lambda).
  double lambda = 0.5, mu = -0.53;
  /// The largest displacement of a vertex from its input position along x,
  /// y and z (the radii of the ellipsoid it stays in; model units; > 0):
  /// half the voxel's sides.
  std::array<double, 3> max_displacement{};
  /// Restore the enclosed volume (openings closed by fans) after each pass.
  bool keep_volume = true;
  /// A boundary loop whose vertices are all within this fraction of the
  /// smallest max_displacement from its plane slides along itself in that
  /// plane; a loop that is not planar stays fixed. The same tolerance makes
  /// a flat region planar.
  double planar_tolerance = 0.01;
  /// Flat regions (planar caps) of at least this area (model units squared;
  /// 0: none held) keep their plane: triangles grown across edges while
  /// their normals stay within flat_angle_degrees of the first one's. Their
  /// inner vertices move in the plane, their rims along themselves in the
  /// plane, so a cap stays flat and its rim sharp.
  double flat_min_area = 0;
  double flat_angle_degrees = 1;
  /// The voxel's sides when the surface is a staircase (model units; zeros
  /// otherwise): flat regions facing a grid direction are its terraces, to
  /// be smoothed, not caps.
  std::array<double, 3> grid{};
};

/// What smooth_surface did.
struct SmoothReport {
  int passes = 0;
  /// Largest distance of a vertex from its input position (model units),
  /// and the largest in units of the ellipsoid (<= 1 up to rounding).
  double max_displacement = 0, max_displacement_ratio = 0;
  /// Enclosed volume (openings closed by fans from their centroids) before
  /// and after (model units cubed).
  double volume_before = 0, volume_after = 0;
  size_t flat_regions = 0;    ///< planar caps held
  size_t held_vertices = 0;   ///< on openings and flat regions: moved in their plane
  size_t fixed_vertices = 0;  ///< on non-planar openings, bow-ties, pinches: not moved
};

/// Smooths `mesh` in place: moves vertices only (the triangles and their
/// count are unchanged). Preconditions: `adj` is build_adjacency(mesh),
/// without non-manifold edges, triangles consistently oriented (outward
/// for the volume to be positive). Nothing moves (and the report is empty)
/// unless passes > 0 and every max_displacement > 0. Cost: O(passes n).
SmoothReport smooth_surface(SurfaceMesh& mesh, const TriangleAdjacency& adj,
                            const SmoothOptions& options);

/// The passes that take a staircase's steps away: 6 (2 voxel / median
/// edge length)^2, i.e. the smoothing spreads over about two voxels (a
/// diffusion reaches as the square root of its passes; 24 for marching
/// cubes' edges of about a voxel; measured on the binary phantoms: dihedral
/// angles above 60 degrees are gone after 16 and the mean distance to the
/// smooth surface levels off by 25), at least 10, at most 200. `voxel` > 0
/// in model units.
int staircase_passes(const SurfaceMesh& mesh, double voxel);

/// Median edge length of `mesh` (model units; 0 for an empty mesh).
double median_edge_length(const SurfaceMesh& mesh);

}  // namespace vm
