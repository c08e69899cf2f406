// The exit-code table, the memory cap, the parse allocation budget and
// AtomicFile's folders: the pieces every subcommand's error handling and
// output writing stands on.
#include <filesystem>
#include <fstream>
#include <new>
#include <sstream>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "common/allocation_budget.h"
#include "common/atomic_file.h"
#include "common/cpu_features.h"
#include "common/exit_codes.h"
#include "common/input_error.h"
#include "common/memory_cap.h"
#include "maps/grid_size_limits.h"
#include "support/input_error_expectations.h"
#include "support/simd_levels.h"
#include "support/temp_dir.h"

namespace rc {
namespace {

ExitCode CodeFor(const std::exception_ptr& e, std::string* message = nullptr) {
  std::ostringstream err;
  const ExitCode code = ReportException(e, err);
  if (message) *message = err.str();
  return code;
}

// The SIMD level in use starts at the CPU's widest, may be lowered to any
// level the CPU runs and raised back, and refuses one it does not run.
TEST(SimdLevels, LimitLowersTheFormsInUseAndRefusesWhatTheCpuLacks) {
  EXPECT_EQ(SimdInUse(), CpuSimdLevel());
  EXPECT_EQ(UseAvx512(), CpuHasAvx512() && CpuHasAvx2());
  EXPECT_EQ(UseAvx2(), CpuHasAvx2());
  for (SimdLevel level : test::SimdLevelsThisCpuRuns()) {
    const test::ScopedSimdLimit limit(level);
    EXPECT_EQ(SimdInUse(), level);
    EXPECT_EQ(UseAvx512(), level == SimdLevel::kAvx512);
    EXPECT_EQ(UseAvx2(), level != SimdLevel::kScalar);
  }
  EXPECT_EQ(SimdInUse(), CpuSimdLevel());
  if (CpuSimdLevel() != SimdLevel::kAvx512) {
    EXPECT_THROW(LimitSimd(SimdLevel::kAvx512), std::invalid_argument);
  }
  SimdLevel parsed = SimdLevel::kScalar;
  for (SimdLevel level : {SimdLevel::kScalar, SimdLevel::kAvx2, SimdLevel::kAvx512}) {
    EXPECT_TRUE(ParseSimdLevel(ToString(level), &parsed));
    EXPECT_EQ(parsed, level);
  }
  EXPECT_FALSE(ParseSimdLevel("sse2", &parsed));
  EXPECT_FALSE(ParseSimdLevel("AVX2", &parsed));
}

TEST(ExitCodes, OneTableForEveryError) {
  EXPECT_EQ(CodeFor(std::make_exception_ptr(UsageError("--particles must be positive"))), ExitCode::kUsage);
  std::string message;
  EXPECT_EQ(CodeFor(std::make_exception_ptr(InputError("m.dat", 3, "resolution", "must be positive")), &message),
            ExitCode::kInputError);
  EXPECT_EQ(message, "rcbench: error: m.dat:3: field 'resolution': must be positive\n");
  EXPECT_EQ(CodeFor(std::make_exception_ptr(OutputError("out/t.csv", "cannot open"))), ExitCode::kInputError);
  // Anything else is a bug, never reported as the user's bad input.
  EXPECT_EQ(CodeFor(std::make_exception_ptr(std::logic_error("a row built for another table")), &message),
            ExitCode::kInternalError);
  EXPECT_NE(message.find("internal error"), std::string::npos);
  EXPECT_EQ(CodeFor(std::make_exception_ptr(std::bad_alloc())), ExitCode::kInternalError);
  EXPECT_EQ(ToInt(ExitCode::kSuccess), 0);
  EXPECT_EQ(ToInt(ExitCode::kInputError), 1);
  EXPECT_EQ(ToInt(ExitCode::kUsage), 2);
  EXPECT_EQ(ToInt(ExitCode::kNoPath), 3);
  EXPECT_EQ(ToInt(ExitCode::kInternalError), 4);
  EXPECT_EQ(ExitCodeFooter("").find(" 3 "), std::string::npos);
  EXPECT_NE(ExitCodeFooter("no path").find(" 3 no path;"), std::string::npos);
}

TEST(MemoryCap, MapSizeIsCheckedAgainstItBeforeAllocation) {
  const std::uint64_t saved = MemoryCapBytes();
  SetMemoryCapBytes(1 << 20);
  EXPECT_NO_THROW(CheckMapSize("m.dat", 2, "size", 1000, 1000));  // 1 MB of cells... just under
  const InputError e = test::InputErrorFrom([] { CheckMapSize("m.dat", 2, "size", 2000, 2000); });
  EXPECT_EQ(e.line(), 2);
  EXPECT_NE(std::string(e.what()).find("2000 x 2000 cells needs 3.8 MiB"), std::string::npos) << e.what();
  EXPECT_NE(std::string(e.what()).find("memory cap of 1.0 MiB"), std::string::npos) << e.what();
  SetMemoryCapBytes(saved);
  EXPECT_EQ(BytesFor(UINT64_MAX / 2, 4), UINT64_MAX);  // saturates, never wraps
}

TEST(AllocationBudget, RefusesTheRequestThatPassesItAndOnlyOnItsThread) {
  {
    AllocationBudget budget(1 << 20);
    std::vector<char> small(1000);
    EXPECT_THROW(std::vector<char>(2 << 20), std::bad_alloc);
    EXPECT_TRUE(budget.exceeded());
  }
  std::vector<char> after(4 << 20);  // no budget: unlimited again
  EXPECT_EQ(after.size(), 4u << 20);
  EXPECT_GE(ParseBudgetBytes(1000), kParseBaseBytes);
}

// A parser that turns the refusal into its own exception (as MRPT does)
// still ends as AllocationBudgetExceeded, raised after the budget ended, so
// the caller can allocate its message (a tests/fuzz finding: building it
// inside the exhausted budget threw again and terminated the process).
TEST(AllocationBudget, ParseWithinBudgetReportsTheRefusalAfterTheBudget) {
  auto parser = [] {
    try {
      std::vector<double> huge(1u << 28);
    } catch (const std::bad_alloc&) {
      throw std::runtime_error("the parser's own message");
    }
  };
  try {
    ParseWithinBudget(1 << 20, parser);
    ADD_FAILURE() << "no AllocationBudgetExceeded";
  } catch (const AllocationBudgetExceeded& e) {
    const std::string message = "corrupt archive: over " + std::to_string(e.budget_bytes()) + " bytes";
    EXPECT_EQ(e.budget_bytes(), 1u << 20);
    EXPECT_FALSE(message.empty());
  }
  EXPECT_THROW(ParseWithinBudget(1 << 20, [] { throw std::invalid_argument("own"); }), std::invalid_argument);
  EXPECT_NO_THROW(ParseWithinBudget(1 << 20, [] { std::vector<char> small(100); }));
}

TEST(AtomicFile, CreatesFoldersAndLeavesNothingWithoutCommit) {
  const test::TempDir dir;
  const std::string path = dir.Path("a/b/out.json");
  {
    AtomicFile file(path);
    file.stream() << "{}";
  }
  EXPECT_FALSE(std::filesystem::exists(path));
  {
    AtomicFile file(path);
    file.stream() << "{}";
    file.Commit();
  }
  EXPECT_TRUE(std::filesystem::exists(path));
  EXPECT_THROW(AtomicFile("/proc/rc_no_such_folder/out.json"), OutputError);
}

}  // namespace
}  // namespace rc
