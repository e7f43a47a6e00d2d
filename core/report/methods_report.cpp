// The methods report (methods_report.h): one self-contained, accessible HTML
// page and a ready-to-paste paragraph describing a mesh from its job's
// result and options. Plain string building, no template engine; every
// text from the result or the user is escaped. Our own design; the family's
// wording follows Celik et al. (J. Fluids Eng. 130, 2008).

#include "core/report/methods_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <string_view>
#include <vector>

#include "core/pipeline/option_table.h"

namespace vm {
namespace {

constexpr const char* kMethodCitation = "Marchandise et al. 2012";
// The quality measures' symbols as HTML.
constexpr const char* kGammaK = "\u03b3<sub>K</sub>";
constexpr const char* kGammaT = "\u03b3<sub>t</sub>";

// ---- Text helpers -----------------------------------------------------------

// `text` escaped for HTML element content and quoted attribute values.
std::string esc(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (char ch : text) {
    switch (ch) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out.push_back(ch);
    }
  }
  return out;
}

// RFC 4648 base64 with '=' padding.
std::string base64(std::string_view bytes) {
  static constexpr char kAlphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  size_t i = 0;
  for (; i + 3 <= bytes.size(); i += 3) {
    const uint32_t v = uint32_t(uint8_t(bytes[i])) << 16 | uint32_t(uint8_t(bytes[i + 1])) << 8 |
                       uint32_t(uint8_t(bytes[i + 2]));
    for (int k = 3; k >= 0; --k) out.push_back(kAlphabet[(v >> (6 * k)) & 63]);
  }
  if (i < bytes.size()) {
    uint32_t v = uint32_t(uint8_t(bytes[i])) << 16;
    if (i + 1 < bytes.size()) v |= uint32_t(uint8_t(bytes[i + 1])) << 8;
    out.push_back(kAlphabet[(v >> 18) & 63]);
    out.push_back(kAlphabet[(v >> 12) & 63]);
    out.push_back(i + 1 < bytes.size() ? kAlphabet[(v >> 6) & 63] : '=');
    out.push_back('=');
  }
  return out;
}

std::string num(double x, int digits = 4) { return report_number(x, digits); }
std::string cnt(size_t n) { return report_count(n); }
std::string plural(size_t n, const char* one, const char* many) {
  return cnt(n) + " " + (n == 1 ? one : many);
}

// "a, b and c".
std::string join_and(const std::vector<std::string>& parts) {
  std::string out;
  for (size_t i = 0; i < parts.size(); ++i) {
    if (i > 0) out += i + 1 == parts.size() ? " and " : ", ";
    out += parts[i];
  }
  return out;
}

// ---- What the options were --------------------------------------------------

std::string param_phrase(ParamMethod m) {
  switch (m) {
    case ParamMethod::kHarmonic:
      return "harmonic parameterization onto the disk";
    case ParamMethod::kFloater:
      return "mean-value (Floater) parameterization";
    default:
      return "finite-element least-squares conformal parameterization";
  }
}

std::string mesher_phrase(Mesher2D m) {
  switch (m) {
    case Mesher2D::kDelaunay:
      return "Delaunay refinement";
    case Mesher2D::kAdapt:
      return "planar mesh adaptation";
    default:
      return "frontal-Delaunay meshing";
  }
}

// The edges per circumference N used (after the element budget).
double per_circumference_used(const MeshJobResult& r, const MeshJobOptions& o) {
  return r.budget.coarsened && r.budget.per_circumference > 0
             ? r.budget.per_circumference
             : o.remesh_options.size.per_circumference;
}

bool uniform_size(const MeshJobOptions& o) {
  return o.remesh_options.size.mode == SizeMode::kUniform;
}

// "a target edge length of 2 pi R/20 (R the local vessel radius)" or "a
// uniform target edge length of 0.2 mm".
std::string size_phrase(const MeshJobResult& r, const MeshJobOptions& o, const std::string& unit) {
  if (uniform_size(o))
    return "a uniform target edge length of " + num(o.remesh_options.size.size) + " " + unit;
  return "a target edge length of 2\u03c0R/" + num(per_circumference_used(r, o)) +
         " (R the local vessel radius)";
}

// The first layer's height when set (from a target y+ or given), else 0.
double first_height(const MeshJobResult& r, const MeshJobOptions& o) {
  if (r.first_layer_yplus) return r.first_layer_yplus->height;
  return o.viscous.first_height;
}

// "total thickness 0.2 R, growth 1.2" or "first-layer height 0.01 mm, ...".
std::string layer_phrase(const MeshJobResult& r, const MeshJobOptions& o, const LayerSpec& spec,
                         bool viscous, const std::string& unit) {
  std::string s;
  const double first = viscous ? first_height(r, o) : spec.first_height;
  if (first > 0) {
    s = "first-layer height " + num(first) + " " + unit;
    if (viscous && r.first_layer_yplus)
      s += " from a target y+ of " + num(r.first_layer_yplus->target.yplus);
  } else {
    s = "total thickness " + num(spec.thickness_fraction) + " R";
  }
  return s + ", growth ratio " + num(spec.growth);
}

std::string unit_of(const MeshJobResult& r) {
  return std::string(unit_symbol(r.surface.unit.unit));
}

size_t node_count(const MeshJobResult& r) {
  return r.volume.num_vertices() > 0 ? r.volume.num_vertices() : r.output_surface.num_vertices();
}

bool has_volume(const MeshJobResult& r) {
  return r.volume.num_tets() > 0 || r.volume.num_prisms() > 0;
}

// ---- HTML pieces ------------------------------------------------------------

const char* const kStyle =
    "body{margin:0;background:#fff;color:#1f2328;line-height:1.5;"
    "font-family:system-ui,-apple-system,\"Segoe UI\",Roboto,Helvetica,Arial,sans-serif}"
    "main{max-width:60rem;margin:0 auto;padding:1.5rem}"
    "h1{font-size:1.9rem;margin:0 0 .25rem}"
    "h2{font-size:1.3rem;margin:2rem 0 .5rem;border-bottom:1px solid #d0d7de;"
    "padding-bottom:.2rem}"
    ".sub{color:#57606a;margin-top:0}"
    ".paste{background:#f6f8fa;border-left:4px solid #0969da;padding:.75rem 1rem}"
    "table{border-collapse:collapse;margin:.5rem 0 1.25rem;font-size:.95rem}"
    "caption{text-align:left;font-weight:600;padding:.25rem 0}"
    "th,td{border:1px solid #d0d7de;padding:.25rem .6rem;text-align:left;vertical-align:top}"
    "th{background:#f6f8fa}"
    "td.n{text-align:right;font-variant-numeric:tabular-nums;white-space:nowrap}"
    "figure{margin:1rem 0}"
    "img{max-width:100%;height:auto;border:1px solid #d0d7de}"
    "figcaption{color:#57606a;font-size:.95rem}"
    "svg{max-width:100%;height:auto}"
    "code{font-family:ui-monospace,SFMono-Regular,Menlo,Consolas,monospace;font-size:.9rem;"
    "background:#f6f8fa;padding:.1rem .3rem;white-space:pre-wrap;overflow-wrap:anywhere}";

// A table: caption (text), header cells and rows of cells (HTML); cells
// flagged numeric are right-aligned.
struct Table {
  std::string caption;
  std::vector<std::string> head;
  std::vector<bool> numeric;
  std::vector<std::vector<std::string>> rows;
};

std::string table_html(const Table& t) {
  std::string s = "<table>\n<caption>" + esc(t.caption) + "</caption>\n<thead><tr>";
  for (const std::string& h : t.head) s += "<th scope=\"col\">" + h + "</th>";
  s += "</tr></thead>\n<tbody>\n";
  for (const auto& row : t.rows) {
    s += "<tr>";
    for (size_t i = 0; i < row.size(); ++i)
      s += (i < t.numeric.size() && t.numeric[i] ? "<td class=\"n\">" : "<td>") + row[i] + "</td>";
    s += "</tr>\n";
  }
  return s + "</tbody>\n</table>\n";
}

// An inline SVG histogram of `q` (equal bins over [0, 1]).
std::string histogram_svg(const QualityStats& q, const std::string& id, const std::string& what,
                          const std::string& measure) {
  const std::string label = "Histogram of " + measure + " over " + cnt(q.count) + " " + what +
                            ": minimum " + num(q.min, 3) + ", mean " + num(q.mean, 3) +
                            ", maximum " + num(q.max, 3);
  std::string s = "<svg role=\"img\" aria-labelledby=\"" + id +
                  "\" viewBox=\"0 0 520 210\" width=\"520\" height=\"210\">";
  s += "<title id=\"" + id + "\">" + esc(label) + "</title>";
  const double x0 = 60, x1 = 505, y0 = 14, y1 = 170;
  size_t peak = 0;
  for (size_t c : q.histogram) peak = std::max(peak, c);
  s += "<rect x=\"" + num(x0) + "\" y=\"" + num(y0) + "\" width=\"" + num(x1 - x0) +
       "\" height=\"" + num(y1 - y0) + "\" fill=\"#f6f8fa\" stroke=\"#8c959f\"/>";
  const size_t bins = q.histogram.size();
  for (size_t i = 0; i < bins && peak > 0; ++i) {
    if (q.histogram[i] == 0) continue;
    const double bw = (x1 - x0) / double(bins);
    double h = (y1 - y0) * double(q.histogram[i]) / double(peak);
    h = std::max(h, 1.5);  // a bin with anything in it stays visible
    char buf[160];
    std::snprintf(buf, sizeof buf,
                  "<rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" fill=\"#0969da\"/>",
                  x0 + bw * double(i) + 0.5, y1 - h, bw - 1, h);
    s += buf;
  }
  s += "<g aria-hidden=\"true\">";  // the labels: the title says it all
  for (int k = 0; k <= 4; ++k) {
    const double x = x0 + (x1 - x0) * k / 4;
    s += "<text x=\"" + num(x) +
         "\" y=\"188\" text-anchor=\"middle\" font-size=\"13\" "
         "fill=\"#1f2328\">" +
         num(k / 4.0) + "</text>";
  }
  s += "<text x=\"" + num(0.5 * (x0 + x1)) +
       "\" y=\"204\" text-anchor=\"middle\" font-size=\"13\" fill=\"#1f2328\">\u03b3<tspan "
       "font-size=\"10\" dy=\"3\">" +
       esc(measure.substr(measure.size() - 1)) + "</tspan></text>";
  s += "<text x=\"" + num(x0 - 6) + "\" y=\"" + num(y0 + 10) +
       "\" text-anchor=\"end\" font-size=\"13\" fill=\"#1f2328\">" + cnt(peak) + "</text>";
  s += "<text x=\"" + num(x0 - 6) + "\" y=\"" + num(y1) +
       "\" text-anchor=\"end\" font-size=\"13\" fill=\"#1f2328\">0</text>";
  return s + "</g></svg>";
}

// A row of the quality table; `name` is HTML.
std::string stats_row(const std::string& name, const QualityStats& q) {
  return "<tr><td>" + name + "</td><td class=\"n\">" + cnt(q.count) + "</td><td class=\"n\">" +
         (q.count ? num(q.min, 3) : "-") + "</td><td class=\"n\">" +
         (q.count ? num(q.mean, 3) : "-") + "</td></tr>\n";
}

std::string point_html(const std::array<double, 3>& p) {
  std::string s = "(";  // built by appends: GCC 12 warns falsely on "(" + string&&
  s += num(p[0]);
  s += ", ";
  s += num(p[1]);
  s += ", ";
  s += num(p[2]);
  return s + ")";
}

std::string opening_source_text(const OpeningSource& src) {
  std::string s = opening_source_name(src.kind);
  const std::string shape = opening_shape_name(src.shape);
  if (!shape.empty()) s += " (" + shape + ")";
  if (!src.name.empty()) s += ", " + src.name;
  return s;
}

// The input's repairs and cuts, one sentence each (plain text).
std::vector<std::string> repairs_done(const PreparedSurface& p, const std::string& unit) {
  std::vector<std::string> out;
  auto add = [&](size_t n, const char* one, const char* many, const std::string& tail) {
    if (n > 0) out.push_back(plural(n, one, many) + " " + tail);
  };
  add(p.weld.merged_by_tolerance, "vertex", "vertices", "merged within the weld tolerance");
  add(p.repair.degenerate_removed, "degenerate triangle", "degenerate triangles", "removed");
  add(p.repair.collinear_repaired, "flat triangle", "flat triangles", "repaired");
  add(p.repair.duplicates_removed, "duplicate triangle", "duplicate triangles", "removed");
  add(p.repair.flipped, "triangle", "triangles", "re-oriented consistently outward");
  add(p.manifold.fins_removed, "fin", "fins", "removed from non-manifold edges");
  add(p.manifold.edges_split, "non-manifold edge", "non-manifold edges",
      "split into manifold sheets");
  add(p.manifold.vertices_split, "non-manifold vertex", "non-manifold vertices", "split");
  add(p.manifold.twisted_removed, "twisted triangle", "twisted triangles", "removed");
  if (p.resurfaced.resolved() > 0)
    out.push_back(plural(p.resurfaced.resolved(), "place", "places") +
                  " where the surface crossed itself re-surfaced");
  size_t trimmed = 0;
  for (const TrimmedEnd& e : p.trimmed_ends) trimmed += e.trimmed ? 1 : 0;
  add(trimmed, "damaged vessel end", "damaged vessel ends",
      "trimmed back to a clean cross-section");
  size_t closed = 0, added = 0;
  for (const Hole& h : p.holes) closed += h.closed ? 1 : 0, added += h.triangles_added;
  if (closed > 0)
    out.push_back(plural(closed, "hole", "holes") + " closed (" + cnt(added) + " triangles added)");
  add(p.specks_removed, "separate small piece", "separate small pieces", "removed");
  if (p.smoothing.applied)
    out.push_back("smoothed (" + std::to_string(p.smoothing.report.passes) +
                  " passes, vertices moved by at most " +
                  num(p.smoothing.report.max_displacement, 3) + " " + unit + ")");
  add(p.caps_removed, "cap", "caps", "recognised and removed (their rims became openings)");
  for (const ClipCut& c : p.clips)
    out.push_back("cut across the vessel at " + point_html(c.centroid) + " " + unit +
                  " (opening radius " + num(c.radius, 3) + " " + unit + ", " +
                  cnt(c.triangles_removed) + " triangles removed)");
  for (size_t i = 0; i < p.opening_sources.size(); ++i)
    if (p.opening_sources[i].extension > 0)
      out.push_back("flow extension of " + num(p.opening_sources[i].extension, 3) + " " + unit +
                    " added at opening " + std::to_string(i));
  return out;
}

}  // namespace

