// Remeshing options shared by the unit tests.
#pragma once

#include "core/surface/remesh_surface.h"

namespace vm::testing {

/// Default remeshing options at the uniform size h (model units).
inline RemeshOptions uniform_remesh(double h) {
  RemeshOptions o;
  o.size.mode = SizeMode::kUniform;
  o.size.size = h;
  return o;
}

}  // namespace vm::testing
