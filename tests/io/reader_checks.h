// Checks shared by the tests of the surface readers: a message that holds
// a phrase (EXPECT_HAS), the message of an input that must fail, and damaged inputs (truncated,
// corrupted) that must be answered with a result or a message, never a crash (the sanitizer build
// runs the tests).
#pragma once

#include <gtest/gtest.h>

#include <cstddef>
#include <string>

#include "tests/io/surface_writers.h"
#include "tests/support/expect_has.h"

namespace vm::testing {

/// read(bytes of `text`) gives a result, or an error with a message.
template <class Read>
void expect_answered(const Read& read, const std::string& text) {
  auto r = read(to_bytes(text));
  if (!r.ok()) {
    EXPECT_FALSE(r.message().empty());
  }
}

/// The message of read(bytes of `text`), which must fail (empty if it did not).
template <class Read>
std::string error_of(const Read& read, const std::string& text) {
  auto r = read(to_bytes(text));
  EXPECT_FALSE(r.ok());
  return r.message();
}

/// The same for every prefix of `text` whose length is a multiple of `step`.
template <class Read>
void expect_prefixes_answered(const Read& read, const std::string& text, size_t step) {
  for (size_t n = 0; n < text.size(); n += step) expect_answered(read, text.substr(0, n));
}

/// The same for `text` with one byte changed to change(byte), at every
/// position that is a multiple of `step`.
template <class Read, class Change>
void expect_changes_answered(const Read& read, const std::string& text, size_t step,
                             const Change& change) {
  for (size_t i = 0; i < text.size(); i += step) {
    std::string t = text;
    t[i] = change(t[i]);
    expect_answered(read, t);
  }
}

}  // namespace vm::testing
