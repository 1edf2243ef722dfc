// common/thinned.h: a bounded, evenly spaced sample of a stream (the snapshots' point lists).
#include "stitchsim/common/thinned.h"

#include <gtest/gtest.h>

namespace stitchsim {
namespace {

TEST(Thinned, KeepsEverythingUpToItsBoundThenEveryPowerOfTwo) {
  Thinned<int> few(8);
  for (int i = 0; i < 8; ++i) few.Add(i);
  EXPECT_EQ(few.Items(), (std::vector<int>{0, 1, 2, 3, 4, 5, 6, 7}));
  few.Add(8);  // over the bound: every other one from now on
  EXPECT_EQ(few.Items(), (std::vector<int>{0, 2, 4, 6, 8}));
  Thinned<int> many(1000);
  for (int i = 0; i < 100000; ++i) many.Add(i);
  const std::vector<int>& kept = many.Items();
  ASSERT_LE(kept.size(), 1000u);
  ASSERT_GE(kept.size(), 500u);
  EXPECT_EQ(kept.front(), 0);
  const int step = kept[1] - kept[0];  // a power of two, the same all along
  EXPECT_EQ(step & (step - 1), 0);
  for (std::size_t i = 1; i < kept.size(); ++i) EXPECT_EQ(kept[i] - kept[i - 1], step);
}

}  // namespace
}  // namespace stitchsim
