// EXPECT_HAS(text, phrase): the text (an error message, a warning) holds the
// phrase; on failure the whole text is printed.
#pragma once

#include <gtest/gtest.h>

#include <cstddef>
#include <string>

#define EXPECT_HAS(haystack, needle) \
  EXPECT_NE((haystack).find(needle), std::string::npos) << (haystack)

namespace vm::testing {

/// How many times `phrase` occurs in `text` (overlaps counted).
inline size_t count_of(const std::string& text, const std::string& phrase) {
  size_t n = 0;
  for (size_t p = text.find(phrase); p != std::string::npos; p = text.find(phrase, p + 1)) ++n;
  return n;
}

}  // namespace vm::testing
