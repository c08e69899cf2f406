#pragma once
// Paths to the real data beside the project root (../shared/data). Tests that
// need it call RC_REQUIRE_SHARED_DATA(relative path) first, which skips the
// test with a clear message when the file is absent.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

namespace rc::test {

inline std::string SharedDataPath(const std::string& relative) {
  return std::string(RC_SHARED_DATA_DIR) + "/" + relative;
}

}  // namespace rc::test

#define RC_REQUIRE_SHARED_DATA(relative)                                             \
  do {                                                                               \
    if (!std::filesystem::exists(::rc::test::SharedDataPath(relative)))              \
      GTEST_SKIP() << "shared data absent: " << ::rc::test::SharedDataPath(relative) \
                   << " (expected ../shared/data beside the project root)";          \
  } while (0)
