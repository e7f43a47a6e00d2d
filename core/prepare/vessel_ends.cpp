// Vessel ends of a closed surface: geodesic extremities tested for a tube
// behind them, and a cut across each (vessel_ends.h).
#include "core/prepare/vessel_ends.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "core/geom/vec3.h"
#include "core/mesh/adjacency.h"
#include "core/mesh/boundary_loops.h"
#include "core/mesh/edge_geodesics.h"
#include "core/mesh/level_loops.h"
#include "core/mesh/persistent_maxima.h"
#include "core/mesh/topology.h"
#include "core/util/portable_math.h"

namespace vm {
namespace {

Vec3 sub(const Vec3& a, const Vec3& b) { return a - b; }
/// y + s x.
Vec3 axpy(double s, const Vec3& x, const Vec3& y) { return y + s * x; }
/// Distance of p from the line through c along unit a.
double lateral(const Vec3& p, const Vec3& c, const Vec3& a) {
  const Vec3 d = sub(p, c);
  const double t = dot(d, a);
  return std::sqrt(std::max(0.0, dot(d, d) - t * t));
}

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::nth_element(v.begin(), v.begin() + long(v.size() / 2), v.end());
  return v[v.size() / 2];
}

/// Principal direction of points (3 doubles each, about their mean), by
/// power iteration on the scatter matrix from `guess`.
Vec3 principal_direction(const std::vector<Vec3>& pts, const Vec3& guess) {
  Vec3 mean{};
  for (const Vec3& p : pts)
    for (int k = 0; k < 3; ++k) mean[size_t(k)] += p[size_t(k)] / double(pts.size());
  double s[3][3] = {};
  for (const Vec3& p : pts) {
    const Vec3 d = sub(p, mean);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) s[i][j] += d[size_t(i)] * d[size_t(j)];
  }
  Vec3 v = normalized(guess);
  if (dot(v, v) == 0) v = {1, 0, 0};
  for (int it = 0; it < 50; ++it) {
    Vec3 w{};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) w[size_t(i)] += s[i][j] * v[size_t(j)];
    const Vec3 u = normalized(w);
    if (dot(u, u) == 0) break;
    v = u;
  }
  return dot(v, guess) < 0 ? Vec3{-v[0], -v[1], -v[2]} : v;
}

/// A plane section around an axis point.
struct Section {
  bool found = false;
  LevelLoop loop;
  CurveShape shape;
};

/// A geodesic ring around the tip.
struct Ring {
  double s = 0;
  Vec3 centroid{};
  double radius = 0;
};

/// A section on the march from the tip along the vessel.
struct Sample {
  double z = 0;     ///< depth from the tip along the march, in radii
  Vec3 point{};     ///< the plane's point (on the axis as marched)
  Vec3 dir{};       ///< the plane's normal: the axis there, toward the tip
  Section section;  ///< the loop around `point`, if any
};

/// Data shared by the analyses of all candidates.
struct Shared {
  const SurfaceMesh& mesh;
  const VesselEndOptions& options;
  TriangleAdjacency adj;
  VertexGraph graph;
  double longest_edge = 0;
  std::vector<uint8_t> touched_mark;  ///< scratch, per triangle, all 0 between analyses
  std::vector<double> plane_field;    ///< scratch, per vertex

  Vec3 point(int32_t v) const {
    const double* p = &mesh.points[3 * size_t(v)];
    return {p[0], p[1], p[2]};
  }
};

/// A short end is taken as a root when its radius is at least this
/// fraction of every other vessel end's and opening's.
constexpr double kRootWidth = 0.9;

/// What steps 3 and 4 ask of an end: of a vessel end (the options'), or of
/// a short one (step 6 of the header: a short root, whose tube behind the
/// cut is short but held to a tighter radius).
struct Bounds {
  double min_persistence = 1;  ///< of the tip, in radii
  double tube_length = 2.5;    ///< the tube from the cap's end reaches this deep (radii)
  double behind_cut = 1;       ///< ... and this far behind the cut (radii)
  double radius_tolerance = 0.35;
  /// The cap ends where full sections begin and go on for this many radii.
  double full_run = 1;
  /// Sections that step 3 needs to measure R (below: the first radius was
  /// far off).
  size_t min_sections = 6;
  bool short_end = false;

