// ZIP archive writer (PKWARE APPNOTE.TXT, version 2.0 features only: no
// ZIP64, no encryption): several output files as one download.
#pragma once

#include <vector>

#include "core/io/output_file.h"
#include "core/util/result.h"

namespace vm {

/// A ZIP archive of `files`, in their order: each entry DEFLATE-compressed
/// (raw deflate, zlib level 6) or stored when deflating does not shrink it,
/// with its CRC-32, a fixed DOS time (1980-01-01 00:00) so that the same
/// files give the same bytes, and the UTF-8 name flag; then the central
/// directory and the end record. Errors (no ZIP64): more than 65534 files, a
/// file or the archive reaching 4 GiB, a path that is empty, longer than
/// 65535 bytes, absolute, with a backslash, an empty, "." or ".." component,
/// or given twice.
Result<std::string> write_zip(const std::vector<OutputFile>& files);

}  // namespace vm
