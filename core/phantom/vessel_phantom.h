// Synthetic segmentation-like vessel surfaces for tests, the bundled sample
// and benchmarks: an implicit vessel model (tubes of varying radius along
// curved centerlines, a bifurcation, optionally an aneurysm bulb) sampled on
// a voxel grid, extracted by marching cubes and cut open at the vessel ends,
// so that it looks like real segmentation output (staircase, oversampled,
// poorly shaped triangles).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/mesh/surface_mesh.h"
#include "core/util/result.h"

namespace vm {

enum class PhantomKind {
  kTube,         ///< one curved tube of varying radius, 2 openings
  kBifurcation,  ///< a parent vessel splitting into two branches, 3 openings
  kAneurysm,     ///< the bifurcation with a saccular bulb, 3 openings
  kTorus,        ///< a closed torus-like handle (genus 1, 0 openings)
  kTree,         ///< a trunk split three times plus two side branches: 17 branches, 11 openings
  /// Two vessels that touch and pass into each other, each its own closed
  /// shell (as two separately modelled vessels never joined): the surface
  /// crosses itself where they overlap; 4 openings once cut.
  kCrossing,
  /// A capped tube with 20 tiny capped side branches (6-triangle caps) and
  /// 186 labelled faces, as SimVascular exports large models
  /// (outlets_phantom.h); analytic: voxel, noise, binary, dirty and
  /// open_ends do not apply.
  kOutlets,
  /// A short, wide root (radius 1.7, its centerline 1.5 root radii long up
  /// to the branching) splitting into two branches (radii 1.1 and 1.0) that
  /// split again: 7 branches, 5 ends, the root the widest (a pulmonary
  /// trunk's shape).
  kRoot,
};

/// The shape of the caps closing the cut ends (PhantomOptions::flat_caps).
enum class PhantomCapShape {
  kFlat,  ///< a flat fan from the cut's centroid (SimVascular, VMTK)
  /// A fan around one apex lifted 0.1 radius off the cut plane (a capping
  /// tool's fill: the hard carotid's caps).
  kFan,
  /// A smooth dome (paraboloid) bulging 0.3, 0.6 or 1 radius beyond the cut
  /// (in turn from end to end), meeting the wall at a crease of 59, 40 or
  /// 27 degrees (a repair tool's smooth hole fill).
  kDome,
};

struct PhantomOptions {
  PhantomKind kind = PhantomKind::kBifurcation;
  /// Voxel edge length in model units (the model's parent radius is 1).
  /// Smaller voxels give more triangles (~ 1/voxel^2).
  double voxel = 0.1;
  /// Open the vessel ends by clipping with planes (openings); when false the
  /// surface is closed (the tube ends are rounded).
  bool open_ends = true;
  /// With open_ends: close each cut by a flat fan (a capped model, as
  /// SimVascular and VMTK export them: planar caps meeting the wall at a
  /// sharp rim). The surface is then closed.
  bool flat_caps = false;
  /// The shape of those caps (flat by default; the name flat_caps is kept
  /// for the flag that asks for them).
  PhantomCapShape cap_shape = PhantomCapShape::kFlat;
  /// Amplitude of the voxel-value noise, relative to the voxel size
  /// (0 = clean staircase). Deterministic for a given seed.
  double noise = 0.0;
  uint32_t seed = 1;
  /// The raw staircase of a binary voxel mask: the (noisy) field is
  /// thresholded per voxel to inside / outside before marching cubes, so
  /// every vertex sits at the middle of a grid edge and the facet normals
  /// lie on a few directions (the axes, their diagonals), with the voxel's
  /// constant step (what marching cubes on an unsmoothed segmentation
  /// gives). False: the field itself, a staircase smoothed by interpolation.
  bool binary = false;
  /// Segmentation defects added (add_segmentation_defects in
  /// dirty_phantom.h): holes, a fin, touching holes, duplicates, a flipped
  /// patch, a zero-area band. The surface is then neither manifold nor
  /// welded; the truth counts the holes.
  bool dirty = false;
  /// Damaged vessel ends (add_damaged_ends in dirty_phantom.h), as a vessel
  /// cut at an image border leaves them: at each opening, folded rim
  /// triangles, a flap through the wall, tiny loops and a twisted band that
  /// makes the surface non-orientable. Needs open_ends without flat_caps.
  bool damaged_ends = false;
  /// Uniform scale applied to the output coordinates (e.g. 10 for "mm").
  double scale = 1.0;
};

/// What the generator knows about the model, for tests to compare against.
struct PhantomTruth {
  int openings = 0;  ///< boundary loops expected when open_ends (0 with flat_caps)
  int genus = 0;
  /// Defect holes added by `dirty` (boundary loops besides the openings).
  int holes = 0;
  /// Radius of each opening or flat cap (same order as `opening_centers`),
  /// scaled.
  std::vector<double> opening_radii;
  std::vector<std::array<double, 3>> opening_centers;
  /// The free vessel ends of the model, whether cut open or not (same order
  /// as the cuts), scaled: the tip of the rounded end (the centerline's end
  /// plus its radius along the centerline), the unit direction out of the
  /// vessel there, and the radius.
  std::vector<std::array<double, 3>> end_tips;
  std::vector<std::array<double, 3>> end_directions;
  std::vector<double> end_radii;
  /// One face label per triangle (ModelFaceID) for the labelled kinds
  /// (kOutlets), and with flat caps (not dirty): 1 the wall, 2, 3, ...
  /// each cap, as SimVascular labels its faces; else empty.
  std::vector<int32_t> face_labels;
};

/// Builds the phantom. The result is a closed or open, oriented (outward),
/// manifold, single-component indexed triangle surface with welded vertices.
/// Errors: voxel <= 0 or a grid that would exceed ~200M voxels.
Result<SurfaceMesh> make_vessel_phantom(const PhantomOptions& options,
                                        PhantomTruth* truth = nullptr);

}  // namespace vm
