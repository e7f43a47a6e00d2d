// Edge-based volume refinement (Marot, Pellerin and Remacle 2019, section
// 4; front-like order after Frey, Borouchaki and George 1998); see
// refine_volume.h.
//
// Phases: (1) checks: sizes, options, the region closed by constrained
// faces; (2) the first layer: over each boundary face the apex of the
// regular tetrahedron of its size, in BRIO order, each candidate tested
// as below; (3) the queue: the first layer, then the region's vertices,
// each part along a Hilbert curve; (4) for each queued vertex v, its edges
// (v, w) in the current mesh: an edge of metric length >= split_length gets
// one candidate (the metric midpoint when shorter than kFarLength, else one
// unit of h from v). A candidate is rejected when it lies outside the
// region, closer than min_spacing * h to a vertex of v's star, of the
// tetrahedron containing it or of that tetrahedron's neighbors, closer
// than boundary_spacing * h to a constrained face of those tetrahedra, or
// closer than min_spacing * h to a vertex of its cavity (checked by the
// kernel before it changes anything); else it is inserted at once
// (constrained cavity) and queued. Metric lengths use h linear along the
// edge between its ends.
#include "core/volume/refine_volume.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "core/geom/closest_point.h"
#include "core/util/portable_math.h"
#include "core/volume/spatial_sort.h"
#include "core/volume/tet_topology.h"