  static Bounds vessel_end(const VesselEndOptions& o) {
    return {o.min_persistence, o.tube_length, 1, o.radius_tolerance, 1, 6, false};
  }
  static Bounds short_end_bounds() { return {0.35, 1.5, 0.5, 0.1, 0.5, 3, true}; }
};

/// The analysis of one candidate tip (steps 2 to 5 of the header).
class EndAnalysis {
 public:
  EndAnalysis(Shared& sh, int32_t tip, double persistence, bool short_end)
      : sh_(sh),
        tip_(tip),
        persistence_(persistence),
        b_(short_end ? Bounds::short_end_bounds() : Bounds::vessel_end(sh.options)),
        geo_(sh.graph, std::span(&tip, 1)) {}
  ~EndAnalysis() {
    for (int32_t t : touched_) sh_.touched_mark[size_t(t)] = 0;
  }
  EndAnalysis(const EndAnalysis&) = delete;
  EndAnalysis& operator=(const EndAnalysis&) = delete;

  /// True with `end` filled for a vessel end; false with `why` otherwise.
  bool run(VesselEnd& end, NotAVesselEnd& why);
  /// Vertices that other candidates need not try: the end's cap and a
  /// margin, or the rejected extremity's surroundings.
  const std::vector<int32_t>& claimed() const { return claimed_; }
  double first_radius() const { return r0_; }

 private:
  void grow(double s);
  bool rings(std::vector<Ring>& out);
  /// The signed distances to the plane through q normal to a, for the
  /// vertices of the searched triangles.
  void set_plane(const Vec3& q, const Vec3& a);
  Section section(const Vec3& q, const Vec3& a);
  /// Sections every quarter radius from the tip inward to `deepest` radii:
  /// along the straight axis a0 up to `straight` radii in, then following
  /// the section centroids (the axis as the centroid of the last radius of
  /// sections), so that curved vessels are followed.
  std::vector<Sample> march(const Vec3& tip, const Vec3& a0, double R, double straight,
                            double deepest);
  /// The surface beyond a section loop (its "above" side), grown without
  /// crossing it; false if it leaves the searched region.
  bool beyond(const LevelLoop& loop, std::vector<int32_t>& vertices, double& area);

  Shared& sh_;
  int32_t tip_;
  double persistence_;
  Bounds b_;
  EdgeDijkstra geo_;
  size_t settled_seen_ = 0;
  std::vector<int32_t> touched_;
  std::vector<int32_t> claimed_;
  double r0_ = 0;
};

void EndAnalysis::grow(double s) {
  geo_.settle_until(s + sh_.longest_edge);
  const auto& settled = geo_.settled();
  for (; settled_seen_ < settled.size(); ++settled_seen_) {
    const int32_t v = settled[settled_seen_];
    for (int32_t i = sh_.adj.star_offsets[size_t(v)]; i < sh_.adj.star_offsets[size_t(v) + 1];
         ++i) {
      const int32_t t = sh_.adj.star[size_t(i)];
      if (!sh_.touched_mark[size_t(t)]) sh_.touched_mark[size_t(t)] = 1, touched_.push_back(t);
    }
  }
}

bool EndAnalysis::rings(std::vector<Ring>& out) {
  const VesselEndOptions& o = sh_.options;
  const VertexGraph& g = sh_.graph;
  double h = 0;
  const int32_t b = g.offsets[size_t(tip_)], e = g.offsets[size_t(tip_) + 1];
  for (int32_t i = b; i < e; ++i) h += g.lengths[size_t(i)] / double(e - b);
  const double reach = 1.6 + o.tube_length + std::max(o.clip_distance, 1.0) + 1.5;
  double s = 0, r_max = 0;
  for (int k = 0; k < 300; ++k) {
    s += std::max(0.5 * h, 0.12 * (out.empty() ? 0.0 : out.back().radius));
    grow(s);
    const std::vector<LevelLoop> loops =
        level_loops(sh_.mesh, sh_.adj, geo_.distances(), s, touched_);
    if (loops.empty()) break;
    size_t main = 0;
    std::vector<CurveShape> shapes;
    for (size_t i = 0; i < loops.size(); ++i) {
      shapes.push_back(curve_shape(loops[i].points));
      if (shapes[i].perimeter > shapes[main].perimeter) main = i;
    }
    if (!loops[main].closed) break;
    int significant = 0;
    for (size_t i = 0; i < loops.size(); ++i)
      significant += !loops[i].closed || shapes[i].perimeter >= 0.25 * shapes[main].perimeter;
    if (significant > 1) break;  // the rings split: a branching, or around a handle
    out.push_back({s, shapes[main].centroid, shapes[main].radius});
    r_max = std::max(r_max, shapes[main].radius);
    if (s > reach * r_max) break;
  }
  return out.size() >= 4;
}