std::string report_count(size_t n) {
  const std::string digits = std::to_string(n);
  std::string out;
  for (size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out.push_back(',');
    out.push_back(digits[i]);
  }
  return out;
}

std::string report_number(double x, int digits) {
  if (!std::isfinite(x)) return "-";
  digits = std::clamp(digits, 1, 17);
  const double ax = std::abs(x);
  if (ax >= std::pow(10.0, digits) && ax < 1e15)
    return (x < 0 ? "-" : "") + report_count(size_t(std::llround(ax)));
  char buf[48];
  if (ax != 0 && ax < 1e-4) {
    std::snprintf(buf, sizeof buf, "%.*g", digits, x);
    return buf;
  }
  // Fixed notation with `digits` significant digits, trailing zeros dropped.
  const int magnitude = ax == 0 ? 0 : int(std::floor(std::log10(ax)));
  const int decimals = std::max(0, digits - 1 - magnitude);
  std::snprintf(buf, sizeof buf, "%.*f", decimals, x);
  std::string s = buf;
  if (s.find('.') != std::string::npos) {
    while (s.back() == '0') s.pop_back();
    if (s.back() == '.') s.pop_back();
  }
  if (s == "-0") s = "0";
  return s;
}

std::string methods_paragraph(const MethodsReportInput& in) {
  const MeshJobResult& r = *in.result;
  const MeshJobOptions& o = *in.options;
  const std::string unit = unit_of(r);
  const std::string version = in.version.empty() ? "" : " " + in.version;
  std::string s = "The lumen surface (";
  if (!in.input_name.empty()) s += in.input_name + ", ";
  s += cnt(r.surface.input_triangles) + " triangles, " + unit + ")";
  const QualityStats& wq = r.output_quality_stats;
  if (r.remeshed) {
    const SizeOptions& so = o.remesh_options.size;
    s += " was remeshed with vesselmesh" + version + " using " +
         param_phrase(o.remesh_options.param) + " and " +
         mesher_phrase(o.remesh_options.patch.mesher) + " (" + kMethodCitation + ") with " +
         size_phrase(r, o, unit);
    std::vector<std::string> more;
    if (so.gradation > 0) more.push_back("a size gradation of " + num(so.gradation));
    if (so.size_min > 0 || std::isfinite(so.size_max)) {
      std::string clamp = "sizes clamped to";
      if (so.size_min > 0) clamp += " at least " + num(so.size_min) + " " + unit;
      if (so.size_min > 0 && std::isfinite(so.size_max)) clamp += " and";
      if (std::isfinite(so.size_max)) clamp += " at most " + num(so.size_max) + " " + unit;
      more.push_back(clamp);
    }
    if (!so.spheres.empty()) {
      std::string sp = plural(so.spheres.size(), "refinement sphere", "refinement spheres") +
                       " (size " + num(so.spheres[0].size) + " " + unit;
      if (so.spheres.size() > 1) sp += " in the first";
      more.push_back(sp + ")");
    }
    if (!more.empty()) s += ", " + join_and(more);
    s += ". The wall had " + cnt(r.output_surface.num_triangles()) +
         " triangles (minimum and mean triangle quality \u03b3K " + num(wq.min, 3) + " and " +
         num(wq.mean, 3) + ").";
  } else {
    s += " was meshed as given, without remeshing, by vesselmesh" + version + " (" +
         cnt(r.output_surface.num_triangles()) + " wall triangles, minimum and mean triangle " +
         "quality \u03b3K " + num(wq.min, 3) + " and " + num(wq.mean, 3) + ").";
  }
  if (has_volume(r)) {
    const int layers = r.volume_stats.viscous_layers;
    if (layers > 0) {
      s += " A boundary layer of " + std::to_string(layers) + " prismatic layer" +
           (layers == 1 ? "" : "s") + " (" + layer_phrase(r, o, o.viscous, true, unit) +
           ") was grown inward from the wall" +
           (o.keep_prisms ? " and kept as prisms." : " and split into tetrahedra.");
    }
    if (r.volume_stats.wall_layers > 0)
      s += " A vessel wall of " + std::to_string(r.volume_stats.wall_layers) + " layer" +
           (r.volume_stats.wall_layers == 1 ? "" : "s") + " (" +
           layer_phrase(r, o, o.vessel, false, unit) + ") was grown outward.";
    s += std::string(" The ") + (layers > 0 ? "rest of the lumen" : "lumen") +
         ", closed by planar caps, was filled with tetrahedra by constrained Delaunay "
         "tetrahedralization with refinement and optimization";
    if (o.core_size > 0) s += " (core edge length " + num(o.core_size) + " " + unit + ")";
    s += ". The final mesh had " + cnt(node_count(r)) + " nodes and " + cnt(r.volume.num_tets()) +
         " tetrahedra";
    if (r.volume.num_prisms() > 0) s += " and " + cnt(r.volume.num_prisms()) + " prisms";
    s += "; minimum and mean tetrahedron quality \u03b3t were " + num(r.tet_quality_stats.min, 3) +
         " and " + num(r.tet_quality_stats.mean, 3);
    if (layers > 0 && r.core_quality_stats.count > 0)
      s += " (" + num(r.core_quality_stats.min, 3) + " and " + num(r.core_quality_stats.mean, 3) +
           " in the core)";
    s += ".";
  } else {
    s += " No volume mesh was generated.";
  }
  if (!r.preset.solver.empty()) s += " The mesh was prepared for " + r.preset.solver + ".";
  if (in.family && !in.family->rows.empty()) {
    const MeshFamily& f = *in.family;
    std::vector<std::string> hs;
    for (const FamilyMember& m : f.rows) hs.push_back(num(m.h, 3));
    s += " A family of " + std::to_string(f.rows.size()) +
         " meshes refined by r = " + num(f.ratio, 3) + " (h = " + join_and(hs) + " " + f.unit +
         ") was generated for a grid convergence study (Celik et al. 2008).";
  }
  return s;
}

