// The version of vesselmesh, shown by every interface and written into the
// provenance of every output file.
#pragma once

namespace vm {

inline constexpr const char* kVersion = "0.1.0";

}  // namespace vm
