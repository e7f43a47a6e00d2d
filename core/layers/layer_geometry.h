// Small geometry helpers shared by the boundary-layer phases (Marchandise et
// al., section 2.2): the core's vectors and vertex 1-rings, by their short names.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/geom/vec3.h"
#include "core/mesh/adjacency.h"
#include "core/mesh/surface_mesh.h"

namespace vm::layers {

// The vector helpers are the core's (vm::Vec3, core/geom/vec3.h).
using vm::Vec3;

// The vertex 1-rings are the mesh module's (vm::VertexRings, core/mesh/adjacency.h).
using vm::vertex_rings;
using vm::VertexRings;

}  // namespace vm::layers
