// Closest point on a triangle (Ericson, "Real-Time Collision Detection",
// 2005, section 5.1.5), for projecting points back onto the input surface.
#pragma once

namespace vm {

/// Writes to `out` (3 doubles) the point of triangle (a, b, c) closest to p
/// and returns the squared distance. For a degenerate (zero-area) triangle
/// the point returned lies on it but may not be the closest.
double closest_point_on_triangle(const double* p, const double* a, const double* b, const double* c,
                                 double* out);

}  // namespace vm
