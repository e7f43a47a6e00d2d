// A mesh-independence family (Celik et al., J. Fluids Eng. 130, 2008): the
// members' options, their rows of the table, and the run over one prepared
// surface. See mesh_family.h.
#include "core/pipeline/mesh_family.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "core/pipeline/prepare_surface.h"
#include "core/pipeline/validate_options.h"
#include "core/prepare/units.h"
#include "core/util/json_writer.h"
#include "core/util/parallel.h"
#include "core/util/portable_math.h"

namespace vm {
namespace {

/// r^k by products (the same bits in every build).
double power(double r, int k) {
  double s = 1;
  for (int i = 0; i < k; ++i) s *= r;
  return s;
}

/// 1 + g + ... + g^(n-1).
double series(double g, int n) {
  double sum = 0, h = 1;
  for (int i = 0; i < n; ++i, h *= g) sum += h;
  return sum;
}

/// A boundary layer refined with the family: its first layer's height
/// divided by s exactly, in about s times as many layers (at most 100)
/// growing by the n-th root that keeps the first and last layers' height
/// ratio; the total thickness follows (within a few percent of the first
/// member's, as the count is rounded).
void refine_layers(LayerSpec& spec, double s) {
  if (spec.layers <= 0) return;
  const int n0 = spec.layers;
  const int n = std::clamp(int(std::lround(n0 * s)), n0, 100);
  const double g = spec.growth == 1 ? 1 : pm::pow(spec.growth, double(n0) / n);
  if (spec.first_height > 0)
    spec.first_height /= s;
  else  // the first layer is thickness / series(growth, n0) of R
    spec.thickness_fraction =
        std::min(0.9, spec.thickness_fraction / series(spec.growth, n0) / s * series(g, n));
  spec.growth = g;
  spec.layers = n;
}

/// Of a layer of `layers` with growth `g`, the first layer's share of the
/// total thickness.
double first_layer_share(int layers, double g) {
  const double sum = series(g, layers);
  return sum > 0 ? 1 / sum : 0;
}

/// `row`'s lengths times `f` (to the written mesh's unit).
void scale_lengths(FamilyMember& row, double f) {
  row.h *= f;
  row.lumen_volume *= f * f * f;
  row.first_layer_height *= f;
  row.layer_thickness *= f;
  row.size *= f;
}

/// The volume of the tetrahedron q (4 indices into `points`, xyz).
double tet_volume(const std::vector<double>& points, const int32_t* q) {
  auto p = [&](int i) { return &points[3 * size_t(q[i])]; };
  return std::abs(tet_volume6(p(0), p(1), p(2), p(3))) / 6;
}

/// The volume of the prism p (6 indices: bottom triangle, then top), as 3
/// tetrahedra.
double prism_volume(const std::vector<double>& points, const int32_t* p) {
  const int32_t a[4] = {p[0], p[1], p[2], p[3]}, b[4] = {p[1], p[2], p[3], p[4]},
                c[4] = {p[2], p[3], p[4], p[5]};
  return tet_volume(points, a) + tet_volume(points, b) + tet_volume(points, c);
}

/// "%.*g" of x.
std::string number(double x, int digits = 6) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.*g", digits, x);
  return buf;
}

}  // namespace

std::string_view family_layers_name(FamilyLayers layers) {
  return layers == FamilyLayers::kFixed ? "fixed" : "refine";
}

MeshJobOptions family_member_options(const MeshJobOptions& options, int k,
                                     double per_circumference) {
  MeshJobOptions m = options;
  m.family = 1;
  SizeOptions& so = m.remesh_options.size;
  if (per_circumference > 0 && so.mode == SizeMode::kPerCircumference)
    so.per_circumference = per_circumference;
  if (k == 0) return m;
  const double s = power(options.family_ratio, k);
  so.size /= s;
  so.per_circumference *= s;
  so.curvature_points *= s;
  so.size_min /= s;
  so.size_max /= s;
  so.gradation /= s;
  for (RefineSphere& sphere : so.spheres) sphere.size /= s;
  m.core_size /= s;
  m.gradation_divisor *= s;
  m.size_given = true;
  if (options.family_layers == FamilyLayers::kRefine) {
    refine_layers(m.viscous, s);
    refine_layers(m.vessel, s);
    m.yplus.yplus /= s;
  }
  return m;
}

