// Tests of the methods report (core/report/methods_report.h): the paragraph
// and the HTML page of a meshed bifurcation phantom, with its pictures and
// a mesh family built by hand.
#include "core/report/methods_report.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "core/io/stl.h"
#include "core/pipeline/option_table.h"
#include "core/report/render_views.h"
#include "tests/support/expect_has.h"
#include "tests/support/phantoms.h"

namespace vm {
namespace {

struct Meshed {
  MeshJobOptions options;
  MeshJobResult result;
};

// The bifurcation phantom meshed coarsely with 3 boundary layers, once.
const Meshed& meshed() {
  static const Meshed m = [] {
    Meshed m;
    EXPECT_TRUE(set_option_text(m.options, "size", "0.3").ok());
    EXPECT_TRUE(set_option_text(m.options, "layers", "3").ok());
    EXPECT_TRUE(set_option_text(m.options, "growth", "1.2").ok());
    EXPECT_TRUE(set_option_text(m.options, "units", "mm").ok());
    auto r = run_mesh_job(write_stl_binary(testing::phantom(PhantomKind::kBifurcation, true, 0.2)),
                          m.options);
    EXPECT_TRUE(r.ok()) << r.message();
    if (r.ok()) m.result = std::move(r).value();
    return m;
  }();
  return m;
}

MethodsReportInput input_of(const Meshed& m) {
  MethodsReportInput in;
  in.result = &m.result;
  in.options = &m.options;
  in.input_name = "bifurcation.stl";
  in.input_hash = "sha256:0123abcd";
  in.options_text = "--size 0.3 --layers 3 --growth 1.2 --units mm";
  in.version = "0.1.0";
  in.pictures_note = "Pictures are made by the page.";
  return in;
}

bool has(const std::string& s, const std::string& what) {
  return s.find(what) != std::string::npos;
}

TEST(MethodsReport, NumbersAreGroupedAndRounded) {
  EXPECT_EQ(report_count(0), "0");
  EXPECT_EQ(report_count(999), "999");
  EXPECT_EQ(report_count(1000), "1,000");
  EXPECT_EQ(report_count(12345), "12,345");
  EXPECT_EQ(report_count(1234567), "1,234,567");
  EXPECT_EQ(report_number(0.123456), "0.1235");
  EXPECT_EQ(report_number(0.5), "0.5");
  EXPECT_EQ(report_number(2.0), "2");
  EXPECT_EQ(report_number(12.3456, 3), "12.3");
  EXPECT_EQ(report_number(123456.7), "123,457");
  EXPECT_EQ(report_number(-0.00001234, 3), "-1.23e-05");
  EXPECT_EQ(report_number(0), "0");
  EXPECT_EQ(report_number(1.0 / 0.0), "-");
}

TEST(MethodsReport, ParagraphStatesTheLayersAndCounts) {
  const Meshed& m = meshed();
  ASSERT_GT(m.result.volume.num_tets(), 0u);
  const std::string p = methods_paragraph(input_of(m));
  EXPECT_TRUE(has(p, "bifurcation.stl")) << p;
  EXPECT_TRUE(has(p, "vesselmesh 0.1.0")) << p;
  EXPECT_TRUE(has(p, "Marchandise et al.")) << p;
  EXPECT_TRUE(has(p, "uniform target edge length of 0.3 mm")) << p;
  EXPECT_TRUE(has(p, "3 prismatic layers")) << p;
  EXPECT_TRUE(has(p, "growth ratio 1.2")) << p;
  EXPECT_TRUE(has(p, "split into tetrahedra")) << p;
  EXPECT_TRUE(has(p, report_count(m.result.volume.num_vertices()) + " nodes")) << p;
  EXPECT_TRUE(has(p, report_count(m.result.volume.num_tets()) + " tetrahedra")) << p;
  EXPECT_TRUE(has(p, report_count(m.result.output_surface.num_triangles()) + " triangles")) << p;
  EXPECT_FALSE(has(p, "family")) << p;
  EXPECT_EQ(testing::count_of(p, "\n"), 0u);
}

TEST(MethodsReport, HtmlIsSelfContainedAndHasEverySection) {
  const Meshed& m = meshed();
  const MeshJobResult& r = m.result;
  MethodsReportInput in = input_of(m);
  in.images = render_report_views(r);
  ASSERT_EQ(in.images.size(), 3u);
  MeshFamily family;
  family.members = 2;
  family.ratio = 1.4;
  family.unit = "mm";
  for (int k = 0; k < 2; ++k) {
    FamilyMember f;
    f.index = k;
    f.file = "mesh_" + std::to_string(k) + ".msh";
    f.nodes = 12345 + size_t(k) * 20000;
    f.cells = 54321 + size_t(k) * 90000;
    f.h = k ? 0.2143 : 0.3;
    f.ratio = k ? 1.4 : 0;
    f.quality.min = 0.25;
    f.quality.mean = 0.81;
    f.layers = 3 + k;
    f.first_layer_height = 0.01;
    f.layer_thickness = 0.2;
    f.seconds = 1.5;
    family.rows.push_back(f);
  }
  in.family = &family;
  const std::string html = methods_report_html(in);
  if (FILE* f = std::fopen("/tmp/report-sample.html", "wb")) {
    std::fwrite(html.data(), 1, html.size(), f);
    std::fclose(f);
  }
  EXPECT_EQ(html.rfind("<!DOCTYPE html>\n<html lang=\"en\">", 0), 0u);
  EXPECT_TRUE(has(html, "<meta charset=\"utf-8\">"));
  EXPECT_TRUE(has(html, "<title>Mesh methods report: bifurcation.stl</title>"));
  EXPECT_FALSE(has(html, "http://"));
  EXPECT_FALSE(has(html, "https://"));
  EXPECT_FALSE(has(html, "<script"));
  EXPECT_FALSE(has(html, "url("));
  EXPECT_EQ(testing::count_of(html, "<main>"), 1u);
  EXPECT_TRUE(html.ends_with("</main>\n</body>\n</html>\n"));
  // The headings in order.
  const char* sections[] = {"<h1>Mesh methods report</h1>",
                            "<h2>Paragraph for the methods section</h2>",
                            "<h2>Pictures</h2>",
                            "<h2>Quality</h2>",
                            "<h2>Parameters</h2>",
                            "<h2>Openings</h2>",
                            "<h2>Input repairs and cuts</h2>",
                            "<h2>Mesh</h2>",
                            "<h2>Mesh family</h2>",
                            "<h2>Provenance</h2>"};
  size_t at = 0;
  for (const char* s : sections) {
    const size_t p = html.find(s);
    ASSERT_NE(p, std::string::npos) << s;
    EXPECT_GT(p, at) << s;
    at = p;
  }
  // The paragraph, escaped as the page shows it (no markup in it).
  const std::string paragraph = methods_paragraph(in);
  EXPECT_TRUE(has(paragraph, "A family of 2 meshes refined by r = 1.4")) << paragraph;
  EXPECT_TRUE(has(html, "<p class=\"paste\">" + paragraph + "</p>"));
  // Pictures: data URIs with their alt texts and captions.
  EXPECT_EQ(testing::count_of(html, "<img src=\"data:image/png;base64,iVBORw0KGgo"), 3u);
  EXPECT_EQ(testing::count_of(html, "<img "), testing::count_of(html, " alt=\""));
  EXPECT_EQ(testing::count_of(html, "<figcaption>"), testing::count_of(html, "<figure>"));
  for (const ReportImage& img : in.images) EXPECT_TRUE(has(html, img.title));
  // Histograms as accessible SVG.
  EXPECT_EQ(testing::count_of(html, "<svg role=\"img\" aria-labelledby="), 2u);
  EXPECT_EQ(testing::count_of(html, "<title id=\"hist-"), 2u);
  // Tables: every header a column header, every table captioned.
  EXPECT_EQ(testing::count_of(html, "<th>"), 0u);
  EXPECT_EQ(testing::count_of(html, "<th "), testing::count_of(html, "<th scope=\"col\">"));
  EXPECT_EQ(testing::count_of(html, "<table>"), testing::count_of(html, "<caption>"));
  // Openings and groups by name; counts grouped.
  ASSERT_EQ(r.opening_names.size(), 3u);
  for (const std::string& name : r.opening_names)
    EXPECT_TRUE(has(html, "<td>" + name + "</td>")) << name;
  for (const OutputGroup& g : r.groups) EXPECT_TRUE(has(html, "<td>" + g.name + "</td>")) << g.name;
  EXPECT_TRUE(has(html, "<td class=\"n\">" + report_count(r.volume.num_tets()) + "</td>"));
  EXPECT_TRUE(has(html, "sha256:0123abcd"));
  // The options as given, in the parameters and the provenance.
  EXPECT_EQ(testing::count_of(html, "<code>--size 0.3 --layers 3 --growth 1.2 --units mm</code>"),
            2u);
  // The family's rows.
  EXPECT_TRUE(has(html, "<td>mesh_0.msh</td><td class=\"n\">12,345</td><td class=\"n\">54,321"));
  EXPECT_TRUE(has(html, "<td>mesh_1.msh</td><td class=\"n\">32,345</td><td class=\"n\">144,321"));
  EXPECT_TRUE(has(html, "0.2143"));
  // Deterministic.
  EXPECT_EQ(methods_report_html(in), html);
}

TEST(MethodsReport, EscapesTheInputNameAndShowsTheNoteWithoutPictures) {
  const Meshed& m = meshed();
  MethodsReportInput in = input_of(m);
  in.input_name = "a<b & \"c\".stl";
  const std::string html = methods_report_html(in);
  EXPECT_FALSE(has(html, "a<b"));
  EXPECT_TRUE(has(html, "a&lt;b &amp; &quot;c&quot;.stl"));
  EXPECT_TRUE(has(html, "<p>Pictures are made by the page.</p>"));
  EXPECT_EQ(testing::count_of(html, "<img"), 0u);
  EXPECT_FALSE(has(html, "<h2>Mesh family</h2>"));
}

TEST(MethodsReport, SurfaceOnlyMeshSaysSo) {
  const Meshed& m = meshed();
  Meshed s;
  s.options = m.options;
  s.options.volume = false;
  s.result = m.result;
  s.result.volume = VolumeMesh{};
  s.result.tet_quality_stats = QualityStats{};
  s.result.core_quality_stats = QualityStats{};
  s.result.volume_stats = VolumeStats{};
  const std::string p = methods_paragraph(input_of(s));
  EXPECT_TRUE(has(p, "No volume mesh was generated.")) << p;
  EXPECT_FALSE(has(p, "tetrahedra")) << p;
  const std::string html = methods_report_html(input_of(s));
  EXPECT_EQ(testing::count_of(html, "<svg"), 1u);
}

}  // namespace
}  // namespace vm
