// ExactSum (common/exact_sum.h), which adds the timed cycle time of a programme verified in
// chunks: the same bits in any order and any grouping, and the right value by a second route.
#include "stitchsim/common/exact_sum.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

namespace stitchsim {
namespace {

std::vector<double> Durations() {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> d(0.001, 2.0);
  std::vector<double> v(100000);
  for (double& x : v) x = d(rng);
  return v;
}

TEST(ExactSum, OrderAndGroupingDoNotChangeTheBits) {
  std::vector<double> v = Durations();
  ExactSum forward;
  for (double x : v) forward.Add(x);
  std::shuffle(v.begin(), v.end(), std::mt19937_64(11));
  ExactSum shuffled;
  for (double x : v) shuffled.Add(x);
  // Seven uneven parts summed apart, then added (the chunks of a run).
  ExactSum parts;
  std::size_t at = 0;
  for (std::size_t len : {1u, 17u, 9999u, 30000u, 3u, 40000u}) {
    ExactSum part;
    for (std::size_t k = 0; k < len; ++k) part.Add(v[at++]);
    parts.Add(part);
  }
  ExactSum rest;
  for (; at < v.size(); ++at) rest.Add(v[at]);
  parts.Add(rest);
  EXPECT_EQ(forward, shuffled);
  EXPECT_EQ(forward, parts);
  EXPECT_EQ(forward.Value(), parts.Value());
}

TEST(ExactSum, ValueAgreesWithALongDoubleSumAndHandValues) {
  const std::vector<double> v = Durations();
  long double reference = 0.0L;  // 64-bit mantissa: 2^11 times finer than double
  ExactSum sum;
  for (double x : v) {
    reference += x;
    sum.Add(x);
  }
  EXPECT_NEAR(sum.Value(), static_cast<double>(reference), 1e-9 * static_cast<double>(reference));
  // Hand values: 0.1 ten times is 1 to within a few ulps of 0.1's rounding (a double sum
  // gives 0.9999999999999999); 0.25 and 0.5 are exact on the grid.
  ExactSum tenths;
  for (int i = 0; i < 10; ++i) tenths.Add(0.1);
  EXPECT_NEAR(tenths.Value(), 1.0, 1e-15);
  ExactSum quarters;
  quarters.Add(0.25);
  quarters.Add(0.5);
  EXPECT_EQ(quarters.Value(), 0.75);
  EXPECT_EQ(ExactSum().Value(), 0.0);
}

TEST(ExactSum, HexRoundTripsAndRefusesBadText) {
  ExactSum s;
  for (double x : Durations()) s.Add(x);
  ExactSum back;
  ASSERT_TRUE(ExactSum::FromHex(s.Hex(), back));
  EXPECT_EQ(back, s);
  EXPECT_EQ(s.Hex().size(), 32u);
  ExactSum bad;
  EXPECT_FALSE(ExactSum::FromHex("", bad));
  EXPECT_FALSE(ExactSum::FromHex(std::string(31, '0'), bad));
  EXPECT_FALSE(ExactSum::FromHex(std::string(31, '0') + "g", bad));
  // A one-unit change shows (the merge would see a different part).
  ExactSum one;
  ASSERT_TRUE(ExactSum::FromHex(std::string(31, '0') + "1", one));
  EXPECT_FALSE(one == ExactSum());
  EXPECT_EQ(one.Value(), std::ldexp(1.0, -64));
}

}  // namespace
}  // namespace stitchsim
