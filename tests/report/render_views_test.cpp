// Tests of the report's pictures (core/report/render_views.h): the PNG
// encoder (decoded here by hand: chunks, CRCs, zlib, row filters) and the
// three views of a meshed bifurcation phantom.
#include "core/report/render_views.h"

#include <gtest/gtest.h>
#include <zlib.h>

#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "core/io/stl.h"
#include "core/pipeline/option_table.h"
#include "tests/support/phantoms.h"

namespace vm {
namespace {

uint32_t be32(const std::string& s, size_t at) {
  return uint32_t(uint8_t(s[at])) << 24 | uint32_t(uint8_t(s[at + 1])) << 16 |
         uint32_t(uint8_t(s[at + 2])) << 8 | uint32_t(uint8_t(s[at + 3]));
}

// A PNG as the encoder writes it, decoded: the chunks checked (CRCs, IHDR
// first, IEND last), IDAT inflated (its size checked) and unfiltered.
struct DecodedPng {
  bool ok = false;
  int width = 0, height = 0;
  size_t inflated = 0;
  std::vector<uint8_t> rgb;
};

DecodedPng decode_png(const std::string& png) {
  DecodedPng d;
  EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  std::string idat;
  size_t at = 8;
  bool ihdr = false, iend = false;
  while (at + 12 <= png.size()) {
    const uint32_t len = be32(png, at);
    const std::string type = png.substr(at + 4, 4);
    if (at + 12 + len > png.size()) break;
    const uLong crc = crc32(0L, reinterpret_cast<const Bytef*>(png.data() + at + 4), len + 4);
    EXPECT_EQ(uint32_t(crc), be32(png, at + 8 + len)) << type;
    const std::string data = png.substr(at + 8, len);
    if (type == "IHDR") {
      EXPECT_EQ(at, 8u);
      EXPECT_EQ(len, 13u);
      d.width = int(be32(data, 0));
      d.height = int(be32(data, 4));
      EXPECT_EQ(data.substr(8, 5), std::string("\x08\x02\x00\x00\x00", 5));
      ihdr = true;
    } else if (type == "IDAT") {
      idat += data;
    } else if (type == "IEND") {
      iend = true;
      EXPECT_EQ(at + 12 + len, png.size());
    }
    at += 12 + len;
  }
  EXPECT_TRUE(ihdr && iend);
  if (!ihdr || d.width <= 0 || d.height <= 0) return d;
  const size_t stride = 3 * size_t(d.width);
  std::vector<uint8_t> raw(size_t(d.height) * (stride + 1) + 16);
  uLongf raw_size = uLongf(raw.size());
  if (uncompress(raw.data(), &raw_size, reinterpret_cast<const Bytef*>(idat.data()),
                 uLong(idat.size())) != Z_OK)
    return d;
  d.inflated = raw_size;
  if (raw_size != size_t(d.height) * (stride + 1)) return d;
  d.rgb.assign(size_t(d.height) * stride, 0);
  for (size_t y = 0; y < size_t(d.height); ++y) {
    const uint8_t filter = raw[y * (stride + 1)];
    const uint8_t* in = &raw[y * (stride + 1) + 1];
    uint8_t* row = &d.rgb[y * stride];
    const uint8_t* prev = y > 0 ? &d.rgb[(y - 1) * stride] : nullptr;
    for (size_t i = 0; i < stride; ++i) {
      const int a = i >= 3 ? row[i - 3] : 0, b = prev ? prev[i] : 0,
                c = prev && i >= 3 ? prev[i - 3] : 0;
      int pred = 0;
      if (filter == 1) pred = a;
      if (filter == 2) pred = b;
      if (filter == 3) pred = (a + b) / 2;
      if (filter == 4) {
        const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
        pred = pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
      }
      EXPECT_LE(filter, 4);
      row[i] = uint8_t(in[i] + pred);
    }
  }
  d.ok = true;
  return d;
}

// The bifurcation phantom meshed coarsely with 3 boundary layers (and a
// vessel wall when asked), once per setting.
const MeshJobResult& meshed(bool wall, bool volume = true) {
  static MeshJobResult results[3];
  static bool done[3] = {false, false, false};
  const int k = !volume ? 2 : wall ? 1 : 0;
  if (!done[k]) {
    MeshJobOptions o;
    EXPECT_TRUE(set_option_text(o, "size", "0.3").ok());
    EXPECT_TRUE(set_option_text(o, "layers", "3").ok());
    EXPECT_TRUE(set_option_text(o, "units", "mm").ok());
    if (wall) {
      EXPECT_TRUE(set_option_text(o, "wall_thickness", "0.15").ok());
      EXPECT_TRUE(set_option_text(o, "wall_layers", "2").ok());
    }
    o.volume = volume;
    auto r =
        run_mesh_job(write_stl_binary(testing::phantom(PhantomKind::kBifurcation, true, 0.2)), o);
    EXPECT_TRUE(r.ok()) << r.message();
    if (r.ok()) results[k] = std::move(r).value();
    done[k] = true;
  }
  return results[k];
}

const uint8_t kWhite[3] = {255, 255, 255};

size_t count_colour(const DecodedPng& d, const uint8_t* c) {
  size_t n = 0;
  for (size_t i = 0; i + 2 < d.rgb.size(); i += 3)
    n += d.rgb[i] == c[0] && d.rgb[i + 1] == c[1] && d.rgb[i + 2] == c[2];
  return n;
}

void save(const std::string& path, const std::string& bytes) {
  if (FILE* f = std::fopen(path.c_str(), "wb")) {
    std::fwrite(bytes.data(), 1, bytes.size(), f);
    std::fclose(f);
  }
}

TEST(RenderViews, PngRoundTripsThroughZlib) {
  RgbImage img;
  img.width = 37;
  img.height = 23;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      img.rgb.push_back(uint8_t(7 * x));
      img.rgb.push_back(uint8_t(11 * y));
      img.rgb.push_back(uint8_t((x * y) ^ 0x5a));
    }
  const std::string png = encode_png(img);
  const DecodedPng d = decode_png(png);
  ASSERT_TRUE(d.ok);
  EXPECT_EQ(d.width, 37);
  EXPECT_EQ(d.height, 23);
  EXPECT_EQ(d.inflated, size_t(23 * (1 + 3 * 37)));
  EXPECT_EQ(d.rgb, img.rgb);
  EXPECT_EQ(encode_png(img), png);  // deterministic
}

TEST(RenderViews, ThreeViewsOfAMeshWithLayers) {
  const MeshJobResult& r = meshed(false);
  ASSERT_GT(r.volume.num_tets(), 0u);
  ASSERT_EQ(r.volume_stats.viscous_layers, 3);
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<ReportImage> views = render_report_views(r, 800, 600);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("render_report_views: %.3f s for %zu tetrahedra, %zu wall triangles\n", seconds,
              r.volume.num_tets(), r.output_surface.num_triangles());
  EXPECT_LT(seconds, 5.0);
  ASSERT_EQ(views.size(), 3u);
  std::vector<DecodedPng> px;
  for (size_t i = 0; i < views.size(); ++i) {
    save("/tmp/report-view-" + std::to_string(i + 1) + ".png", views[i].png);
    px.push_back(decode_png(views[i].png));
    ASSERT_TRUE(px.back().ok) << i;
    EXPECT_EQ(px.back().width, 800);
    EXPECT_EQ(px.back().height, 600);
    EXPECT_EQ(px.back().inflated, size_t(600 * (1 + 3 * 800)));
    EXPECT_FALSE(views[i].title.empty());
    EXPECT_GT(views[i].alt.size(), 30u);
  }
  EXPECT_EQ(views[0].title, "Wall mesh");
  EXPECT_NE(views[0].alt.find(report_count(r.output_surface.num_triangles()) + " triangles"),
            std::string::npos)
      << views[0].alt;
  EXPECT_NE(views[1].alt.find("elements cut"), std::string::npos) << views[1].alt;
  EXPECT_NE(views[2].alt.find("3 boundary layers"), std::string::npos) << views[2].alt;

  // The wall: not blank (a good share drawn), the silhouette inside the
  // frame (the outermost rows and columns are background), the whole
  // frame used along one axis at least (fitted with a margin).
  const DecodedPng& wall = px[0];
  const size_t drawn = wall.rgb.size() / 3 - count_colour(wall, kWhite);
  EXPECT_GT(drawn, size_t(0.15 * 800 * 600));
  int x0 = 800, x1 = -1, y0 = 600, y1 = -1;
  for (int y = 0; y < 600; ++y)
    for (int x = 0; x < 800; ++x) {
      const uint8_t* p = &wall.rgb[3 * (size_t(y) * 800 + size_t(x))];
      if (p[0] == 255 && p[1] == 255 && p[2] == 255) continue;
      x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
    }
  EXPECT_GT(x0, 5);
  EXPECT_LT(x1, 794);
  EXPECT_GT(y0, 5);
  EXPECT_LT(y1, 594);
  EXPECT_TRUE(x1 - x0 > 0.8 * 800 || y1 - y0 > 0.8 * 600)
      << x0 << " " << x1 << " " << y0 << " " << y1;
  // Dark edges are drawn: some pixels much darker than the shading's.
  size_t dark = 0;
  for (size_t i = 0; i < wall.rgb.size(); i += 3)
    dark += wall.rgb[i] < 110 && wall.rgb[i + 1] < 90 && wall.rgb[i + 2] < 90;
  EXPECT_GT(dark, 1000u);

  // The cut shows the core and the layer in their colours; the close-up
  // shows the layer larger (a bigger share of its pixels).
  const size_t core_cut = count_colour(px[1], kReportPartColours[0]);
  const size_t layer_cut = count_colour(px[1], kReportPartColours[1]);
  const size_t layer_zoom = count_colour(px[2], kReportPartColours[1]);
  const size_t core_zoom = count_colour(px[2], kReportPartColours[0]);
  EXPECT_GT(core_cut, 5000u);
  EXPECT_GT(layer_cut, 500u);
  EXPECT_GT(layer_zoom, 4 * layer_cut);
  EXPECT_GT(core_zoom, 1000u);
  EXPECT_EQ(count_colour(px[1], kReportPartColours[2]), 0u);

  // Deterministic.
  const std::vector<ReportImage> again = render_report_views(r, 800, 600);
  ASSERT_EQ(again.size(), views.size());
  for (size_t i = 0; i < views.size(); ++i) EXPECT_EQ(again[i].png, views[i].png) << i;
}

TEST(RenderViews, VesselWallHasItsOwnColour) {
  const MeshJobResult& r = meshed(true);
  ASSERT_GT(r.volume_stats.wall_layers, 0);
  const std::vector<ReportImage> views = render_report_views(r, 400, 300);
  ASSERT_EQ(views.size(), 3u);
  save("/tmp/report-view-wall-cut.png", views[1].png);
  save("/tmp/report-view-wall-close-up.png", views[2].png);
  const DecodedPng cut = decode_png(views[1].png);
  ASSERT_TRUE(cut.ok);
  EXPECT_EQ(cut.width, 400);
  EXPECT_GT(count_colour(cut, kReportPartColours[2]), 100u);
  EXPECT_GT(count_colour(cut, kReportPartColours[1]), 100u);
  EXPECT_NE(views[1].alt.find("vessel wall"), std::string::npos) << views[1].alt;
}

TEST(RenderViews, SurfaceOnlyGetsTheWallViewAlone) {
  const MeshJobResult& r = meshed(false, false);
  ASSERT_TRUE(r.volume.tets.empty());
  const std::vector<ReportImage> views = render_report_views(r, 320, 200);
  ASSERT_EQ(views.size(), 1u);
  const DecodedPng d = decode_png(views[0].png);
  ASSERT_TRUE(d.ok);
  EXPECT_EQ(d.width, 320);
  EXPECT_EQ(d.height, 200);
  EXPECT_GT(d.rgb.size() / 3 - count_colour(d, kWhite), size_t(0.1 * 320 * 200));
}

TEST(RenderViews, EmptyResultGivesABlankWallView) {
  MeshJobResult empty;
  const std::vector<ReportImage> views = render_report_views(empty, 64, 48);
  ASSERT_EQ(views.size(), 1u);
  const DecodedPng d = decode_png(views[0].png);
  ASSERT_TRUE(d.ok);
  EXPECT_EQ(count_colour(d, kWhite), size_t(64 * 48));
}

}  // namespace
}  // namespace vm
