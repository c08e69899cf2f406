// UninitializedVector (common/uninitialized_vector.h): only a resize with no
// value skips initialization; every way of giving elements a value still
// gives it, for trivial types and for types with constructors.
#include "common/uninitialized_vector.h"

#include <cstdint>
#include <string>

#include <gtest/gtest.h>

namespace rc {
namespace {

TEST(UninitializedVector, ValuesGivenAreKept) {
  UninitializedVector<std::uint64_t> v(3, 7);
  v.push_back(8);
  v.resize(6, 9);
  EXPECT_EQ(v, (UninitializedVector<std::uint64_t>{7, 7, 7, 8, 9, 9}));
  v.assign(2, 5);
  EXPECT_EQ(v, (UninitializedVector<std::uint64_t>{5, 5}));
}

TEST(UninitializedVector, ResizeKeepsTheOldElementsAndLeavesRoomToWrite) {
  UninitializedVector<std::uint32_t> v{1, 2};
  v.resize(1000);
  ASSERT_EQ(v.size(), 1000u);
  EXPECT_EQ(v[0], 1u);
  EXPECT_EQ(v[1], 2u);
  for (std::size_t i = 2; i < v.size(); ++i) v[i] = static_cast<std::uint32_t>(i);
  EXPECT_EQ(v[999], 999u);
}

TEST(UninitializedVector, ClassTypesAreStillConstructed) {
  // Default-initialization of a class type runs its default constructor.
  UninitializedVector<std::string> v;
  v.resize(2);
  EXPECT_EQ(v[0], "");
  v.emplace_back(3, 'x');
  EXPECT_EQ(v[2], "xxx");
  UninitializedVector<std::string> copy = v;
  EXPECT_EQ(copy, v);
}

}  // namespace
}  // namespace rc
