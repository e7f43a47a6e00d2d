// The open tube the output tests mesh, through the whole job.
#pragma once

#include <gtest/gtest.h>

#include <utility>

#include "core/io/stl.h"
#include "core/pipeline/mesh_job.h"
#include "tests/support/test_meshes.h"

namespace vm::testing {

/// open_tube(24, 8, 1.0, 4.0) meshed with `o` (read from a binary STL); an
/// empty result, with a test failure, on error.
inline MeshJobResult meshed_tube(const MeshJobOptions& o) {
  auto r = run_mesh_job(write_stl_binary(open_tube(24, 8, 1.0, 4.0)), o);
  EXPECT_TRUE(r.ok()) << r.message();
  return r.ok() ? std::move(r).value() : MeshJobResult{};
}

}  // namespace vm::testing
