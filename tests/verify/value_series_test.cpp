// ValueSeries: the per-bucket envelope equals a brute-force one at the final bucket width; a
// series built from parts in any order equals the serial one; JSON round trip.
#include "stitchsim/verify/value_series.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <random>
#include <vector>

namespace stitchsim::verify {
namespace {

struct Point {
  int line;
  double value;
};

std::vector<Point> RandomPoints(int count, int max_line, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> line(1, max_line);
  std::normal_distribution<double> value(0.0, 3.0);
  std::vector<Point> out;
  for (int i = 0; i < count; ++i) out.push_back({line(rng), value(rng)});
  std::sort(out.begin(), out.end(), [](const Point& a, const Point& b) { return a.line < b.line; });
  return out;
}

void ExpectSame(const ValueSeries& a, const ValueSeries& b) {
  ASSERT_EQ(a.BucketLines(), b.BucketLines());
  ASSERT_EQ(a.FirstLine(), b.FirstLine());
  ASSERT_EQ(a.Min().size(), b.Min().size());
  for (std::size_t i = 0; i < a.Min().size(); ++i) {
    if (std::isnan(a.Min()[i])) {
      EXPECT_TRUE(std::isnan(b.Min()[i])) << i;
      continue;
    }
    EXPECT_EQ(a.Min()[i], b.Min()[i]) << i;
    EXPECT_EQ(a.Max()[i], b.Max()[i]) << i;
  }
}

TEST(ValueSeriesTest, EnvelopeEqualsBruteForceAtTheSmallestWidthThatFits) {
  const std::vector<Point> points = RandomPoints(50000, 1000000, 7);
  ValueSeries s;
  for (const Point& p : points) s.Add(p.line, p.value);
  // The smallest power-of-two width whose buckets over [first, last] line fit kMaxBuckets.
  const int lo = points.front().line, hi = points.back().line;
  long width = 1;
  while ((hi / width) - (lo / width) + 1 > ValueSeries::kMaxBuckets) width *= 2;
  ASSERT_EQ(s.BucketLines(), width);
  EXPECT_EQ(s.FirstLine(), lo / width * width);
  std::vector<float> mn(s.Min().size(), NAN), mx(s.Min().size(), NAN);
  for (const Point& p : points) {
    const auto k = static_cast<std::size_t>(p.line / width - lo / width);
    const auto v = static_cast<float>(p.value);
    mn[k] = std::isnan(mn[k]) ? v : std::min(mn[k], v);
    mx[k] = std::isnan(mx[k]) ? v : std::max(mx[k], v);
  }
  for (std::size_t k = 0; k < mn.size(); ++k) {
    if (std::isnan(mn[k])) {
      EXPECT_TRUE(std::isnan(s.Min()[k]));
    } else {
      EXPECT_EQ(s.Min()[k], mn[k]);
      EXPECT_EQ(s.Max()[k], mx[k]);
    }
  }
}

TEST(ValueSeriesTest, PartsAbsorbedInAnyOrderEqualTheSerialSeries) {
  const std::vector<Point> points = RandomPoints(20000, 300000, 11);
  ValueSeries serial;
  for (const Point& p : points) serial.Add(p.line, p.value);
  // Cut at uneven places; a short part sees a much finer width than the whole.
  const std::vector<std::size_t> cuts = {0, 13, 2000, 2001, 15000, points.size()};
  std::vector<ValueSeries> parts(cuts.size() - 1);
  for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
    for (std::size_t i = cuts[k]; i < cuts[k + 1]; ++i)
      parts[k].Add(points[i].line, points[i].value);
  }
  ValueSeries forward, backward;
  for (const auto& p : parts) forward.Absorb(p);
  for (auto it = parts.rbegin(); it != parts.rend(); ++it) backward.Absorb(*it);
  ExpectSame(serial, forward);
  ExpectSame(serial, backward);
  ASSERT_GT(serial.BucketLines(), 64);  // the parts were coarsened on the way
}

TEST(ValueSeriesTest, JsonRoundTripAndMalformedInputIsRefused) {
  ValueSeries s;
  s.Add(10, 1.5);
  s.Add(40000, -2.0);
  s.Add(5, NAN);  // ignored
  ValueSeries back;
  ASSERT_TRUE(back.FromJson(s.ToJson()));
  ExpectSame(s, back);
  nlohmann::json bad = s.ToJson();
  bad["min"].push_back(1.0);  // sizes differ
  EXPECT_FALSE(back.FromJson(bad));
  ExpectSame(s, back);  // unchanged
  EXPECT_FALSE(back.FromJson(nlohmann::json::object()));
}

}  // namespace
}  // namespace stitchsim::verify