FamilyMember family_member_row(const MeshJobResult& result, const MeshJobOptions& options, int k,
                               double previous_h) {
  FamilyMember row;
  row.index = k;
  row.scale = 1 / power(options.family_ratio, k);
  const VolumeMesh& v = result.volume;
  row.nodes = v.points.empty() ? result.output_surface.num_vertices() : v.num_vertices();
  row.tetrahedra = v.tets.size() / 4;
  row.prisms = v.prisms.size() / 6;
  row.triangles = v.triangles.size() / 3;
  row.quads = v.quads.size() / 4;
  row.wall_triangles = result.output_surface.num_triangles();
  row.cells = row.tetrahedra + row.prisms;
  row.lumen_volume = result.volume_stats.lumen_volume;
  // The whole volume meshed (lumen and vessel wall), for h, and the
  // viscous layer's: its tetrahedra (part 1) or, kept, its prisms (those
  // not in the vessel wall's region).
  double volume = 0, layer_volume = 0;
  for (size_t t = 0; t < row.tetrahedra; ++t) {
    const double vt = tet_volume(v.points, &v.tets[4 * t]);
    volume += vt;
    if (t < result.tet_part.size() && result.tet_part[t] == 1) layer_volume += vt;
  }
  for (size_t p = 0; p < row.prisms; ++p) {
    const double vp = prism_volume(v.points, &v.prisms[6 * p]);
    volume += vp;
    const size_t region = p < v.prism_region.size() ? size_t(v.prism_region[p]) : 0;
    if (region >= result.region_names.size() || result.region_names[region] != "vessel_wall")
      layer_volume += vp;
  }
  row.h = row.cells > 0 ? pm::cbrt(volume / double(row.cells)) : 0;
  row.ratio = previous_h > 0 && row.h > 0 ? previous_h / row.h : 0;
  row.quality = result.tet_quality_stats;
  row.core_quality = result.core_quality_stats;
  row.wall_quality_min = result.output_quality_stats.min;
  row.wall_quality_mean = result.output_quality_stats.mean;
  const VolumeStats& vs = result.volume_stats;
  row.layers = vs.viscous_layers;
  if (row.layers > 0 && vs.boundary_layer.wall_area > 0) {
    row.layer_thickness = layer_volume / vs.boundary_layer.wall_area;
    row.first_layer_height =
        row.layer_thickness * first_layer_share(row.layers, options.viscous.growth);
  }
  const SizeOptions& so = options.remesh_options.size;
  if (so.mode == SizeMode::kUniform)
    row.size = so.size;
  else
    row.per_circumference = so.per_circumference;
  row.seconds = result.seconds_total;
  return row;
}

std::string family_csv(const MeshFamily& family) {
  std::string out =
      "member,file,scale,nodes,tetrahedra,prisms,cells,lumen_volume,h,ratio,gamma_t_min,"
      "gamma_t_mean,core_gamma_t_min,core_gamma_t_mean,wall_gamma_k_min,wall_gamma_k_mean,"
      "layers,first_layer_height,layer_thickness,seconds\n";
  for (const FamilyMember& m : family.rows) {
    const std::string fields[] = {std::to_string(m.index),
                                  m.file,
                                  number(m.scale),
                                  std::to_string(m.nodes),
                                  std::to_string(m.tetrahedra),
                                  std::to_string(m.prisms),
                                  std::to_string(m.cells),
                                  number(m.lumen_volume, 8),
                                  number(m.h),
                                  number(m.ratio, 4),
                                  number(m.quality.min, 4),
                                  number(m.quality.mean, 4),
                                  number(m.core_quality.min, 4),
                                  number(m.core_quality.mean, 4),
                                  number(m.wall_quality_min, 4),
                                  number(m.wall_quality_mean, 4),
                                  std::to_string(m.layers),
                                  number(m.first_layer_height, 4),
                                  number(m.layer_thickness, 4),
                                  number(m.seconds, 3)};
    for (size_t i = 0; i < std::size(fields); ++i) {
      if (i > 0) out += ',';
      out += fields[i];
    }
    out += '\n';
  }
  return out;
}

