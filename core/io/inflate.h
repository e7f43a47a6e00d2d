// zlib (RFC 1950) and gzip (RFC 1952) decompression with a hard limit on the
// output size, using the zlib library (never a hand-written inflate).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/util/result.h"

namespace vm {

/// Decompresses one zlib stream. Output larger than `max_output` bytes is
/// refused ("decompressed data exceeds the limit of N bytes (compression
/// ratio over R): refused") without allocating beyond the limit. Errors: a
/// corrupt stream (zlib's message and the compressed byte offset), a stream
/// that ends early. Bytes after the end of the stream are ignored.
Result<std::vector<uint8_t>> inflate_zlib(std::span<const uint8_t> in, size_t max_output);

/// Decompresses gzip data: one member or several concatenated (as `cat
/// a.gz b.gz` makes), each checked against its CRC. Same limit and errors as
/// inflate_zlib. Trailing bytes that do not start another member (e.g. zero
/// padding) are ignored with a note in `warnings` when given.
Result<std::vector<uint8_t>> inflate_gzip(std::span<const uint8_t> in, size_t max_output,
                                          std::vector<std::string>* warnings = nullptr);

/// The first min(n, whole size) bytes of what inflate_gzip gives for `in`
/// (members read in order), inflating no further: a format is told from a
/// stream's start without inflating the whole. Errors: those of inflate_gzip
/// met within that part (a member's CRC is checked only when its end is
/// within it); never the limit's.
Result<std::vector<uint8_t>> inflate_gzip_prefix(std::span<const uint8_t> in, size_t n);

/// Decompresses one zlib stream into exactly out.size() bytes (a block of a
/// VTK XML array, whose uncompressed size the block header gives). Errors: a
/// corrupt stream, or a stream that gives fewer or more bytes than out.size().
Status inflate_zlib_exact(std::span<const uint8_t> in, std::span<uint8_t> out);

}  // namespace vm