std::string methods_report_html(const MethodsReportInput& in) {
  const MeshJobResult& r = *in.result;
  const MeshJobOptions& o = *in.options;
  const std::string unit = unit_of(r);
  std::string h;
  h.reserve(1 << 16);
  h += "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
       "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>";
  h += "Mesh methods report" + (in.input_name.empty() ? "" : ": " + esc(in.input_name));
  h += "</title>\n<style>" + std::string(kStyle) + "</style>\n</head>\n<body>\n<main>\n";

  // 1. Title.
  h += "<h1>Mesh methods report</h1>\n<p class=\"sub\">";
  if (!in.input_name.empty()) h += esc(in.input_name) + " \u00b7 ";
  h += "vesselmesh " + esc(in.version.empty() ? "(version not given)" : in.version) + "</p>\n";

  // 2. The paragraph.
  h += "<h2>Paragraph for the methods section</h2>\n<p class=\"paste\">" +
       esc(methods_paragraph(in)) + "</p>\n";

  // 3. Pictures.
  h += "<h2>Pictures</h2>\n";
  if (in.images.empty()) {
    h += "<p>" + esc(in.pictures_note.empty() ? "No pictures." : in.pictures_note) + "</p>\n";
  } else {
    for (const ReportImage& img : in.images) {
      h += "<figure>\n<img src=\"data:image/png;base64," + base64(img.png) + "\" alt=\"" +
           esc(img.alt) + "\">\n<figcaption>" + esc(img.title) + "</figcaption>\n</figure>\n";
    }
  }

  // 4. Quality.
  h += "<h2>Quality</h2>\n<p>" + std::string(kGammaK) + " is the triangle quality and " + kGammaT +
       " the tetrahedron quality, both 1 for the equilateral element and 0 for a flat one.</p>\n";
  if (r.output_quality_stats.count > 0)
    h += "<figure>\n" +
         histogram_svg(r.output_quality_stats, "hist-wall", "wall triangles", "\u03b3K") +
         "\n<figcaption>Wall triangles (" + kGammaK + "), " + cnt(r.output_quality_stats.count) +
         " triangles</figcaption>\n</figure>\n";
  if (r.tet_quality_stats.count > 0)
    h += "<figure>\n" + histogram_svg(r.tet_quality_stats, "hist-tets", "tetrahedra", "\u03b3t") +
         "\n<figcaption>Tetrahedra (" + kGammaT + "), " + cnt(r.tet_quality_stats.count) +
         " tetrahedra</figcaption>\n</figure>\n";
  {
    h += "<table>\n<caption>Quality per group</caption>\n<thead><tr><th scope=\"col\">Elements"
         "</th><th scope=\"col\">Count</th><th scope=\"col\">Minimum</th><th scope=\"col\">"
         "Mean</th></tr></thead>\n<tbody>\n";
    const std::string gk = std::string(" (") + kGammaK + ")",
                      gt = std::string(" (") + kGammaT + ")";
    h += stats_row("wall triangles as remeshed" + gk, r.output_quality_stats);
    for (const SurfaceGroupQuality& g : r.written_quality) {
      h += stats_row(esc(g.name) + " triangles as written" + gk, g.quality);
      if (g.ring.count > 0) h += stats_row(esc(g.name) + " layer ring" + gk, g.ring);
    }
    if (r.tet_quality_stats.count > 0) h += stats_row("all tetrahedra" + gt, r.tet_quality_stats);
    if (r.core_quality_stats.count > 0)
      h += stats_row("core tetrahedra" + gt, r.core_quality_stats);
    h += "</tbody>\n</table>\n";
  }

  // 5. Parameters.
  {
    Table t{"Parameters as applied", {"Parameter", "Value", "Unit"}, {}, {}};
    auto row = [&](const std::string& name, const std::string& value, const std::string& u) {
      t.rows.push_back({esc(name), esc(value), esc(u)});
    };
    const SizeOptions& so = o.remesh_options.size;
    if (!r.remeshed) {
      row("wall size", "not remeshed", "");
    } else if (uniform_size(o)) {
      row("wall size (uniform)", num(so.size), unit);
    } else {
      std::string n = num(per_circumference_used(r, o));
      if (r.budget.coarsened)
        n += " (lowered from " + num(r.budget.asked_per_circumference) + " by the element budget)";
      row("edges per circumference N (h = 2\u03c0R/N)", n, "");
    }
    if (r.remeshed) {
      row("size gradation", so.gradation > 0 ? num(so.gradation) : "off", "per unit length");
      if (so.size_min > 0) row("smallest size", num(so.size_min), unit);
      if (std::isfinite(so.size_max)) row("largest size", num(so.size_max), unit);
      if (so.curvature_points > 0) row("curvature points", num(so.curvature_points), "per radian");
      for (const RefineSphere& sp : so.spheres)
        row("refinement sphere",
            "size " + num(sp.size) + " within " + num(sp.radius) + " of " + point_html(sp.center),
            unit);
      row("fidelity", num(o.remesh_options.fidelity), "of h");
    }
    const bool vol = has_volume(r);
    row("volume mesh", vol ? "yes" : "no (surface only)", "");
    if (vol) {
      const int layers = r.volume_stats.viscous_layers;
      row("boundary layers", std::to_string(layers), "");
      if (layers > 0) {
        const double first = first_height(r, o);
        if (first > 0) {
          row("first layer height", num(first), unit);
          if (r.first_layer_yplus) row("target y+", num(r.first_layer_yplus->target.yplus), "");
        } else {
          row("layer thickness", num(o.viscous.thickness_fraction), "of R");
        }
        row("layer growth ratio", num(o.viscous.growth), "");
        row("layer elements", o.keep_prisms ? "prisms" : "split into tetrahedra", "");
      }
      const int wall = r.volume_stats.wall_layers;
      if (wall > 0) {
        row("vessel wall layers", std::to_string(wall), "");
        if (o.vessel.first_height > 0)
          row("vessel wall first layer height", num(o.vessel.first_height), unit);
        else
          row("vessel wall thickness", num(o.vessel.thickness_fraction), "of R");
      } else {
        row("vessel wall", "none", "");
      }
      row("core size", o.core_size > 0 ? num(o.core_size) : "from the wall's sizes",
          o.core_size > 0 ? unit : "");
    }
    row("element budget", num(o.max_elements), "elements");
    row("solver preset", r.preset.solver.empty() ? "none" : r.preset.solver, "");
    for (const PresetSetting& ps : r.preset.settings)
      row("  " + ps.id + (ps.from_preset ? " (preset)" : " (given)"), ps.value, "");
    row("output units",
        o.output_units == LengthUnit::kGuess ? unit + " (the input's)"
                                             : std::string(unit_symbol(o.output_units)),
        "");
    row("model unit", unit + (r.surface.unit.guessed ? " (guessed)" : " (given)"), "");
    h += "<h2>Parameters</h2>\n" + table_html(t);
    if (!r.preset.note.empty()) h += "<p>" + esc(r.preset.note) + "</p>\n";
    h += "<p>Options as given: <code>" +
         esc(in.options_text.empty() ? "(defaults)" : in.options_text) + "</code></p>\n";
  }

  // 6. Openings.
  {
    h += "<h2>Openings</h2>\n";
    const auto& ops = r.surface.topology.openings;
    const size_t n = std::min(ops.size(), r.opening_names.size());
    if (n == 0) {
      h += "<p>The surface has no opening.</p>\n";
    } else {
      const std::string u = esc(unit);
      Table t{"Openings (" + unit + ")",
              {"Name", "Radius (" + u + ")", "Area (" + u + "\u00b2)", "Centroid (" + u + ")",
               "Source"},
              {false, true, true, false, false},
              {}};
      for (size_t i = 0; i < n; ++i) {
        const Opening& op = ops[i];
        t.rows.push_back({esc(r.opening_names[i]), num(op.radius),
                          num(std::numbers::pi * op.radius * op.radius), point_html(op.centroid),
                          i < r.surface.opening_sources.size()
                              ? esc(opening_source_text(r.surface.opening_sources[i]))
                              : ""});
      }
      h += table_html(t);
    }
  }

  // 7. Repairs and cuts.
  {
    h += "<h2>Input repairs and cuts</h2>\n";
    const std::vector<std::string> done = repairs_done(r.surface, unit);
    if (done.empty()) {
      h += "<p>Repairs and cuts: none.</p>\n";
    } else {
      h += "<ul>\n";
      for (const std::string& d : done) h += "<li>" + esc(d) + "</li>\n";
      h += "</ul>\n";
    }
    const ModelUnit& mu = r.surface.unit;
    h += "<p>Unit: " + esc(unit) +
         (mu.guessed ? ", guessed" + (mu.reason.empty() ? "" : " (" + esc(mu.reason) + ")")
                     : std::string(", given")) +
         ".</p>\n";
    h += "<h3>Warnings</h3>\n";
    if (r.warnings.empty()) {
      h += "<p>none</p>\n";
    } else {
      h += "<ul>\n";
      for (const std::string& w : r.warnings)
        h += "<li>" + esc(phrase_options(w, kFaceCli)) + "</li>\n";
      h += "</ul>\n";
    }
  }

  // 8. Mesh.
  {
    h += "<h2>Mesh</h2>\n";
    Table g{
        "Physical groups", {"Dimension", "Tag", "Name", "Elements"}, {true, true, false, true}, {}};
    for (const OutputGroup& og : r.groups)
      g.rows.push_back(
          {std::to_string(og.dim), std::to_string(og.tag), esc(og.name), cnt(og.elements)});
    h += table_html(g);
    Table t{"Counts and time", {"Quantity", "Value"}, {false, true}, {}};
    t.rows.push_back({"nodes", cnt(node_count(r))});
    t.rows.push_back({"wall triangles", cnt(r.output_surface.num_triangles())});
    if (has_volume(r)) {
      t.rows.push_back({"tetrahedra", cnt(r.volume.num_tets())});
      t.rows.push_back({"prisms", cnt(r.volume.num_prisms())});
      t.rows.push_back({"boundary triangles", cnt(r.volume.num_triangles())});
      t.rows.push_back(
          {"lumen volume (" + esc(unit) + "\u00b3)", num(r.volume_stats.lumen_volume)});
    }
    t.rows.push_back({"meshing time (s)", num(r.seconds_total, 3)});
    h += table_html(t);
  }

  // 9. Family.
  if (in.family && !in.family->rows.empty()) {
    const MeshFamily& f = *in.family;
    const std::string fu = f.unit.empty() ? unit : f.unit;
    h += "<h2>Mesh family</h2>\n<p>Member k has every size of the first member divided by "
         "r<sup>k</sup>, r = " +
         num(f.ratio, 3) + "; its boundary layer " +
         (f.layers == FamilyLayers::kFixed
              ? "is the first member's (one first-layer height in every member)"
              : "is refined with it (the first layer divided by r<sup>k</sup>, more layers of "
                "the same total thickness)") +
         ". h is the representative cell size (V / cells)<sup>1/3</sup>, V the meshed volume "
         "(Celik et al. 2008).</p>\n";
    const std::string u = esc(fu);
    Table t{"Mesh family (lengths in " + fu + ")",
            {"Member", "File", "Nodes", "Cells", "h (" + u + ")", "Ratio",
             std::string(kGammaT) + " min", std::string(kGammaT) + " mean",
             "Core " + std::string(kGammaT) + " min", "Layers", "First layer height (" + u + ")",
             "Thickness (" + u + ")", "Seconds"},
            {true, false, true, true, true, true, true, true, true, true, true, true, true},
            {}};
    for (const FamilyMember& m : f.rows)
      t.rows.push_back({std::to_string(m.index), esc(m.file.empty() ? "-" : m.file), cnt(m.nodes),
                        cnt(m.cells), num(m.h), m.ratio > 0 ? num(m.ratio) : "-",
                        num(m.quality.min, 3), num(m.quality.mean, 3), num(m.core_quality.min, 3),
                        std::to_string(m.layers), m.layers > 0 ? num(m.first_layer_height) : "-",
                        m.layers > 0 ? num(m.layer_thickness) : "-", num(m.seconds, 3)});
    h += table_html(t);
  }

  // 10. Provenance.
  h += "<h2>Provenance</h2>\n<ul>\n<li>vesselmesh " +
       esc(in.version.empty() ? "(version not given)" : in.version) + "</li>\n";
  if (!in.input_name.empty()) h += "<li>Input: " + esc(in.input_name) + "</li>\n";
  h += "<li>Input hash: <code>" + esc(in.input_hash.empty() ? "(not given)" : in.input_hash) +
       "</code></li>\n<li>Input file: " + esc(r.surface.format) + ", " +
       cnt(r.surface.input_triangles) + " triangles</li>\n<li>Options: <code>" +
       esc(in.options_text.empty() ? "(defaults)" : in.options_text) + "</code></li>\n</ul>\n";
  h += "</main>\n</body>\n</html>\n";
  return h;
}

}  // namespace vm
