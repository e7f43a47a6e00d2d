// Elementary functions that give the same bits in every build.
//
// The C library's sin, cos, atan2, hypot, cbrt, ... differ in their last
// bits between glibc (the native build) and musl (Emscripten's, the
// WebAssembly build), and one flipped bit early in the pipeline changes the
// mesh (a point lands on the other side of a Delaunay test). These use only
// IEEE-754 +, -, *, / and sqrt, which round the same everywhere (the build
// turns floating-point contraction off): argument reduction, then a short
// Taylor series. Accuracy: within about 2 ulp of the true value; the core
// uses them wherever a result reaches the mesh. See docs/ARCHITECTURE.md,
// "Determinism".
#pragma once

namespace vm::pm {

/// sin and cos of x (radians). Exact reduction for |x| < 2^19; beyond that
/// (no angle in the pipeline comes near) the C library's, not portable.
double sin(double x);
double cos(double x);
double tan(double x);
/// atan(x) in [-pi/2, pi/2]; atan2(y, x) in [-pi, pi] with the C library's
/// conventions for zeros and infinities of x and y.
double atan(double x);
double atan2(double y, double x);
/// asin, acos of x in [-1, 1] (NaN outside).
double asin(double x);
double acos(double x);
/// e^x, e^x - 1 (accurate near 0), 2^x (exact at integers).
double exp(double x);
double expm1(double x);
double exp2(double x);
/// Natural and base-2 logarithms (log2 is exact at powers of two); NaN for
/// x < 0, -infinity at 0.
double log(double x);
double log2(double x);
/// x^y for x > 0 (exp(y log x)); x^y of x = 0 is 0 for y > 0.
double pow(double x, double y);
/// Cube root, any sign.
double cbrt(double x);
/// sqrt(x^2 + y^2) without overflow or underflow in between.
double hypot(double x, double y);
double hypot(double x, double y, double z);

}  // namespace vm::pm