std::string family_json(const MeshFamily& family) {
  JsonWriter j;
  j.begin_object();
  j.key("members").value(family.members);
  j.key("ratio").value(family.ratio);
  j.key("layers").value(family_layers_name(family.layers));
  j.key("unit").value(family.unit);
  j.key("rows").begin_array();
  for (const FamilyMember& m : family.rows) {
    j.begin_object();
    j.key("member").value(m.index);
    j.key("file").value(m.file);
    j.key("scale").value(m.scale);
    j.key("nodes").value(m.nodes);
    j.key("tetrahedra").value(m.tetrahedra);
    j.key("prisms").value(m.prisms);
    j.key("triangles").value(m.triangles);
    j.key("quads").value(m.quads);
    j.key("wall_triangles").value(m.wall_triangles);
    j.key("cells").value(m.cells);
    j.key("lumen_volume").value(m.lumen_volume);
    j.key("h").value(m.h);
    j.key("ratio").value(m.ratio);
    j.key("gamma_t_min").value(m.quality.min);
    j.key("gamma_t_mean").value(m.quality.mean);
    j.key("core_gamma_t_min").value(m.core_quality.min);
    j.key("core_gamma_t_mean").value(m.core_quality.mean);
    j.key("wall_gamma_k_min").value(m.wall_quality_min);
    j.key("wall_gamma_k_mean").value(m.wall_quality_mean);
    j.key("layers").value(m.layers);
    j.key("first_layer_height").value(m.first_layer_height);
    j.key("layer_thickness").value(m.layer_thickness);
    if (m.per_circumference > 0)
      j.key("per_circumference").value(m.per_circumference);
    else
      j.key("size").value(m.size);
    j.key("seconds").value(m.seconds);
    j.end_object();
  }
  j.end_array();
  j.end_object();
  return j.str();
}

Result<MeshFamily> run_mesh_family(std::span<const uint8_t> file_bytes,
                                   const MeshJobOptions& options, const FamilyMemberFn& on_member,
                                   const ProgressFn& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  const int n = std::max(1, options.family);
  if (Status st = validate_options(options, options.format); !st.ok()) return st;
  MeshFamily family;
  family.members = n;
  family.ratio = options.family_ratio;
  family.layers = options.family_layers;
  // The members' shares of the progress bar, by their expected work (r^3k).
  std::vector<double> share(size_t(n) + 1, 0);
  for (int k = 0; k < n; ++k)
    share[size_t(k) + 1] = share[size_t(k)] + power(options.family_ratio, 3 * k);
  auto member_progress = [&](int k) -> ProgressFn {
    const double from = share[size_t(k)] / share.back(), to = share[size_t(k) + 1] / share.back();
    return [&progress, from, to, k, n](double f, std::string_view stage) {
      const std::string label = "member " + std::to_string(k + 1) + " of " + std::to_string(n) +
                                ": " + std::string(stage);
      return report_progress(progress, from + (to - from) * f, label);
    };
  };
  // One preparation for every member.
  set_thread_count(options.threads);
  ProgressFn first = member_progress(0);
  ProgressFn prepare_progress = [&](double f, std::string_view stage) {
    return first(0.2 * f, stage);
  };
  Result<PreparedSurface> prepared = prepare_surface(file_bytes, options.prepare, prepare_progress);
  if (!prepared.ok()) return prepared.status();
  const double seconds_prepare =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  PreparedSurface surface = std::move(prepared).value();
  double per_circumference = 0, previous_h = 0;
  for (int k = 0; k < n; ++k) {
    const MeshJobOptions member = family_member_options(options, k, per_circumference);
    ProgressFn p = member_progress(k);
    auto r = run_mesh_job_on(surface, member, p);
    if (!r.ok()) {
      const Status& st = r.status();
      if (k == 0 || st.cancelled()) return st;
      // Said as the member's: an option refused is that member's value.
      return Status::Error("family member " + std::to_string(k + 1) + " of " + std::to_string(n) +
                           " (sizes / " + number(power(options.family_ratio, k), 3) + "): " +
                           (st.option().empty() ? "" : "{" + st.option() + "} ") + st.message());
    }
    MeshJobResult& res = r.value();
    if (k == 0) {
      res.seconds_total += seconds_prepare;
      // The first member's size as used (the default, maybe coarsened to
      // the budget), which the others refine.
      if (res.budget.coarsened) per_circumference = res.budget.per_circumference;
      family.unit = std::string(unit_symbol(options.output_units != LengthUnit::kGuess
                                                ? options.output_units
                                                : res.surface.unit.unit));
    }
    FamilyMember row = family_member_row(res, member, k, previous_h);
    previous_h = row.h;
    if (options.output_units != LengthUnit::kGuess)
      scale_lengths(row, metres_per_unit(res.surface.unit.unit) /
                             metres_per_unit(options.output_units));
    family.rows.push_back(std::move(row));
    surface = res.surface;  // with any opening cut deeper
    if (on_member)
      if (Status st = on_member(k, member, res); !st.ok()) return st;
  }
  return family;
}

}  // namespace vm