namespace vm {
namespace {

// Edges at least this long (units of h) get a point one unit from their
// end instead of their midpoint.
constexpr double kFarLength = 2.5;

inline double dist2(const double* a, const double* b) {
  const double x = a[0] - b[0], y = a[1] - b[1], z = a[2] - b[2];
  return x * x + y * y + z * z;
}

// Metric length of a segment of length L with h linear from ha to hb.
inline double metric_length(double L, double ha, double hb) {
  const double d = hb - ha;
  if (std::fabs(d) <= 1e-9 * ha) return L / ha;
  return L * pm::log(hb / ha) / d;
}

}  // namespace

Status refine_volume(Delaunay3D& kernel, const VolumeSizeField& field,
                     std::vector<double>& vertex_h, const RefineOptions& options,
                     RefineStats* stats, const ProgressFn& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  RefineStats st;
  // Phase 1: checks.
  if (vertex_h.size() != kernel.num_vertices())
    return Status::Error("refine: one size per kernel vertex expected");
  for (double h : vertex_h)
    if (!(h > 0) || !std::isfinite(h)) return Status::Error("refine: sizes must be finite and > 0");
  if (!(options.split_length > 1) || !(options.min_spacing > 0) ||
      !(options.min_spacing < options.split_length) || !(options.boundary_spacing >= 0))
    return Status::Error(
        "refine: options need split_length > 1, 0 < min_spacing < split_length, "
        "boundary_spacing >= 0");
  const int32_t tag = options.region_tag;
  const int32_t cap = int32_t(kernel.tet_capacity());
  std::vector<uint8_t> in_region(kernel.num_vertices(), 0);
  for (int32_t t = 0; t < cap; ++t) {
    if (!kernel.is_live(t) || kernel.is_ghost(t) || kernel.tag(t) != tag) continue;
    for (int k = 0; k < 4; ++k) {
      in_region[size_t(kernel.tet(t)[k])] = 1;
      const int32_t u = kernel.neighbor(t, k) >> 2;
      if ((kernel.is_ghost(u) || kernel.tag(u) != tag) && !kernel.is_constrained(t, k))
        return Status::Error(
            "refine: the region is not closed by constrained faces (a face to the outside is "
            "not constrained)");
    }
  }

  // h at a candidate given an upper bound (see RefineOptions::size_tolerance).
  auto size_at = [&](const double* p, double ub) {
    ++st.size_evaluations;
    return field.eval(p, ub, options.size_tolerance);
  };

  // The test and insertion of a candidate p with exact size hp, located
  // from tetrahedron hint; r2 / b2: squared spacing to vertices / faces.
  // Returns the new vertex or -1.
  auto try_insert = [&](const double* p, double hp, double hspacing, int32_t hint) -> int32_t {
    const double r2 = options.min_spacing * options.min_spacing * hspacing * hspacing;
    const double b2 = options.boundary_spacing * options.boundary_spacing * hp * hp;
    const Delaunay3D::Location loc = kernel.locate(p, hint);
    if (kernel.is_ghost(loc.tet) || kernel.tag(loc.tet) != tag) {
      ++st.rejected_outside;
      return -1;
    }
    if (loc.type == Delaunay3D::LocationType::kOnVertex) {
      ++st.rejected_spacing;
      return -1;
    }
    // The tetrahedron containing p and its neighbors: their vertices and
    // constrained faces.
    bool close = false, near_boundary = false;
    auto check_tet = [&](int32_t t) {
      const int32_t* tv = kernel.tet(t);
      for (int k = 0; k < 4; ++k) {
        if (tv[k] != Delaunay3D::kInfinite) {
          if (dist2(p, kernel.point(tv[k])) < r2) close = true;
        }
        if (!kernel.is_constrained(t, k)) continue;
        const int* f = kFaceOut[k];
        if (tv[f[0]] < 0 || tv[f[1]] < 0 || tv[f[2]] < 0) continue;
        double q[3];
        if (closest_point_on_triangle(p, kernel.point(tv[f[0]]), kernel.point(tv[f[1]]),
                                      kernel.point(tv[f[2]]), q) < b2)
          near_boundary = true;
      }
    };
    check_tet(loc.tet);
    for (int k = 0; k < 4; ++k) {
      const int32_t u = kernel.neighbor(loc.tet, k) >> 2;
      if (!kernel.is_ghost(u)) check_tet(u);
    }
    if (close) {
      ++st.rejected_spacing;
      return -1;
    }
    if (near_boundary) {
      ++st.rejected_boundary;
      return -1;
    }
    // Last, every vertex p would be joined to (its cavity's: after flips
    // or clipped cavities the tetrahedra around p miss some neighbors).
    const Delaunay3D::InsertResult ins =
        kernel.insert(p, loc.tet, true, options.min_spacing * hspacing);
    if (ins.status == Delaunay3D::InsertStatus::kTooClose) {
      ++st.rejected_spacing;
      return -1;
    }
    if (ins.status != Delaunay3D::InsertStatus::kInserted) {
      ++st.rejected_kernel;
      return -1;
    }
    vertex_h.push_back(hp);
    ++st.inserted;
    return ins.vertex;
  };

  // Phase 2: the first layer: the apex of the regular tetrahedron on each
  // boundary face (height sqrt(2/3) h inward from its centroid), faces
  // along a Hilbert curve of their centroids.
  const double g = field.gradation();
  std::vector<int32_t> queue, generation(kernel.num_vertices(), 0);
  {
    // Boundary faces as vertex triples, counterclockwise seen from outside
    // the region (constrained faces are never removed, so the triples stay
    // valid while points are inserted).
    std::vector<int32_t> faces;
    std::vector<double> centroids;  // of the faces
    for (int32_t t = 0; t < cap; ++t) {
      if (!kernel.is_live(t) || kernel.is_ghost(t) || kernel.tag(t) != tag) continue;
      for (int k = 0; k < 4; ++k) {
        const int32_t u = kernel.neighbor(t, k) >> 2;
        if (!kernel.is_ghost(u) && kernel.tag(u) == tag) continue;
        for (int c = 0; c < 3; ++c) {
          double x = 0;
          for (int s : kFaceOut[k]) x += kernel.point(kernel.tet(t)[s])[c];
          centroids.push_back(x / 3);
          faces.push_back(kernel.tet(t)[kFaceOut[k][c]]);
        }
      }
    }
    const double height = std::sqrt(2.0 / 3.0);
    std::vector<double> apex, apex_h;
    std::vector<int32_t> apex_vertex;
    for (size_t i = 0; i < faces.size() / 3 && options.first_layer; ++i) {
      const int32_t a = faces[3 * i], b = faces[3 * i + 1], c = faces[3 * i + 2];
      const double *pa = kernel.point(a), *pb = kernel.point(b), *pc = kernel.point(c);
      double u[3], w[3];
      for (int j = 0; j < 3; ++j) u[j] = pb[j] - pa[j], w[j] = pc[j] - pa[j];
      // Outward normal.
      const double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2],
                           u[0] * w[1] - u[1] * w[0]};
      const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      if (!(len > 0)) continue;
      const double hf = (vertex_h[size_t(a)] + vertex_h[size_t(b)] + vertex_h[size_t(c)]) / 3;
      for (int j = 0; j < 3; ++j)
        apex.push_back(centroids[3 * i + size_t(j)] - height * hf * n[j] / len);
      apex_h.push_back(hf);
      apex_vertex.push_back(a);
    }
    // BRIO order: the first points are spread over the whole surface and
    // break the long tetrahedra of the boundary-only triangulation
    // everywhere at once; points inserted along a curve would keep
    // re-creating long tetrahedra to the far side (cavities 3x larger).
    const std::vector<int32_t> order = brio_hilbert_order(apex);
    for (size_t oi = 0; oi < order.size(); ++oi) {
      if ((oi & 4095) == 0 && !report_progress(progress, 0.0, "refine volume"))
        return Status::Cancelled();
      const size_t i = size_t(order[oi]);
      const double* p = &apex[3 * i];
      const double hf = apex_h[i];
      ++st.candidates;
      const double hp = size_at(p, hf + g * hf);
      const int32_t v = try_insert(p, hp, std::min(hp, hf), kernel.vertex_tet(apex_vertex[i]));
      if (v >= 0) {
        queue.push_back(v);
        generation.push_back(1);
      }
    }
    hilbert_sort(kernel.points(), queue.data(), int64_t(queue.size()));
  }
  st.first_layer = st.inserted;
  st.first_layer_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  // Phase 3: the queue: the first layer, then the region's vertices along a
  // Hilbert curve, then every new vertex.
  {
    const size_t first = queue.size();
    for (size_t v = 0; v < in_region.size(); ++v)
      if (in_region[v]) queue.push_back(int32_t(v));
    hilbert_sort(kernel.points(), queue.data() + first, int64_t(queue.size() - first));
  }

  // Phase 4: edges of each queued vertex.
  const double split = options.split_length;
  const double min_h = field.min_size();
  std::vector<int32_t> star, nbs, nb_tet;
  std::vector<uint32_t> seen(kernel.num_vertices(), 0);
  uint32_t stamp = 0;
  double last_fraction = 0;
  for (size_t qi = 0; qi < queue.size(); ++qi) {
    if ((qi & 1023) == 0) {
      last_fraction = std::max(last_fraction, double(qi) / double(queue.size() + 1));
      if (!report_progress(progress, last_fraction, "refine volume")) return Status::Cancelled();
    }
    if (st.inserted >= options.max_points) {
      st.hit_max_points = true;
      break;
    }
    const int32_t v = queue[qi];
    ++st.vertices_processed;
    kernel.tets_around_vertex(v, star);
    // Neighbors of v (each once, with a tetrahedron of the edge).
    if (++stamp == 0) std::fill(seen.begin(), seen.end(), 0), stamp = 1;
    seen.resize(kernel.num_vertices(), 0);
    nbs.clear();
    nb_tet.clear();
    for (int32_t t : star) {
      if (kernel.is_ghost(t) || kernel.tag(t) != tag) continue;
      for (int k = 0; k < 4; ++k) {
        const int32_t w = kernel.tet(t)[k];
        if (w == v || seen[size_t(w)] == stamp) continue;
        seen[size_t(w)] = stamp;
        nbs.push_back(w);
        nb_tet.push_back(t);
      }
    }
    const size_t n_nbs = nbs.size();
    // Copies: insertions reallocate the kernel's point array.
    const double xv[3] = {kernel.point(v)[0], kernel.point(v)[1], kernel.point(v)[2]};
    const double hv = vertex_h[size_t(v)];
    for (size_t i = 0; i < n_nbs; ++i) {
      const int32_t w = nbs[i];
      const double* xw = kernel.point(w);
      const double hw = vertex_h[size_t(w)];
      const double L = std::sqrt(dist2(xv, xw));
      const double ell = metric_length(L, hv, hw);
      if (ell < split) continue;
      // Distance d of the candidate from v along the edge.
      double d;
      if (ell < kFarLength) {
        const double dh = hw - hv;
        d = std::fabs(dh) <= 1e-9 * hv ? 0.5 * L : L * (std::sqrt(hv * hw) - hv) / dh;
      } else {
        const double gam = std::clamp((hw - hv) / L, -g, g);
        d = std::fabs(gam) < 1e-12 ? hv : hv * pm::expm1(gam) / gam;
      }
      const double s = d / L;
      const double p[3] = {xv[0] + s * (xw[0] - xv[0]), xv[1] + s * (xw[1] - xv[1]),
                           xv[2] + s * (xw[2] - xv[2])};
      ++st.candidates;
      // Cheap rejection first: h >= its Lipschitz lower bound from v and w,
      // against v's neighbors (and the points just inserted around v).
      const double lo = std::max({hv - g * d, hw - g * (L - d), min_h});
      const double lo2 = options.min_spacing * options.min_spacing * lo * lo;
      bool close = dist2(p, xv) < lo2;
      for (size_t j = 0; j < nbs.size() && !close; ++j)
        close = dist2(p, kernel.point(nbs[j])) < lo2;
      if (close) {
        ++st.rejected_spacing;
        continue;
      }
      // h is g-Lipschitz and vertex_h holds its values (or upper bounds of
      // them): every neighbor gives an upper bound.
      double ub = std::min(hv + g * d, hw + g * (L - d));
      for (size_t j = 0; j < nbs.size(); ++j) {
        const double hj = vertex_h[size_t(nbs[j])];
        if (hj < ub) ub = std::min(ub, hj + g * std::sqrt(dist2(p, kernel.point(nbs[j]))));
      }
      const double hp = size_at(p, ub);
      const double r2 = options.min_spacing * options.min_spacing * hp * hp;
      for (size_t j = 0; j < nbs.size() && !close; ++j) close = dist2(p, kernel.point(nbs[j])) < r2;
      if (close) {
        ++st.rejected_spacing;
        continue;
      }
      const int32_t nv = try_insert(p, hp, hp, nb_tet[i]);
      if (nv < 0) continue;
      queue.push_back(nv);
      generation.push_back(generation[size_t(v)] + 1);
      st.generations = std::max(st.generations, generation.back());
      nbs.push_back(nv);  // checked by the next candidates around v
    }
  }
  st.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (stats) *stats = st;
  return Status::Ok();
}

}  // namespace vm
