// EXPECT_HAS(text, phrase): the text (an error message, a warning) holds the
// phrase; on failure the whole text is printed.
#pragma once

#include <gtest/gtest.h>

#include <string>

#define EXPECT_HAS(haystack, needle) \
  EXPECT_NE((haystack).find(needle), std::string::npos) << (haystack)