void EndAnalysis::set_plane(const Vec3& q, const Vec3& a) {
  for (int32_t t : touched_)
    for (int k = 0; k < 3; ++k) {
      const int32_t v = sh_.mesh.triangles[3 * size_t(t) + size_t(k)];
      sh_.plane_field[size_t(v)] = dot(sub(sh_.point(v), q), a);
    }
}

Section EndAnalysis::section(const Vec3& q, const Vec3& a) {
  Section sec;
  set_plane(q, a);
  std::vector<LevelLoop> loops = level_loops(sh_.mesh, sh_.adj, sh_.plane_field, 0.0, touched_);
  double best = 1e300;
  for (LevelLoop& loop : loops) {
    if (!loop.closed || loop.size() < 3 || winding_number(loop.points, q, a) == 0) continue;
    const CurveShape shape = curve_shape(loop.points);
    if (shape.radius < best) {
      best = shape.radius;
      sec.found = true;
      sec.shape = shape;
      sec.loop = std::move(loop);
    }
  }
  return sec;
}

std::vector<Sample> EndAnalysis::march(const Vec3& tip, const Vec3& a0, double R, double straight,
                                       double deepest) {
  constexpr double kStep = 0.25;
  const double kTurn = 6 * std::numbers::pi / 180;
  std::vector<Sample> out;
  Vec3 dir = a0, last = tip;
  for (int i = 1; i * kStep <= deepest + 1e-9; ++i) {
    Sample s;
    s.z = i * kStep;
    s.point = s.z <= straight + 1e-9 ? axpy(-s.z * R, a0, tip) : axpy(-kStep * R, dir, last);
    s.dir = dir;
    s.section = section(s.point, dir);
    last = s.z > straight && s.section.found ? s.section.shape.centroid : s.point;
    const bool turn = s.z >= straight;
    out.push_back(std::move(s));
    // The axis: from the centroid one radius back to this one, turning by
    // at most kTurn a step (a bend of radius 2.4 R is followed; the corner
    // from an aneurysm's neck into its parent vessel is not).
    if (turn && out.size() > 4 && out.back().section.found && out[out.size() - 5].section.found) {
      const Vec3 d = normalized(
          sub(out[out.size() - 5].section.shape.centroid, out.back().section.shape.centroid));
      const double c = dot(d, dir);
      if (c >= pm::cos(kTurn)) {
        dir = d;
      } else if (dot(d, d) > 0) {
        const Vec3 across = normalized(axpy(-c, dir, d));
        dir = normalized(
            axpy(pm::sin(kTurn), across,
                 Vec3{pm::cos(kTurn) * dir[0], pm::cos(kTurn) * dir[1], pm::cos(kTurn) * dir[2]}));
      }
    }
  }
  return out;
}

