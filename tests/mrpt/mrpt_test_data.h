#pragma once
// MRPT's example datasets (Debian: mrpt-common). Tests that need them skip
// with a clear message when they are not installed.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

namespace rc::test {

inline std::string MrptDatasetPath(const std::string& name) { return "/usr/share/mrpt/datasets/" + name; }

}  // namespace rc::test

#define RC_REQUIRE_MRPT_DATASET(name)                                              \
  do {                                                                             \
    if (!std::filesystem::exists(::rc::test::MrptDatasetPath(name)))               \
      GTEST_SKIP() << "MRPT dataset absent: " << ::rc::test::MrptDatasetPath(name) \
                   << " (install mrpt-common, see scripts/setup)";                 \
  } while (0)
