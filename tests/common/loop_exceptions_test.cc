// LoopExceptions (common/loop_exceptions.h): iterations that throw inside an
// OpenMP loop do not end the process, and the caller gets the lowest
// throwing iteration's exception at any thread count.
#include "common/loop_exceptions.h"

#include <omp.h>

#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace rc {
namespace {

std::string FirstMessage(int threads) {
  constexpr int kIterations = 64;
  LoopExceptions exceptions(kIterations);
  std::vector<int> ran(kIterations, 0);
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1)
  for (int i = 0; i < kIterations; ++i)
    exceptions.Run(static_cast<std::size_t>(i), [&] {
      ran[i] = 1;
      if (i % 10 == 7) throw std::runtime_error("iteration " + std::to_string(i));
    });
  for (int i = 0; i < kIterations; ++i) EXPECT_EQ(ran[i], 1) << "a throw must not stop the other iterations";
  try {
    exceptions.RethrowFirst();
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "nothing thrown";
}

TEST(LoopExceptions, TheLowestThrowingIterationReachesTheCallerAtAnyThreadCount) {
  for (int threads : {1, 2, 4}) EXPECT_EQ(FirstMessage(threads), "iteration 7") << threads << " threads";
}

TEST(LoopExceptions, NothingIsThrownWhenNoIterationThrew) {
  LoopExceptions exceptions(3);
  for (std::size_t i = 0; i < 3; ++i) exceptions.Run(i, [] {});
  EXPECT_NO_THROW(exceptions.RethrowFirst());
}

}  // namespace
}  // namespace rc
