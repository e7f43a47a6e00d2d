// Replays the reader inputs kept in tests/fuzz/regressions/readers/ (found
// by scripts/fuzz.sh, or hostile inputs written by hand) through the same
// check as the fuzz target: a value or an error, never a crash (ASan/UBSan
// in the sanitized build) and never a malformed surface. A file whose name
// contains ".ok." must also be read.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include "tests/fuzz/check_surface.h"

namespace vm {
namespace {

TEST(FuzzRegressions, KeptReaderInputsAreReadOrRefusedCleanly) {
  const std::filesystem::path dir =
      std::filesystem::path(VM_SOURCE_DIR) / "tests/fuzz/regressions/readers";
  size_t files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    std::ifstream in(entry.path(), std::ios::binary);
    const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                                     std::istreambuf_iterator<char>());
    const bool read = fuzz::read_and_check(bytes);
    if (entry.path().filename().string().find(".ok.") != std::string::npos) {
      EXPECT_TRUE(read) << entry.path();
    }
    ++files;
  }
  EXPECT_GT(files, 0u);
}

}  // namespace
}  // namespace vm
