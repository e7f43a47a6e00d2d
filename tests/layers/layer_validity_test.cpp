#include "core/layers/layer_validity.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>

namespace vm {
namespace {

/// One wall triangle in z = 0 (layer side +z), its columns along the given
/// directions (unit, 3 per corner), `height` tall.
struct OneColumn {
  SurfaceMesh wall;
  LayerDirections dirs;
  std::vector<double> requested;
  OneColumn(std::vector<double> directions, double height) {
    wall.points = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    wall.triangles = {0, 1, 2};
    dirs.direction = std::move(directions);
    dirs.normal = {0, 0, 1, 0, 0, 1, 0, 0, 1};
    dirs.triangle_normal = {0, 0, 1};
    requested = {height, height, height};
  }
  double score(const std::vector<double>& fractions, std::array<double, 3> f) const {
    const LayerValidity v(wall, dirs, requested, fractions, /*outward=*/true, 0.05, 0);
    return v.score(0, f.data());
  }
};

TEST(LayerValidity, FacesBetweenStackedPrismsMayNotLeanFarFromTheColumn) {
  // Straight columns, corner 2's twenty times shorter (a thinned corner next
  // to full ones): the face between two layers slopes down to it, 67
  // degrees from the columns at the middle, though every prism is sound.
  const OneColumn c({0, 0, 1, 0, 0, 1, 0, 0, 1}, 5.0);
  EXPECT_GE(c.score({0, 1}, {1, 1, 0.05}), 1.0);  // one layer: no face between prisms
  EXPECT_LT(c.score({0, 0.5, 1}, {1, 1, 0.05}), 1.0);
  EXPECT_GE(c.score({0, 0.5, 1}, {0.1, 0.1, 0.05}), 1.0);  // lower: the faces follow the wall
}

TEST(LayerValidity, AWallThatLeansItselfIsNotRefusedForIt) {
  // A sheared column (all corners along one direction 70 degrees from the
  // normal): the faces lean as the wall does, which no thinning can mend.
  const double a = 70.0 * M_PI / 180;
  const double x = std::sin(a), z = std::cos(a);
  const OneColumn c({x, 0, z, x, 0, z, x, 0, z}, 0.1);
  EXPECT_GE(c.score({0, 0.25, 0.5, 0.75, 1}, {1, 1, 1}), 1.0);
}

}  // namespace
}  // namespace vm