bool EndAnalysis::beyond(const LevelLoop& loop, std::vector<int32_t>& vertices, double& area) {
  const SurfaceMesh& m = sh_.mesh;
  auto above = [&](int32_t v) { return sh_.plane_field[size_t(v)] > 0; };
  std::vector<int32_t> inside(loop.triangles.begin(), loop.triangles.end());
  std::sort(inside.begin(), inside.end());
  std::vector<int32_t> queue;
  auto visit = [&](int32_t t) {
    auto it = std::lower_bound(inside.begin(), inside.end(), t);
    if (it != inside.end() && *it == t) return;
    inside.insert(it, t);
    queue.push_back(t);
  };
  bool leak = false;
  for (int32_t t : loop.triangles)
    for (int k = 0; k < 3; ++k) {
      const int32_t h = 3 * t + k;
      const int32_t a = half_edge_from(m, h), b = half_edge_to(m, h);
      if (!above(a) || !above(b)) continue;
      const int32_t o = sh_.adj.opposite[size_t(h)];
      if (o < 0 || !sh_.touched_mark[size_t(o / 3)])
        leak = true;
      else
        visit(o / 3);
    }
  area = 0;
  for (size_t i = 0; i < queue.size() && !leak; ++i) {
    const int32_t t = queue[i];
    const int32_t* c = &m.triangles[3 * size_t(t)];
    double u[3], w[3], n[3];
    v3::sub(&m.points[3 * size_t(c[1])], &m.points[3 * size_t(c[0])], u);
    v3::sub(&m.points[3 * size_t(c[2])], &m.points[3 * size_t(c[0])], w);
    v3::cross(u, w, n);
    area += 0.5 * v3::norm(n);
    for (int k = 0; k < 3; ++k) {
      vertices.push_back(c[k]);
      const int32_t o = sh_.adj.opposite[3 * size_t(t) + size_t(k)];
      if (o < 0 || !sh_.touched_mark[size_t(o / 3)]) {
        leak = true;
        break;
      }
      visit(o / 3);
    }
  }
  std::sort(vertices.begin(), vertices.end());
  vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
  return !leak;
}

