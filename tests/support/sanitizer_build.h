#pragma once
// What a test may do differently in CI's sanitizer builds (RC_SANITIZE set;
// .ci/run's sanitize and tsan stages), where every check costs 4-10x its
// Release time and the stage must fit CI's budget (docs/robustness.md, "CI
// stage times"). The sanitizers' job is to run every code path under
// ASan+UBSan; the Release stage keeps the statistical weight. Two tools:
//  - FullOrUnderSanitizer(full, reduced): a test that repeats one check over
//    many instances (scenarios, random pairs, seeds) runs fewer of them. Every
//    instance still runs its whole code path and is checked the same way.
//  - RC_RELEASE_ONLY(why): a long accuracy regression (one filter run over
//    hundreds of records) whose code paths shorter tests already run under
//    the sanitizer is skipped there, with `why` naming those tests. ctest
//    reports it as skipped, never as passed.
#include <gtest/gtest.h>

namespace rc::test {

#ifdef RC_SANITIZED_TESTS
inline constexpr bool kSanitizerBuild = true;
#else
inline constexpr bool kSanitizerBuild = false;
#endif

// `full` in a Release build, `reduced` in a sanitizer build.
template <class T>
constexpr T FullOrUnderSanitizer(T full, T reduced) {
  return kSanitizerBuild ? reduced : full;
}

}  // namespace rc::test

#define RC_RELEASE_ONLY(why)                                                                   \
  do {                                                                                         \
    if (::rc::test::kSanitizerBuild)                                                           \
      GTEST_SKIP() << "a Release-only accuracy regression (tests/support/sanitizer_build.h); " \
                   << "under the sanitizer its code runs in " << why;                          \
  } while (0)
