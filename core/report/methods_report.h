// The methods report: one self-contained HTML page (no network, no script
// needed to read it) that describes a mesh for a paper's methods section or
// supplement: pictures, quality histograms, the parameters with their
// units, the openings, the input's repairs and cuts, provenance, the mesh
// family's table when there is one, and a ready-to-paste paragraph. Our own
// design; the family follows Celik et al. (J. Fluids Eng. 130, 2008).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "core/pipeline/mesh_family.h"
#include "core/pipeline/mesh_job.h"

namespace vm {

/// A picture for the report: PNG bytes, a caption and a text alternative.
struct ReportImage {
  std::string title;  ///< caption, e.g. "Wall mesh"
  std::string alt;    ///< text alternative (what the picture shows)
  std::string png;    ///< PNG file bytes
};

/// What the report is made from. `result` and `options` are required (the
/// mesh described, and its options as applied); the rest is optional.
struct MethodsReportInput {
  const MeshJobResult* result = nullptr;
  const MeshJobOptions* options = nullptr;
  std::string input_name;    ///< the input file's name ("" : not shown)
  std::string input_hash;    ///< input_hash (core/io/provenance.h)
  std::string options_text;  ///< options_provenance: the options as given
  std::string version;       ///< vesselmesh's version
  /// The family, when the mesh is its first member (nullptr: none).
  const MeshFamily* family = nullptr;
  /// The pictures (wall, cut, boundary layer close-up); empty: the report
  /// says where pictures come from instead of showing any.
  std::vector<ReportImage> images;
  /// Said when `images` is empty (e.g. "Pictures: ... made by the page").
  std::string pictures_note;
};

/// The ready-to-paste paragraph (plain text, one paragraph) describing the
/// mesh in words with its numbers: method, sizes, layers, element counts,
/// quality, and the family when there is one.
std::string methods_paragraph(const MethodsReportInput& input);

/// The report as one HTML document (UTF-8, lang="en", inline CSS, images as
/// data: URIs, histograms as inline SVG, tables with headers), accessible
/// (passes axe-core's WCAG 2 A/AA rules). Precondition: input.result and
/// input.options are set.
std::string methods_report_html(const MethodsReportInput& input);

/// A count with a comma every three digits ("12,345"; no locale).
std::string report_count(size_t n);

/// A number with `digits` significant digits, without exponent from 1e-4
/// up to 1e15 (larger than 10^digits: rounded, digits grouped as
/// report_count's), "-" for a non-finite one.
std::string report_number(double x, int digits = 4);

}  // namespace vm