bool EndAnalysis::run(VesselEnd& end, NotAVesselEnd& why) {
  const VesselEndOptions& o = sh_.options;
  const double D = o.clip_distance;
  const Vec3 tip_point = sh_.point(tip_);
  why.where = tip_point;
  auto reject = [&](std::string reason) {
    why.why = std::move(reason);
    why.radius = r0_;
    // Its surroundings: the rings up to half a radius.
    for (int32_t v : geo_.settled())
      if (geo_.distances()[size_t(v)] <= 0.5 * r0_) claimed_.push_back(v);
    return false;
  };

  // Step 2: rings, their knee, a first radius and axis.
  std::vector<Ring> ring;
  if (!rings(ring)) return reject("too small to be a vessel");
  // The knee: the first ring past which the radius grows by less than 0.3
  // per unit of geodesic distance over the next half radius (about 1 over
  // a flat end, cos(s / R) over a rounded one, 0 along the vessel).
  auto radius_at = [&](double s) {
    for (size_t j = 1; j < ring.size(); ++j)
      if (ring[j].s >= s) {
        const double t = (s - ring[j - 1].s) / (ring[j].s - ring[j - 1].s);
        return ring[j - 1].radius + t * (ring[j].radius - ring[j - 1].radius);
      }
    return ring.back().radius;
  };
  size_t knee = ring.size() - 1;
  for (size_t k = 1; k < ring.size(); ++k) {
    const double ahead = 0.5 * ring[k].radius;
    if (radius_at(ring[k].s + ahead) - ring[k].radius < 0.3 * ahead) {
      knee = k;
      break;
    }
  }
  for (size_t j = knee; j < ring.size() && ring[j].s <= ring[knee].s + 0.5 * ring[knee].radius; ++j)
    r0_ = std::max(r0_, ring[j].radius);
  if (r0_ <= 0) r0_ = ring[knee].radius;
  std::vector<Vec3> centres;
  for (size_t k = knee; k < ring.size() && ring[k].s <= ring[knee].s + 2 * r0_; ++k)
    centres.push_back(ring[k].centroid);
  Vec3 a = normalized(sub(tip_point, centres.back()));
  if (centres.size() >= 3 && ring[knee + centres.size() - 1].s - ring[knee].s >= 0.75 * r0_)
    a = principal_direction(centres, a);
  Vec3 c0{};
  for (const Vec3& c : centres)
    for (int k = 0; k < 3; ++k) c0[size_t(k)] += c[size_t(k)] / double(centres.size());
  if (persistence_ < b_.min_persistence * r0_) return reject("a bump");

  // Step 3: sections perpendicular to the axis marched from the tip, every
  // quarter radius down to `deepest` radii in.
  double R = r0_;
  // Deep enough for a cap ending 3.5 radii in and the tube behind it.
  const double deepest = std::max({b_.tube_length + 2.5, D, 4.5}) + 1.5;
  grow(ring[knee].s + (deepest + 1 + std::numbers::pi) * 1.2 * R);
  // The tip: the farthest point near the candidate along the axis.
  double h = -1e300;
  for (int32_t v : geo_.settled())
    if (geo_.distances()[size_t(v)] <= ring[knee].s + R)
      h = std::max(h, dot(sub(sh_.point(v), c0), a));
  Vec3 tip = axpy(h, a, c0);
  auto roundness = [](const Section& s) {
    return s.found && s.shape.max_distance > 0 ? s.shape.min_distance / s.shape.max_distance : 0.0;
  };
  auto at = [](const std::vector<Sample>& m, double z) -> const Sample* {
    for (const Sample& s : m)
      if (std::abs(s.z - z) < 1e-6) return &s;
    return nullptr;
  };
  std::vector<Sample> samples;
  double z_cap = 1.5;
  std::vector<int32_t> cap;
  double cap_area = 0;
  for (int round = 0; round < 8; ++round) {
    samples = march(tip, a, R, z_cap + 0.5, deepest);
    // R: the median section from 1 radius in; for a short end, the widest
    // round section before the first that is not round from half a radius
    // in (the cap grows to the tube's radius, the branching ends it).
    std::vector<double> radii;
    double widest = 0;
    for (const Sample& s : samples) {
      if (!b_.short_end) {
        if (s.z >= 1 && s.section.found) radii.push_back(s.section.shape.radius);
        continue;
      }
      if (roundness(s.section) < 0.6) {
        if (s.z >= 0.5) break;
        continue;
      }
      widest = std::max(widest, s.section.shape.radius);
      if (s.z >= 0.75) radii.push_back(s.section.shape.radius);
    }
    // A first radius far off (from rings on a lopsided end): march again at
    // the scale of the sections (or a larger one if few sections were
    // found: all of them were on the end) before judging them.
    if (radii.size() < b_.min_sections) {
      if (round >= 3) return reject("no tube behind it");
      R *= 1.5;
      continue;
    }
    const double R_new = b_.short_end ? widest : median(radii);
    if (round < 3 && std::abs(R_new - R) > 0.1 * R) {
      R = R_new;
      continue;
    }
    // The cap ends where full round sections begin and go on for a radius
    // (at about 1 for a rounded end, 0.5 for a flat one, deeper for a flat
    // oblique one; half a radius for a short end).
    auto full = [&](double z) {
      const Sample* s = at(samples, z);
      return s && s->section.found &&
             std::abs(s->section.shape.radius / R_new - 1) <= std::min(0.15, b_.radius_tolerance) &&
             roundness(s->section) >= 0.6;
    };
    z_cap = -1;
    for (double z = 0.5; z <= 3.5 + 1e-9; z += 0.25)
      if (full(z) && full(z + 0.5) && (b_.full_run < 1 || full(z + 1))) {
        z_cap = z;
        break;
      }
    if (z_cap < 0) return reject("no tube behind it");
    // The axis at the end, from the sections just behind the cap.
    std::vector<Vec3> centres_near;
    for (const Sample& s : samples)
      if (s.section.found && s.z >= z_cap - 1e-9 &&
          s.z <= z_cap + (b_.short_end ? 0.5 : 1.5) + 1e-9)
        centres_near.push_back(s.section.shape.centroid);
    const Vec3 a_new = principal_direction(centres_near, a);
    // The tip: the farthest point beyond the cap's end along that axis.
    const Sample& ref = *at(samples, z_cap);
    set_plane(ref.point, ref.dir);
    cap.clear();
    if (!beyond(ref.section.loop, cap, cap_area))
      return reject("the part beyond " + number_text(z_cap, 3) + " radii in is not an end");
    const Vec3 c_ref = ref.section.shape.centroid;
    double h_new = z_cap * R_new;
    if (!cap.empty()) {
      h_new = -1e300;
      for (int32_t v : cap) h_new = std::max(h_new, dot(sub(sh_.point(v), c_ref), a_new));
    }
    const Vec3 tip_new = axpy(h_new, a_new, c_ref);
    const Vec3 moved = sub(tip_new, tip);
    const bool settled = dot(a_new, a) > pm::cos(std::numbers::pi / 180) &&
                         std::abs(R_new - R) < 0.02 * R && dot(moved, moved) < 0.0009 * R * R;
    a = a_new;
    R = R_new;
    tip = tip_new;
    if (settled) break;
  }
  samples = march(tip, a, R, z_cap + 0.5, deepest);

  // Step 5 (before the tests, which include the cut): the cut D radii in
  // along the march, or deeper where the section there is less round than
  // the tube behind it (it would cross a flat end cut obliquely).
  std::vector<double> tube_roundness;
  for (const Sample& s : samples)
    if (s.z >= z_cap && s.section.found) tube_roundness.push_back(roundness(s.section));
  const double round_enough = 0.92 * median(tube_roundness);
  // The section z radii in: between the march's samples, from the one
  // before along its axis.
  auto section_at = [&](double z) {
    const Sample* before = nullptr;
    for (const Sample& s : samples)
      if (s.z <= z + 1e-9) before = &s;
    Sample s;
    s.z = z;
    if (!before) {
      s.dir = a;
      s.point = axpy(-z * R, a, tip);
    } else {
      s.dir = before->dir;
      const Vec3 from = before->z > z_cap + 0.5 && before->section.found
                            ? before->section.shape.centroid
                            : before->point;
      s.point = axpy(-(z - before->z) * R, before->dir, from);
    }
    s.section = section(s.point, s.dir);
    return s;
  };
  double z_cut = D;
  Sample cut = section_at(z_cut);
  for (double z = D + 0.25; roundness(cut.section) < round_enough && z <= z_cap + 1 + 1e-9;
       z += 0.25) {
    Sample deeper = section_at(z);
    if (roundness(deeper.section) >= round_enough) z_cut = z, cut = std::move(deeper);
  }
  if (roundness(cut.section) < round_enough) z_cut = D, cut = section_at(D);
  if (!cut.section.found)
    return reject("no section around its axis " + number_text(z_cut, 3) + " radii in");
  // The cut's normal: the axis from the tube's sections at and behind it
  // (not in front of it, where an oblique or lopsided end would pull it
  // over), then the section again with that normal.
  std::vector<Vec3> behind_cut = {cut.section.shape.centroid};
  for (const Sample& s : samples)
    if (s.section.found && s.z > z_cut + 1e-9 &&
        s.z <= std::max(z_cut, z_cap) + (b_.short_end ? b_.behind_cut : 1.5) + 1e-9)
      behind_cut.push_back(s.section.shape.centroid);
  const Vec3 cut_axis = behind_cut.size() >= 3 ? principal_direction(behind_cut, cut.dir) : cut.dir;
  const Vec3 cut_point = cut.section.shape.centroid;
  const Section cut_section = section(cut_point, cut_axis);
  if (!cut_section.found) return reject("no section around its axis at the cut");

  // Step 4: the tests: a tube from the cap's end on (to tube_length radii
  // in at least) and behind the cut, a round cut, a cap beyond it.
  const double tube_end = std::max(b_.tube_length, z_cap + b_.tube_length - 1);
  for (const Sample& s : samples) {
    const bool in_tube = s.z >= z_cap - 1e-9 && s.z <= tube_end + 1e-9;
    const bool behind = s.z >= z_cut - 1e-9 && s.z <= z_cut + b_.behind_cut + 1e-9;
    if (!in_tube && !behind) continue;
    const std::string where = number_text(s.z, 3) + " radii in";
    if (!s.section.found) return reject("no section around its axis " + where);
    if (std::abs(s.section.shape.radius / R - 1) > b_.radius_tolerance)
      return reject("no tube of radius " + number_text(R, 3) + " behind it (radius " +
                    number_text(s.section.shape.radius, 3) + " " + where + ")");
    if (roundness(s.section) < o.min_roundness)
      return reject("the section " + where + " is not round");
    if (lateral(s.section.shape.centroid, s.point, s.dir) > o.max_offset * R)
      return reject("the section " + where + " is off the axis");
  }
  if (cut_section.shape.radius > (1 + b_.radius_tolerance) * R)
    return reject("wider than the tube behind it");
  if (roundness(cut_section) < o.min_roundness) return reject("the cut would not be round");
  set_plane(cut_point, cut_axis);
  cap.clear();
  if (!beyond(cut_section.loop, cap, cap_area))
    return reject("the part beyond a cut " + number_text(z_cut, 3) + " radii in is not an end");
  for (int32_t v : cap) {
    const Vec3 p = sh_.point(v);
    if (lateral(p, cut_point, cut_axis) > (2 + 0.25 * z_cut) * R ||
        dot(sub(p, cut_point), cut_axis) > (z_cut + 0.5) * R)
      return reject("the part beyond the cut is not a cap");
  }
  if (cap_area > 2 * (2 + 2 * z_cut) * std::numbers::pi * R * R)
    return reject("the part beyond the cut is too large for a cap");
  if (persistence_ < b_.min_persistence * R) return reject("a bump");

  end.axis = cut_axis;
  end.radius = R;
  end.tip = tip;
  end.plane = {cut_point, cut_axis};
  end.cut_radius = cut_section.shape.radius;
  end.cut_depth = z_cut;
  end.persistence = persistence_;
  end.short_end = b_.short_end;
  // Claimed: the cap and everything within 2 R of the axis down to R below
  // the cut.
  for (int32_t t : touched_)
    for (int k = 0; k < 3; ++k) {
      const int32_t v = sh_.mesh.triangles[3 * size_t(t) + size_t(k)];
      const Vec3 p = sh_.point(v);
      if (dot(sub(p, cut_point), cut_axis) >= -R && lateral(p, cut_point, cut_axis) <= 2 * R)
        claimed_.push_back(v);
    }
  claimed_.insert(claimed_.end(), cap.begin(), cap.end());
  return true;
}

}  // namespace

