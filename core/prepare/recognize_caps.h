// Recognising the caps of a capped vessel model (what SimVascular, VMTK and
// CAD-like segmentation exports hand over: a closed surface whose inlets and
// outlets are flat disks; what repair tools make of holes: fans around a
// lifted apex, smooth domes), so that each can be removed and its rim become
// an opening that vesselmesh caps itself (surface/cap_openings.h), with the
// boundary layer's rings in the cap plane (Marchandise et al., section 2:
// planar sections for the flow conditions).
//
// Phases: (1) candidate regions, from the face labels when the file has them
// (each connected part of a label), else grown across flat edges from seed
// triangles, bounded by sharp edges; (2) tests of each candidate: a disk
// (one component, one boundary loop, Euler characteristic 1), planar, a
// minority of the surface; without labels also a rim that is sharp all
// around, a wall meeting it at roughly a right angle and going straight
// back from it like a vessel of the cap's radius (which a voxel staircase's
// terrace does not); (3) unlabelled caps much narrower than the lumen
// across their rim (flat spots of a noisy wall) are dropped; (4) caps
// touching each other are dropped.
// Caps that are not planar (method: our own), on unlabelled surfaces: after
// phase 2, the triangles outside the planar caps are grown into regions
// bounded by the edges joining two crease vertices (vertices two of whose
// triangles' normals, bilaterally filtered, differ by more than the crease
// angle: every vertex of a crease loop has triangles of both sides, so the
// loop has no gap for a region to leak through; a region's islands are
// taken in); a region is a cap when it is a disk whose
// rim (the crease loop) is a round loop near its best-fit plane, lying on
// the outer side of that plane (bulging at most max_height rim radii, every
// triangle facing out of it), with the wall meeting it at a right angle and
// going back like a vessel of the rim's radius (phase 2's tests, about the
// rim's plane). Its shape: a fan (one vertex inside the rim) or a dome.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "core/mesh/adjacency.h"
#include "core/mesh/surface_mesh.h"
#include "core/mesh/triangle_normals.h"

namespace vm {

struct CapRecognitionOptions {
  /// Every triangle normal of a cap lies within this angle of the cap's mean
  /// normal (degrees).
  double planar_angle_degrees = 10;
  /// Every cap vertex lies within this fraction of the cap's equivalent
  /// radius sqrt(area / pi) from the cap's plane.
  double planar_distance = 0.03;
  /// A cap covers at most this fraction of the surface's area.
  double max_area_fraction = 0.3;
  /// Without labels: every rim edge turns the normal by more than this
  /// (degrees) ...
  double rim_angle_degrees = 40;
  /// ... the wall meets the cap at a mean angle of at least this (degrees;
  /// 90 = a right angle) ...
  double wall_angle_degrees = 55;
  /// ... and, within one cap radius of the rim (geodesically), the wall goes
  /// back from the cap plane at least this fast (depth gained per unit of
  /// geodesic distance, median; 1 = straight back) ...
  double min_depth_rate = 0.5;
  /// ... at a distance from the cap's axis within these multiples of the
  /// rim's mean radius (median).
  double min_radius_ratio = 0.6, max_radius_ratio = 1.6;
  /// A cap has at least this many rim vertices.
  int min_rim_vertices = 3;
  /// Without labels: a cap's equivalent radius is at least this fraction of
  /// the lumen's half width across its rim (the median half chord from its
  /// rim vertices; smaller: a flat spot on a vessel's side).
  double min_lumen_fraction = 0.25;
  /// Caps that are not planar (unlabelled surfaces): bounded by edges that
  /// turn the normal by more than this (degrees) ...
  double crease_angle_degrees = 20;
  /// ... a rim whose vertices lie within this fraction of its radius of its
  /// best-fit plane ...
  double rim_planar_distance = 0.15;
  /// ... a cap on the outer side of that plane, bulging at most this many
  /// rim radii beyond it ...
  double max_height = 1.2;
  /// ... each triangle facing out of it: its unit normal's component along
  /// the plane's normal at least this.
  double min_facing = 0.2;
};

/// What a recognised cap is: a labelled face, or by shape planar, a fan
/// around an apex off the rim's plane, or a dome.
enum class CapShape { kLabelled, kPlanar, kFan, kDome };

/// "labelled", "planar", "fan", "dome".
const char* cap_shape_name(CapShape shape);

/// One recognised cap.
struct RecognizedCap {
  std::vector<int32_t> triangles;  ///< triangle indices of the input
  int32_t label = -1;              ///< its face label, or -1 (found by shape)
  std::string name;                ///< the label's name in the file, or ""
  CapShape shape = CapShape::kPlanar;
  double area = 0;  ///< model units squared
  /// Equivalent radius sqrt(area / pi); of the rim's loop for a fan or a
  /// dome.
  double radius = 0;
  /// The cap's area-weighted centroid and mean normal (unit, out of the
  /// surface); for a fan or a dome, the rim's best-fit plane: the mean of
  /// its vertices and the unit normal of its vector area, out of the
  /// surface. Removing a fan or a dome means cutting at that plane.
  std::array<double, 3> centroid{};
  std::array<double, 3> normal{};
  /// How far the cap bulges beyond that plane (0 for a planar one).
  double height = 0;
  /// Found by its rim (a fan, a dome, or a nearly flat cap that failed the
  /// planar tests): removing it means cutting at the rim's best-fit plane.
  bool cut_at_rim = false;
};

struct CapRecognition {
  std::vector<RecognizedCap> caps;
  /// Why candidates that looked like caps were not taken (a labelled region
  /// that is not planar, two caps sharing a vertex...), for warnings.
  std::vector<std::string> notes;
};

/// Finds the caps of `mesh` (manifold edges expected; consistently outward
/// oriented, as prepare_surface leaves it). `labels`: one face label per
/// triangle, or empty (a single label for all is as good as none: the
/// caps are then found by shape); `label_names`: names of labels where the file gives
/// them. `adj` is build_adjacency(mesh); `normals`: triangle_normals(mesh)
/// when already known (else computed here).
CapRecognition recognize_caps(const SurfaceMesh& mesh, const TriangleAdjacency& adj,
                              std::span<const int32_t> labels,
                              std::span<const std::pair<int32_t, std::string>> label_names,
                              const CapRecognitionOptions& options = {},
                              const TriangleNormals* normals = nullptr);

}  // namespace vm
