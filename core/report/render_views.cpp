// Pictures of a mesh without a GPU (render_views.h): a small z-buffered
// software rasterizer of convex polygons (orthographic views, flat Lambert
// shading with a soft ambient, element edges darkened by the pixel's
// distance to the polygon's sides, 2x2 supersampling) and a PNG encoder on
// zlib. Our own design.

#include "core/report/render_views.h"

#include <zlib.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "core/geom/vec3.h"

namespace vm {
namespace {

using V3 = Vec3;
using Rgb = std::array<uint8_t, 3>;

V3 sub(const V3& a, const V3& b) { return a - b; }
V3 unit(const V3& a) { return normalized(a); }
V3 point(const std::vector<double>& points, int32_t i) { return at(points, i); }

// ---- PNG ------------------------------------------------------------------

void put_u32(std::string& out, uint32_t v) {
  out.push_back(char(v >> 24));
  out.push_back(char(v >> 16));
  out.push_back(char(v >> 8));
  out.push_back(char(v));
}

// Appends a chunk: length, type, data, CRC-32 of type and data.
void put_chunk(std::string& out, const char* type, const std::string& data) {
  put_u32(out, uint32_t(data.size()));
  const size_t start = out.size();
  out.append(type, 4);
  out += data;
  const uLong crc =
      crc32(0L, reinterpret_cast<const Bytef*>(out.data() + start), uInt(out.size() - start));
  put_u32(out, uint32_t(crc));
}

uint8_t paeth(int a, int b, int c) {
  const int p = a + b - c;
  const int pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
  return uint8_t(pa <= pb && pa <= pc ? a : pb <= pc ? b : c);
}

// ---- Rasterizer -----------------------------------------------------------

constexpr int kSuper = 2;  // supersampling factor per axis
const Rgb kBackground = {255, 255, 255};
const Rgb kEdge = {38, 42, 52};
const Rgb kWallFront = {204, 92, 74};   // lumen wall seen from outside
const Rgb kWallBack = {150, 132, 120};  // its inside, seen through an opening
// The cut's parts: 0 core, 1 viscous layer, 2 vessel wall.
const Rgb kPartColour[3] = {
    {kReportPartColours[0][0], kReportPartColours[0][1], kReportPartColours[0][2]},
    {kReportPartColours[1][0], kReportPartColours[1][1], kReportPartColours[1][2]},
    {kReportPartColours[2][0], kReportPartColours[2][1], kReportPartColours[2][2]}};
const char* const kPartColourName[3] = {"light blue", "orange", "purple"};
const Rgb kFrame = {20, 110, 60};  // the close-up's square on the cut

// An orthographic camera: screen x = ox + scale (p . u - cu), screen y = oy -
// scale (p . v - cv), depth p . w (larger is nearer); u, v, w orthonormal
// and right-handed (w = u x v points at the viewer).
struct Camera {
  V3 u{1, 0, 0}, v{0, 1, 0}, w{0, 0, 1};
  double cu = 0, cv = 0, scale = 1, ox = 0, oy = 0;
  double x(double pu) const { return ox + scale * (pu - cu); }
  double y(double pv) const { return oy - scale * (pv - cv); }
};

// Fits the box [u0, u1] x [v0, v1] (plane coordinates) into a canvas of
// width x height pixels with `margin` of it free on each side.
void fit(Camera& cam, double u0, double u1, double v0, double v1, int width, int height,
         double margin) {
  const double du = std::max(u1 - u0, 1e-300), dv = std::max(v1 - v0, 1e-300);
  cam.scale = std::min(width * (1 - 2 * margin) / du, height * (1 - 2 * margin) / dv);
  cam.cu = 0.5 * (u0 + u1);
  cam.cv = 0.5 * (v0 + v1);
  cam.ox = 0.5 * width;
  cam.oy = 0.5 * height;
}

struct Canvas {
  int width = 0, height = 0;  // supersampled pixels
  std::vector<uint8_t> rgb;
  std::vector<float> depth;
  Canvas(int w, int h)
      : width(w),
        height(h),
        rgb(size_t(w) * size_t(h) * 3),
        depth(size_t(w) * size_t(h), -std::numeric_limits<float>::infinity()) {
    for (size_t i = 0; i < size_t(w) * size_t(h); ++i)
      std::memcpy(&rgb[3 * i], kBackground.data(), 3);
  }
};

// Fills the convex polygon xy[0..n) (screen coordinates, either orientation)
// with `colour`, its sides darkened within about a pixel of them by
// `edge_strength` (0..1), scaled down for polygons too small to show their
// sides. `z` (n depths, planar polygon) enables the depth test; null: drawn
// over. Pixel (i, j) is covered when its centre is inside.
void fill_polygon(Canvas& c, const double (*xy)[2], const double* z, int n, const Rgb& colour,
                  double edge_strength) {
  if (n < 3) return;
  double area2 = 0, perimeter = 0;
  for (int i = 0; i < n; ++i) {
    const double* a = xy[i];
    const double* b = xy[(i + 1) % n];
    area2 += a[0] * b[1] - a[1] * b[0];
    perimeter += std::hypot(b[0] - a[0], b[1] - a[1]);
  }
  if (!(std::abs(area2) > 1e-12) || !(perimeter > 0)) return;
  const double sign = area2 > 0 ? 1 : -1;
  // Side i as a x + b y + d = distance inside (>= 0 inside).
  double la[8], lb[8], ld[8];
  for (int i = 0; i < n; ++i) {
    const double* a = xy[i];
    const double* b = xy[(i + 1) % n];
    const double ex = b[0] - a[0], ey = b[1] - a[1], len = std::hypot(ex, ey);
    if (len <= 0) {
      la[i] = lb[i] = 0, ld[i] = 1e300;
      continue;
    }
    la[i] = -sign * ey / len;
    lb[i] = sign * ex / len;
    ld[i] = -(la[i] * a[0] + lb[i] * a[1]);
  }
  // Depth as an affine function of the screen position (from the first
  // three corners).
  double z0 = 0, zx = 0, zy = 0;
  if (z) {
    const double x1 = xy[1][0] - xy[0][0], y1 = xy[1][1] - xy[0][1];
    const double x2 = xy[2][0] - xy[0][0], y2 = xy[2][1] - xy[0][1];
    const double det = x1 * y2 - x2 * y1;
    if (std::abs(det) > 1e-12) {
      zx = ((z[1] - z[0]) * y2 - (z[2] - z[0]) * y1) / det;
      zy = ((z[2] - z[0]) * x1 - (z[1] - z[0]) * x2) / det;
    }
    z0 = z[0] - zx * xy[0][0] - zy * xy[0][1];
  }
  // Sides fade out on polygons whose inradius (2 A / P) is under a few
  // final pixels: a dense mesh would otherwise be all edge.
  const double inradius = std::abs(area2) / perimeter / kSuper;
  const double strength = edge_strength * std::clamp((inradius - 1.0) / 2.0, 0.0, 1.0);
  const double half_width = 0.55 * kSuper;

  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  for (int i = 0; i < n; ++i) {
    x0 = std::min(x0, xy[i][0]), x1 = std::max(x1, xy[i][0]);
    y0 = std::min(y0, xy[i][1]), y1 = std::max(y1, xy[i][1]);
  }
  const int i0 = std::max(0, int(std::floor(x0 - 0.5))),
            i1 = std::min(c.width - 1, int(std::ceil(x1 - 0.5)));
  const int j0 = std::max(0, int(std::floor(y0 - 0.5))),
            j1 = std::min(c.height - 1, int(std::ceil(y1 - 0.5)));
  for (int j = j0; j <= j1; ++j) {
    const double py = j + 0.5;
    for (int i = i0; i <= i1; ++i) {
      const double px = i + 0.5;
      double e = 1e300;
      for (int k = 0; k < n; ++k) e = std::min(e, la[k] * px + lb[k] * py + ld[k]);
      if (e < 0) continue;
      const size_t at = size_t(j) * size_t(c.width) + size_t(i);
      if (z) {
        const float d = float(z0 + zx * px + zy * py);
        if (d < c.depth[at]) continue;
        c.depth[at] = d;
      }
      const double t = strength * std::clamp(1 - (e - half_width) / kSuper, 0.0, 1.0);
      for (int k = 0; k < 3; ++k)
        c.rgb[3 * at + size_t(k)] = uint8_t(std::lround(colour[k] + t * (kEdge[k] - colour[k])));
    }
  }
}

// The outline of the square [x0, x1] x [y0, y1] (screen), `w` pixels wide.
void draw_box(Canvas& c, double x0, double y0, double x1, double y1, int w, const Rgb& colour) {
  auto fill = [&](int a0, int b0, int a1, int b1) {
    for (int j = std::max(0, b0); j <= std::min(c.height - 1, b1); ++j)
      for (int i = std::max(0, a0); i <= std::min(c.width - 1, a1); ++i)
        std::memcpy(&c.rgb[3 * (size_t(j) * size_t(c.width) + size_t(i))], colour.data(), 3);
  };
  const int a0 = int(std::lround(x0)), a1 = int(std::lround(x1));
  const int b0 = int(std::lround(y0)), b1 = int(std::lround(y1));
  fill(a0 - w, b0 - w, a1 + w, b0);
  fill(a0 - w, b1, a1 + w, b1 + w);
  fill(a0 - w, b0, a0, b1);
  fill(a1, b0, a1 + w, b1);
}

// The canvas averaged over kSuper x kSuper blocks.
RgbImage downsample(const Canvas& c) {
  RgbImage img;
  img.width = c.width / kSuper;
  img.height = c.height / kSuper;
  img.rgb.resize(size_t(img.width) * size_t(img.height) * 3);
  for (int j = 0; j < img.height; ++j)
    for (int i = 0; i < img.width; ++i)
      for (int k = 0; k < 3; ++k) {
        int sum = 0;
        for (int b = 0; b < kSuper; ++b)
          for (int a = 0; a < kSuper; ++a)
            sum += c.rgb[3 * (size_t(j * kSuper + b) * size_t(c.width) + size_t(i * kSuper + a)) +
                         size_t(k)];
        img.rgb[3 * (size_t(j) * size_t(img.width) + size_t(i)) + size_t(k)] =
            uint8_t((sum + kSuper * kSuper / 2) / (kSuper * kSuper));
      }
  return img;
}

// ---- Principal axes -------------------------------------------------------

// Eigenvectors of the symmetric 3x3 matrix `a` (cyclic Jacobi), as columns
// of the result ordered by decreasing eigenvalue; each made to have its
// largest component positive (deterministic signs).
std::array<V3, 3> principal_axes(double a[3][3]) {
  double vec[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (int sweep = 0; sweep < 50; ++sweep) {
    const double off = std::abs(a[0][1]) + std::abs(a[0][2]) + std::abs(a[1][2]);
    const double diag = std::abs(a[0][0]) + std::abs(a[1][1]) + std::abs(a[2][2]);
    if (off <= 1e-15 * diag || off == 0) break;
    for (int p = 0; p < 2; ++p)
      for (int q = p + 1; q < 3; ++q) {
        if (a[p][q] == 0) continue;
        const double theta = (a[q][q] - a[p][p]) / (2 * a[p][q]);
        const double t = (theta >= 0 ? 1 : -1) / (std::abs(theta) + std::sqrt(theta * theta + 1));
        const double cs = 1 / std::sqrt(t * t + 1), sn = t * cs;
        for (int k = 0; k < 3; ++k) {  // columns p, q of a
          const double akp = a[k][p], akq = a[k][q];
          a[k][p] = cs * akp - sn * akq;
          a[k][q] = sn * akp + cs * akq;
        }
        for (int k = 0; k < 3; ++k) {  // rows p, q
          const double apk = a[p][k], aqk = a[q][k];
          a[p][k] = cs * apk - sn * aqk;
          a[q][k] = sn * apk + cs * aqk;
        }
        for (int k = 0; k < 3; ++k) {
          const double vkp = vec[k][p], vkq = vec[k][q];
          vec[k][p] = cs * vkp - sn * vkq;
          vec[k][q] = sn * vkp + cs * vkq;
        }
      }
  }
  int order[3] = {0, 1, 2};
  std::sort(order, order + 3, [&](int x, int y) { return a[x][x] > a[y][y]; });
  std::array<V3, 3> axes;
  for (int c = 0; c < 3; ++c) {
    V3 e = {vec[0][order[c]], vec[1][order[c]], vec[2][order[c]]};
    int big = 0;
    for (int k = 1; k < 3; ++k)
      if (std::abs(e[k]) > std::abs(e[big]) + 1e-12) big = k;
    if (e[big] < 0) e = {-e[0], -e[1], -e[2]};
    axes[c] = unit(e);
  }
  return axes;
}

// The camera axes of the wall view: u along the points' largest principal
// axis, w (towards the viewer) along the smallest, v = w x u.
Camera principal_camera(const std::vector<double>& points) {
  Camera cam;
  const size_t n = points.size() / 3;
  if (n == 0) return cam;
  V3 mean = {0, 0, 0};
  for (size_t i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) mean[size_t(k)] += points[3 * i + size_t(k)];
  for (double& m : mean) m /= double(n);
  double cov[3][3] = {};
  for (size_t i = 0; i < n; ++i) {
    const V3 d = sub(point(points, int32_t(i)), mean);
    for (int r = 0; r < 3; ++r)
      for (int s = 0; s < 3; ++s) cov[r][s] += d[size_t(r)] * d[size_t(s)];
  }
  const std::array<V3, 3> axes = principal_axes(cov);
  cam.u = axes[0];
  cam.w = axes[2];
  cam.v = unit(cross(cam.w, cam.u));
  return cam;
}

std::string length_text(double x) { return report_number(x, 3); }

// ---- The cut --------------------------------------------------------------

// The polygons where the cells meet the plane, in plane coordinates (u, v).
struct Cut {
  std::vector<double> uv;       // 2 per corner
  std::vector<uint32_t> first;  // polygon k: corners [first[k], first[k + 1])
  std::vector<uint8_t> part;    // per polygon
  size_t per_part[3] = {0, 0, 0};
  double u0 = 1e300, u1 = -1e300, v0 = 1e300, v1 = -1e300;
  size_t size() const { return part.size(); }
};

// Adds the section of the convex cell with corners `corner[0..n)` (indices
// into points) and edges `edges` by the plane (p - origin) . w = 0: the
// points where its edges cross, ordered around their centre.
void cut_cell(const std::vector<double>& points, const int32_t* corner, int n,
              const int (*edges)[2], int nedges, const Camera& cam, const V3& origin, uint8_t part,
              Cut& cut) {
  double d[6];
  bool above = false, below = false;
  for (int i = 0; i < n; ++i) {
    d[i] = dot(sub(point(points, corner[i]), origin), cam.w);
    (d[i] >= 0 ? above : below) = true;
  }
  if (!above || !below) return;
  double pu[9], pv[9];
  int m = 0;
  for (int e = 0; e < nedges; ++e) {
    const int a = edges[e][0], b = edges[e][1];
    if ((d[a] >= 0) == (d[b] >= 0)) continue;
    const double t = d[a] / (d[a] - d[b]);
    const V3 pa = point(points, corner[a]), pb = point(points, corner[b]);
    const V3 p = {pa[0] + t * (pb[0] - pa[0]), pa[1] + t * (pb[1] - pa[1]),
                  pa[2] + t * (pb[2] - pa[2])};
    pu[m] = dot(p, cam.u);
    pv[m] = dot(p, cam.v);
    ++m;
  }
  if (m < 3) return;
  double cu = 0, cv = 0;
  for (int i = 0; i < m; ++i) cu += pu[i], cv += pv[i];
  cu /= m, cv /= m;
  int order[9];
  double angle[9];
  for (int i = 0; i < m; ++i) order[i] = i, angle[i] = std::atan2(pv[i] - cv, pu[i] - cu);
  std::sort(order, order + m, [&](int a, int b) { return angle[a] < angle[b]; });
  if (cut.first.empty()) cut.first.push_back(0);
  for (int i = 0; i < m; ++i) {
    const double u = pu[order[i]], v = pv[order[i]];
    cut.uv.push_back(u);
    cut.uv.push_back(v);
    cut.u0 = std::min(cut.u0, u), cut.u1 = std::max(cut.u1, u);
    cut.v0 = std::min(cut.v0, v), cut.v1 = std::max(cut.v1, v);
  }
  cut.first.push_back(uint32_t(cut.uv.size() / 2));
  cut.part.push_back(part);
  ++cut.per_part[part];
}

Cut cut_volume(const MeshJobResult& r, const Camera& cam, const V3& origin) {
  static constexpr int kTetEdges[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  static constexpr int kPrismEdges[9][2] = {{0, 1}, {1, 2}, {2, 0}, {3, 4}, {4, 5},
                                            {5, 3}, {0, 3}, {1, 4}, {2, 5}};
  const VolumeMesh& m = r.volume;
  Cut cut;
  for (size_t t = 0; t < m.num_tets(); ++t) {
    const uint8_t part = t < r.tet_part.size() ? std::min<uint8_t>(r.tet_part[t], 2) : 0;
    cut_cell(m.points, &m.tets[4 * t], 4, kTetEdges, 6, cam, origin, part, cut);
  }
  for (size_t p = 0; p < m.num_prisms(); ++p) {
    const bool wall = p < m.prism_region.size() && m.prism_region[p] == 2;
    cut_cell(m.points, &m.prisms[6 * p], 6, kPrismEdges, 9, cam, origin, wall ? 2 : 1, cut);
  }
  return cut;
}

// Draws the cut's polygons that reach into the canvas.
void draw_cut(Canvas& c, const Cut& cut, const Camera& cam, double edge_strength) {
  double xy[9][2];
  for (size_t k = 0; k < cut.size(); ++k) {
    const int n = int(cut.first[k + 1] - cut.first[k]);
    bool left = true, right = true, up = true, down = true;
    for (int i = 0; i < n; ++i) {
      const double* p = &cut.uv[2 * (cut.first[k] + size_t(i))];
      xy[i][0] = cam.x(p[0]);
      xy[i][1] = cam.y(p[1]);
      left &= xy[i][0]<0, right &= xy[i][0]> c.width;
      up &= xy[i][1]<0, down &= xy[i][1]> c.height;
    }
    if (left || right || up || down) continue;
    fill_polygon(c, xy, nullptr, n, kPartColour[cut.part[k]], edge_strength);
  }
}

// ---- The views ------------------------------------------------------------

RgbImage render_wall(const SurfaceMesh& s, const Camera& axes, int width, int height,
                     std::array<double, 3>& extent) {
  Canvas c(width * kSuper, height * kSuper);
  Camera cam = axes;
  double u0 = 1e300, u1 = -1e300, v0 = 1e300, v1 = -1e300, w0 = 1e300, w1 = -1e300;
  const size_t nv = s.points.size() / 3;
  std::vector<double> sx(nv), sy(nv), sz(nv);
  for (size_t i = 0; i < nv; ++i) {
    const V3 p = point(s.points, int32_t(i));
    const double pu = dot(p, cam.u), pv = dot(p, cam.v), pw = dot(p, cam.w);
    u0 = std::min(u0, pu), u1 = std::max(u1, pu);
    v0 = std::min(v0, pv), v1 = std::max(v1, pv);
    w0 = std::min(w0, pw), w1 = std::max(w1, pw);
    sz[i] = pw;
  }
  extent = {nv ? u1 - u0 : 0, nv ? v1 - v0 : 0, nv ? w1 - w0 : 0};
  if (nv == 0) return downsample(c);
  fit(cam, u0, u1, v0, v1, c.width, c.height, 0.05);
  for (size_t i = 0; i < nv; ++i) {
    const V3 p = point(s.points, int32_t(i));
    sx[i] = cam.x(dot(p, cam.u));
    sy[i] = cam.y(dot(p, cam.v));
  }
  // Light from the upper left, in front.
  const V3 light = unit({-0.35 * cam.u[0] + 0.55 * cam.v[0] + cam.w[0],
                         -0.35 * cam.u[1] + 0.55 * cam.v[1] + cam.w[1],
                         -0.35 * cam.u[2] + 0.55 * cam.v[2] + cam.w[2]});
  double xy[3][2], z[3];
  for (size_t t = 0; t < s.triangles.size() / 3; ++t) {
    const int32_t* tv = &s.triangles[3 * t];
    const V3 a = point(s.points, tv[0]), b = point(s.points, tv[1]), cc = point(s.points, tv[2]);
    const V3 n = unit(cross(sub(b, a), sub(cc, a)));
    const bool front = dot(n, cam.w) >= 0;
    const double shade = 0.38 + 0.62 * std::abs(dot(n, light));
    const Rgb& base = front ? kWallFront : kWallBack;
    Rgb colour;
    for (int k = 0; k < 3; ++k) colour[k] = uint8_t(std::min(255.0, base[k] * shade + 0.5));
    for (int k = 0; k < 3; ++k) {
      xy[k][0] = sx[size_t(tv[k])];
      xy[k][1] = sy[size_t(tv[k])];
      z[k] = sz[size_t(tv[k])];
    }
    fill_polygon(c, xy, z, 3, colour, 0.75);
  }
  return downsample(c);
}

// The place of the close-up: a point where the cut meets the lumen wall
// (output_surface) and the direction into the lumen there, in plane
// coordinates, and the local viscous layer thickness (0: none found).
struct WallPlace {
  bool found = false;
  double u = 0, v = 0, inward_u = 0, inward_v = 0, layer = 0;
};

WallPlace find_wall_place(const MeshJobResult& r, const Cut& cut, const Camera& cam,
                          const V3& origin) {
  WallPlace best;
  const SurfaceMesh& s = r.output_surface;
  const double cu = 0.5 * (cut.u0 + cut.u1), cv = 0.5 * (cut.v0 + cut.v1);
  // Openings: the close-up avoids the caps' corners.
  std::vector<std::array<double, 3>> opening;  // u, v, radius
  for (const Opening& o : r.surface.topology.openings) {
    const V3 p = {o.centroid[0], o.centroid[1], o.centroid[2]};
    opening.push_back({dot(p, cam.u), dot(p, cam.v), o.radius});
  }
  double best_score = 1e300;
  for (size_t t = 0; t < s.triangles.size() / 3; ++t) {
    const int32_t* tv = &s.triangles[3 * t];
    double d[3];
    V3 p[3];
    for (int k = 0; k < 3; ++k) {
      p[k] = point(s.points, tv[k]);
      d[k] = dot(sub(p[k], origin), cam.w);
    }
    // The midpoint of the segment where the triangle crosses the plane.
    double su = 0, sv = 0;
    int m = 0;
    for (int k = 0; k < 3; ++k) {
      const int l = (k + 1) % 3;
      if ((d[k] >= 0) == (d[l] >= 0)) continue;
      const double f = d[k] / (d[k] - d[l]);
      const V3 q = {p[k][0] + f * (p[l][0] - p[k][0]), p[k][1] + f * (p[l][1] - p[k][1]),
                    p[k][2] + f * (p[l][2] - p[k][2])};
      su += dot(q, cam.u), sv += dot(q, cam.v), ++m;
    }
    if (m != 2) continue;
    su /= 2, sv /= 2;
    double near_opening = 0;
    for (const auto& o : opening)
      if (std::hypot(su - o[0], sv - o[1]) < 2 * o[2]) near_opening = 1;
    // Nearest the cut's centre along u, then the wall above it; away from
    // the openings.
    const double score = std::abs(su - cu) + 0.25 * std::abs(sv - cv) + 1e9 * near_opening;
    if (score < best_score) {
      best_score = score;
      best.found = true;
      best.u = su, best.v = sv;
      // The inward direction: the triangle's outward normal, in the plane,
      // reversed.
      const V3 n = unit(cross(sub(p[1], p[0]), sub(p[2], p[0])));
      const double nu = -dot(n, cam.u), nv = -dot(n, cam.v), len = std::hypot(nu, nv);
      best.inward_u = len > 0 ? nu / len : 0;
      best.inward_v = len > 0 ? nv / len : 0;
    }
  }
  if (!best.found) return best;
  // The layer's local thickness: the distance from the wall point to the
  // nearest corner of a core polygon, if there is a layer.
  if (cut.per_part[1] > 0) {
    double nearest = 1e300;
    for (size_t k = 0; k < cut.size(); ++k) {
      if (cut.part[k] != 0) continue;
      for (uint32_t i = cut.first[k]; i < cut.first[k + 1]; ++i)
        nearest = std::min(nearest, std::hypot(cut.uv[2 * i] - best.u, cut.uv[2 * i + 1] - best.v));
    }
    if (nearest < 1e300) best.layer = nearest;
  }
  return best;
}

std::string parts_text(const Cut& cut) {
  static const char* const names[3] = {"core", "boundary layer", "vessel wall"};
  std::string out;
  for (int p = 0; p < 3; ++p) {
    if (cut.per_part[p] == 0) continue;
    if (!out.empty()) out += ", ";
    out += std::string(names[p]) + " " + kPartColourName[p] + " (" + report_count(cut.per_part[p]) +
           ")";
  }
  return out;
}

}  // namespace

std::string encode_png(const RgbImage& image) {
  const size_t w = size_t(std::max(image.width, 0)), h = size_t(std::max(image.height, 0));
  const size_t stride = 3 * w;
  // Filtered rows: per row the filter (none, sub, up, average, Paeth) whose
  // bytes, taken as signed, have the smallest sum of magnitudes.
  std::string raw;
  raw.reserve(h * (stride + 1));
  std::vector<uint8_t> zero(stride, 0), trial[5];
  for (auto& t : trial) t.resize(stride);
  for (size_t y = 0; y < h; ++y) {
    const uint8_t* row = &image.rgb[y * stride];
    const uint8_t* prev = y > 0 ? &image.rgb[(y - 1) * stride] : zero.data();
    long best_cost = -1;
    int best = 0;
    for (int f = 0; f < 5; ++f) {
      long cost = 0;
      for (size_t i = 0; i < stride; ++i) {
        const int a = i >= 3 ? row[i - 3] : 0, b = prev[i], c = i >= 3 ? prev[i - 3] : 0;
        const int pred = f == 0   ? 0
                         : f == 1 ? a
                         : f == 2 ? b
                         : f == 3 ? (a + b) / 2
                                  : paeth(a, b, c);
        const uint8_t out = uint8_t(row[i] - pred);
        trial[f][i] = out;
        cost += std::abs(int(int8_t(out)));
      }
      if (best_cost < 0 || cost < best_cost) best_cost = cost, best = f;
    }
    raw.push_back(char(best));
    raw.append(reinterpret_cast<const char*>(trial[best].data()), stride);
  }
  uLongf packed_size = compressBound(uLong(raw.size()));
  std::string packed(packed_size, '\0');
  compress2(reinterpret_cast<Bytef*>(packed.data()), &packed_size,
            reinterpret_cast<const Bytef*>(raw.data()), uLong(raw.size()), 6);
  packed.resize(packed_size);

  std::string png("\x89PNG\r\n\x1a\n", 8);
  std::string ihdr;
  put_u32(ihdr, uint32_t(w));
  put_u32(ihdr, uint32_t(h));
  ihdr += std::string("\x08\x02\x00\x00\x00", 5);  // 8 bits, RGB, deflate, no interlace
  put_chunk(png, "IHDR", ihdr);
  put_chunk(png, "IDAT", packed);
  put_chunk(png, "IEND", "");
  return png;
}

std::vector<ReportImage> render_report_views(const MeshJobResult& result, int width, int height) {
  width = std::max(width, 16);
  height = std::max(height, 16);
  std::vector<ReportImage> views;
  const SurfaceMesh& wall = result.output_surface;
  const std::string unit(unit_symbol(result.surface.unit.unit));
  const Camera axes = principal_camera(wall.points);

  // (1) The wall.
  std::array<double, 3> extent{};
  RgbImage img = render_wall(wall, axes, width, height, extent);
  ReportImage w;
  w.title = "Wall mesh";
  w.alt = "Wall mesh: " + report_count(wall.num_triangles()) + " triangles on " +
          report_count(wall.num_vertices()) +
          " vertices, shaded, seen across its smallest extent (" + length_text(extent[0]) + " by " +
          length_text(extent[1]) + " " + unit + " in the picture, " + length_text(extent[2]) + " " +
          unit + " deep)";
  w.png = encode_png(img);
  views.push_back(std::move(w));
  if (result.volume.tets.empty() && result.volume.prisms.empty()) return views;

  // (2) The cut: the plane through the lumen's bounding-box centre that
  // holds the longest axis and faces the viewer of (1).
  V3 lo = {1e300, 1e300, 1e300}, hi = {-1e300, -1e300, -1e300};
  for (size_t i = 0; i < wall.points.size(); ++i)
    lo[i % 3] = std::min(lo[i % 3], wall.points[i]),
           hi[i % 3] = std::max(hi[i % 3], wall.points[i]);
  const V3 origin = {0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), 0.5 * (lo[2] + hi[2])};
  const Cut cut = cut_volume(result, axes, origin);
  if (cut.size() == 0) return views;
  Canvas c(width * kSuper, height * kSuper);
  Camera cam = axes;
  fit(cam, cut.u0, cut.u1, cut.v0, cut.v1, c.width, c.height, 0.05);
  draw_cut(c, cut, cam, 0.85);
  const WallPlace place = find_wall_place(result, cut, axes, origin);
  // The close-up's square: about 3.5 layer thicknesses (the layer, a little
  // outside it and the core beyond), else an eighth of the view.
  const double view = std::max(cut.u1 - cut.u0, cut.v1 - cut.v0);
  double side = view / 8, centre_u = place.u, centre_v = place.v;
  if (place.found && place.layer > 0) {
    side = std::clamp(3.5 * place.layer, view / 200, view / 3);
    // Shifted into the lumen, less when a vessel wall lies outside.
    const double shift = (cut.per_part[2] > 0 ? 0.1 : 0.35) * side;
    centre_u += place.inward_u * shift;
    centre_v += place.inward_v * shift;
  }
  const bool close_up = place.found;
  if (close_up) {
    const double h = 0.5 * side;
    draw_box(c, cam.x(centre_u - h), cam.y(centre_v + h), cam.x(centre_u + h), cam.y(centre_v - h),
             2 * kSuper, kFrame);
  }
  ReportImage cv;
  cv.title = "Cut through the volume mesh";
  cv.alt =
      "Cut through the volume mesh by the plane through the lumen's centre along its "
      "longest extent: " +
      report_count(cut.size()) + " elements cut (" + parts_text(cut) + "), element sides dark" +
      (close_up ? "; a green square marks the close-up" : "");
  cv.png = encode_png(downsample(c));
  views.push_back(std::move(cv));
  if (!close_up) return views;

  // (3) The close-up.
  Canvas z(width * kSuper, height * kSuper);
  Camera zc = axes;
  const double h = 0.5 * side;
  fit(zc, centre_u - h, centre_u + h, centre_v - h, centre_v + h, z.width, z.height, 0.02);
  draw_cut(z, cut, zc, 0.9);
  ReportImage zv;
  zv.title = "Boundary layer close-up";
  const int layers = result.volume_stats.viscous_layers;
  zv.alt = "Close-up of the cut where it meets the wall, a square of " + length_text(side) + " " +
           unit + ": " +
           (layers > 0 ? "the " + std::to_string(layers) + " boundary layers (orange, about " +
                             length_text(place.layer) + " " + unit +
                             " thick) between the wall and the core (light blue)"
                       : std::string("the core's elements at the wall (no boundary layer)")) +
           (cut.per_part[2] ? ", the vessel wall (purple) outside" : "");
  zv.png = encode_png(downsample(z));
  views.push_back(std::move(zv));
  return views;
}

}  // namespace vm