VesselEnds find_vessel_ends(const SurfaceMesh& mesh, const VesselEndOptions& options) {
  VesselEnds out;
  if (mesh.num_triangles() == 0) return out;
  Shared sh{mesh, options, build_adjacency(mesh), build_vertex_graph(mesh), 0, {}, {}};
  const size_t nv = mesh.num_vertices();
  sh.touched_mark.assign(mesh.num_triangles(), 0);
  sh.plane_field.assign(nv, 0);
  std::vector<double> lengths = sh.graph.lengths;
  for (double l : lengths) sh.longest_edge = std::max(sh.longest_edge, l);
  const double floor = 2 * median(lengths);

  // Components of the vertex graph, largest first; tiny ones are skipped.
  std::vector<int32_t> component(nv, -1);
  std::vector<std::pair<size_t, int32_t>> sizes;  // (size, a vertex)
  for (size_t v0 = 0; v0 < nv; ++v0) {
    if (component[v0] >= 0 || sh.graph.offsets[v0] == sh.graph.offsets[v0 + 1]) continue;
    const int32_t id = int32_t(sizes.size());
    std::vector<int32_t> stack = {int32_t(v0)};
    component[v0] = id;
    size_t count = 0;
    while (!stack.empty()) {
      const int32_t v = stack.back();
      stack.pop_back();
      ++count;
      for (int32_t i = sh.graph.offsets[size_t(v)]; i < sh.graph.offsets[size_t(v) + 1]; ++i) {
        const int32_t w = sh.graph.neighbors[size_t(i)];
        if (component[size_t(w)] < 0) component[size_t(w)] = id, stack.push_back(w);
      }
    }
    sizes.emplace_back(count, int32_t(v0));
  }
  std::sort(sizes.rbegin(), sizes.rend());

  // Step 1: candidates.
  std::vector<FieldMaximum> candidates;
  for (const auto& [count, v0] : sizes) {
    if (count < 32 || count * 100 < sizes[0].first) continue;
    auto farthest = [&](const EdgeDijkstra& d) {
      int32_t best = d.settled().front();
      for (int32_t v : d.settled())
        if (d.distances()[size_t(v)] > d.distances()[size_t(best)]) best = v;
      return best;
    };
    EdgeDijkstra from_any(sh.graph, std::span(&v0, 1));
    from_any.settle_all();
    const int32_t a = farthest(from_any);
    EdgeDijkstra from_a(sh.graph, std::span(&a, 1));
    from_a.settle_all();
    const int32_t b = farthest(from_a);
    EdgeDijkstra from_b(sh.graph, std::span(&b, 1));
    from_b.settle_all();
    for (const EdgeDijkstra* d : {&from_a, &from_b})
      for (const FieldMaximum& m : persistent_maxima(sh.graph, d->distances(), floor))
        candidates.push_back(m);
  }
  std::stable_sort(
      candidates.begin(), candidates.end(),
      [](const FieldMaximum& x, const FieldMaximum& y) { return x.persistence > y.persistence; });

  // Steps 2-5 per candidate, skipping those on an end found or a bulge
  // rejected; the short end's test (step 6) for those that are no vessel
  // end. `report`: rejected extremities are listed.
  std::vector<uint8_t> claimed(nv, 0);
  // Candidates that are no vessel end, with their first radius: maybe a
  // short root (step 6).
  std::vector<std::pair<FieldMaximum, double>> maybe_short;
  std::vector<int32_t> found_at;  // the candidate vertex of each end found
  // Whether an end cut within a radius of `end`'s cut was found already.
  auto found_already = [&](const VesselEnd& end) {
    return std::any_of(out.ends.begin(), out.ends.end(), [&](const VesselEnd& e) {
      const Vec3 d = sub(e.plane.point, end.plane.point);
      return std::sqrt(dot(d, d)) < std::max(e.radius, end.radius);
    });
  };
  // Extremities found to be no vessel end by the tests (not by
  // persistence): a second look from another vertex of theirs is not taken.
  std::vector<NotAVesselEnd> tested;
  auto examine = [&](const std::vector<FieldMaximum>& list, bool report) {
    for (const FieldMaximum& c : list) {
      if (claimed[size_t(c.vertex)]) continue;
      if (!report && std::any_of(tested.begin(), tested.end(), [&](const NotAVesselEnd& r) {
            const Vec3 d = sub(r.where, sh.point(c.vertex));
            return std::sqrt(dot(d, d)) < 2 * r.radius;
          }))
        continue;
      VesselEnd end;
      NotAVesselEnd why;
      bool found = false;
      double first_radius = 0;
      {
        EndAnalysis analysis(sh, c.vertex, c.persistence, false);
        found = analysis.run(end, why);
        first_radius = analysis.first_radius();
        for (int32_t v : analysis.claimed()) claimed[size_t(v)] = 1;
      }
      claimed[size_t(c.vertex)] = 1;
      if (!found && first_radius > 0 && why.why != "a bump" &&
          why.why != "too small to be a vessel")
        tested.push_back(why);
      if (!found && why.why != "too small to be a vessel" && first_radius > 0)
        maybe_short.push_back({c, first_radius});
      if (found) {
        if (!found_already(end)) out.ends.push_back(end), found_at.push_back(c.vertex);
      } else if (report && c.persistence >= 1.5 * first_radius && first_radius > 0) {
        bool again = false;
        for (const NotAVesselEnd& r : out.rejected) {
          const Vec3 d = sub(r.where, why.where);
          again |= std::sqrt(dot(d, d)) < 2 * std::max(r.radius, why.radius);
        }
        if (!again) out.rejected.push_back(why);
      }
    }
  };
  examine(candidates, true);
  // Step 1 again: the maxima of the distance from the ends found (an end
  // whose vessel is short and wide, which the far points' distance passes
  // into the branches beside it, is far from all of them).
  if (!found_at.empty()) {
    EdgeDijkstra from_ends(sh.graph, found_at);
    from_ends.settle_all();
    std::vector<FieldMaximum> more = persistent_maxima(sh.graph, from_ends.distances(), floor);
    examine(more, false);
  }
  // Step 6: the widest short end, if wider than every vessel end and
  // opening (a root: an aneurysm is narrower than its parent vessel),
  // tried from the widest candidates down (their first radius, from the
  // rings, is rough: 0.7 of the widest is tried).
  double widest = 0;
  for (const VesselEnd& e : out.ends) widest = std::max(widest, e.radius);
  for (const std::vector<int32_t>& loop : boundary_loops(mesh, sh.adj))
    widest = std::max(widest, describe_loop(mesh, loop).radius);
  std::stable_sort(maybe_short.begin(), maybe_short.end(),
                   [](const auto& x, const auto& y) { return x.second > y.second; });
  for (const auto& [c, first_radius] : maybe_short) {
    if (first_radius < 0.7 * widest) break;
    EndAnalysis analysis(sh, c.vertex, c.persistence, true);
    VesselEnd root;
    NotAVesselEnd why;
    if (!analysis.run(root, why) || root.radius < kRootWidth * widest) continue;
    if (!found_already(root)) out.ends.push_back(root);
    break;
  }
  std::stable_sort(out.ends.begin(), out.ends.end(),
                   [](const VesselEnd& x, const VesselEnd& y) { return x.radius > y.radius; });
  return out;
}

}  // namespace vm
