// The HTML report's laid tows (run/html_laid.h) on hand-made strips on a plane: a straight
// strip keeps its ends (and one station in 64) and every tow edge as given; an arc keeps stations
// so that no dropped one lies further from its chord than the tolerance (the sagitta R (1 - cos(a /
// 2)) of each kept pair, a closed form); past the budget a strip is one ribbon between its
// outermost laid tows' edges; a station off the surface (NaN edges) is never merged away, nor are
// its neighbours.
#include "stitchsim/run/html_laid.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "run_test_support.h"
#include "stitchsim/common/units.h"

namespace stitchsim::run {
namespace {

constexpr int kTows = 4;
constexpr double kWidthMm = 6.35;

// RFC 4648 decoding, written here so the test does not read back through the writer's code.
template <typename T>
std::vector<T> Decode(const nlohmann::json& text) {
  const std::string s = text.get<std::string>();
  const std::string abc = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::vector<unsigned char> bytes;
  unsigned buffer = 0;
  int bits = 0;
  for (char c : s) {
    if (c == '=') break;
    buffer = (buffer << 6) | static_cast<unsigned>(abc.find(c));
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      bytes.push_back(static_cast<unsigned char>((buffer >> bits) & 0xFF));
    }
  }
  std::vector<T> out(bytes.size() / sizeof(T));
  std::memcpy(out.data(), bytes.data(), out.size() * sizeof(T));
  return out;
}

verify::LaidMaterial Empty() { return testing::EmptyLaid(kTows, kWidthMm, 3.0); }

// Adds a strip of `n` stations along a centre line given by `at(f)` (point, unit left normal
// in the plane), tow edges at offsets (k / 2 - b) w to its left; tows 2 and 3 laid.
template <typename At>
verify::LaidMaterial& AddStrip(verify::LaidMaterial& m, int n, At at) {
  verify::LaidStrip s;
  s.line = 12;
  s.ply = 3;
  s.course = 5;
  s.tows = 0b0110;
  s.feed_mm_s = 150.0F;
  s.first_station = static_cast<std::uint32_t>(m.stations.size());
  s.station_count = static_cast<std::uint32_t>(n);
  for (int i = 0; i < n; ++i) {
    const auto [p, left] = at(static_cast<double>(i) / (n - 1));
    verify::LaidStation st;
    st.tool = p.template cast<float>();
    m.stations.push_back(st);
    for (int b = 0; b <= kTows; ++b) {
      m.boundary.push_back((p + (kTows / 2.0 - b) * kWidthMm * left).template cast<float>());
      m.boundary_uv.emplace_back(0.0F, 0.0F);
    }
  }
  m.strips.push_back(s);
  for (int t = 1; t <= kTows; ++t) {
    m.steering_radius_mm.push_back(t == 2 ? 500.0F : std::nanf(""));
    m.fiber_angle_deg.push_back(std::nanf(""));
  }
  return m;
}

auto StraightAlongX(double f) {
  return std::pair{Eigen::Vector3d(300.0 * f, 0.0, 0.0), Eigen::Vector3d(0.0, 1.0, 0.0)};
}

TEST(HtmlLaid, StraightStripKeepsItsEndsAndEdges) {
  verify::LaidMaterial m = Empty();
  LaidThinning t;
  const auto json = PageLaidJson(AddStrip(m, 101, StraightAlongX), 1000000, &t);
  ASSERT_FALSE(json.is_null());
  EXPECT_EQ(json["bounds_per_station"], kTows + 1);
  // The ends and one station in 64 (the most one chord replaces): 0, 64, 100.
  const auto fraction = Decode<float>(json["stations"]["fraction"]);
  ASSERT_EQ(fraction.size(), 3u);
  EXPECT_EQ(fraction[0], 0.0F);
  EXPECT_FLOAT_EQ(fraction[1], 0.64F);
  EXPECT_EQ(fraction[2], 1.0F);
  EXPECT_NE(json["note"].get<std::string>().find("3 of 101 stations"), std::string::npos);
  const auto bound = Decode<float>(json["stations"]["boundary"]);
  ASSERT_EQ(bound.size(), 3u * (kTows + 1) * 3);
  // Station 3 (the far end), edge b: x 300, y (2 - b) w.
  for (int b = 0; b <= kTows; ++b) {
    EXPECT_NEAR(bound[3 * (2 * (kTows + 1) + b)], 300.0, 1e-3);
    EXPECT_NEAR(bound[3 * (2 * (kTows + 1) + b) + 1], (2 - b) * kWidthMm, 1e-4);
  }
  EXPECT_EQ(Decode<std::int32_t>(json["strips"]["line"]), std::vector<std::int32_t>{12});
  EXPECT_EQ(Decode<std::int32_t>(json["strips"]["course"]), std::vector<std::int32_t>{5});
  EXPECT_EQ(Decode<std::uint32_t>(json["strips"]["mask_lo"]), std::vector<std::uint32_t>{6});
  EXPECT_EQ(Decode<std::int32_t>(json["strips"]["first"]), (std::vector<std::int32_t>{0, 3}));
  const auto steer = Decode<float>(json["strips"]["steer"]);
  ASSERT_EQ(steer.size(), static_cast<std::size_t>(kTows));
  EXPECT_EQ(steer[1], 500.0F);
  EXPECT_TRUE(std::isnan(steer[0]));
}

TEST(HtmlLaid, ArcKeepsEveryDroppedStationWithinTheToleranceOfItsChord) {
  constexpr double kRadiusMm = 400.0;
  constexpr double kSweep = kPi / 2;
  const auto arc = [&](double f) {
    const double a = kSweep * f;
    return std::pair{Eigen::Vector3d(kRadiusMm * std::sin(a), kRadiusMm * (1 - std::cos(a)), 0),
                     Eigen::Vector3d(-std::sin(a), std::cos(a), 0.0)};
  };
  verify::LaidMaterial m = Empty();
  LaidThinning t;
  const auto json = PageLaidJson(AddStrip(m, 400, arc), 10000000, &t);
  ASSERT_FALSE(json.is_null());
  EXPECT_DOUBLE_EQ(t.tolerance_mm, 0.05);
  const auto fraction = Decode<float>(json["stations"]["fraction"]);
  ASSERT_GE(fraction.size(), 2u);
  EXPECT_EQ(fraction.front(), 0.0F);
  EXPECT_EQ(fraction.back(), 1.0F);
  // The outermost edge drawn (tow 2's left, 1 w from the centre, on the outside of the turn:
  // radius R + w) has the largest sagitta over a kept pair.
  const double outer_mm = kRadiusMm + kWidthMm;
  double worst = 0.0;
  for (std::size_t i = 0; i + 1 < fraction.size(); ++i) {
    const double a = kSweep * (fraction[i + 1] - fraction[i]);
    worst = std::max(worst, outer_mm * (1 - std::cos(a / 2)));
  }
  EXPECT_LE(worst, 0.05 + 1e-3);
  // And not wastefully many: the widest chord the tolerance allows, with the stations' step.
  const double widest = 2 * std::acos(1 - 0.05 / outer_mm) + kSweep / 399;
  EXPECT_LE(fraction.size(), 2 * static_cast<std::size_t>(std::ceil(kSweep / widest)) + 2);
  EXPECT_LT(fraction.size(), 400u);
}

TEST(HtmlLaid, PastTheBudgetAStripIsOneRibbonBetweenItsOuterLaidEdges) {
  const auto arc = [](double f) {
    return std::pair{Eigen::Vector3d(200 * std::sin(f), 200 * (1 - std::cos(f)), 0.0),
                     Eigen::Vector3d(-std::sin(f), std::cos(f), 0.0)};
  };
  verify::LaidMaterial m = Empty();
  AddStrip(m, 200, arc);
  // R 200 mm over 1 rad: about 12 stations at 0.25 mm, 22 values each tow by tow (264), 13 as
  // one ribbon (156); 15 values for the strip itself.
  const std::size_t budget = 15 + 160;
  LaidThinning t;
  const auto json = PageLaidJson(m, budget, &t);
  EXPECT_TRUE(t.outer_only);
  EXPECT_LE(t.values + 15, budget);
  EXPECT_EQ(json["bounds_per_station"], 2);
  EXPECT_NE(json["note"].get<std::string>().find("one ribbon"), std::string::npos);
  // Tows 2 and 3 laid: edges 1 (tow 2's left, +w) and 3 (tow 3's right, -w) at the start.
  const auto bound = Decode<float>(json["stations"]["boundary"]);
  ASSERT_GE(bound.size(), 6u);
  EXPECT_NEAR(bound[1], kWidthMm, 1e-4);
  EXPECT_NEAR(bound[4], -kWidthMm, 1e-4);
  const auto fraction = Decode<float>(json["stations"]["fraction"]);
  EXPECT_EQ(bound.size(), fraction.size() * 6);
}

TEST(HtmlLaid, PastAQuarterOfTheBudgetFiguresArePerLine) {
  verify::LaidMaterial s = Empty();
  AddStrip(s, 3, StraightAlongX);
  s.steering_radius_mm = {900.0F, 700.0F, std::nanf(""), 800.0F};
  s.fiber_angle_deg = {0.5F, std::nanf(""), 2.5F, 1.0F};
  // 2 k = 8 figures a line: per tow up to a budget of 32 values, per line below it.
  const auto per_tow = PageLaidJson(s, 32, nullptr);
  EXPECT_EQ(per_tow["figures_per_tow"], true);
  EXPECT_EQ(Decode<float>(per_tow["strips"]["steer"]).size(), 4u);
  LaidThinning t;
  const auto per_line = PageLaidJson(s, 31, &t);
  EXPECT_EQ(per_line["figures_per_tow"], false);
  EXPECT_FALSE(t.per_tow_figures);
  EXPECT_EQ(Decode<float>(per_line["strips"]["steer"]), std::vector<float>{700.0F});
  EXPECT_EQ(Decode<float>(per_line["strips"]["angle"]), std::vector<float>{2.5F});
  EXPECT_NE(per_line["note"].get<std::string>().find("per line"), std::string::npos);
}

TEST(HtmlLaid, AStationOffTheSurfaceIsKept) {
  verify::LaidMaterial m = Empty();
  AddStrip(m, 101, StraightAlongX);
  m.stations[40].on_surface = false;
  const auto json = PageLaidJson(m, 1000000, nullptr);
  const auto fraction = Decode<float>(json["stations"]["fraction"]);
  // It and both neighbours (the quads beside it are not drawn; the rest of the strip is).
  ASSERT_EQ(fraction.size(), 5u);
  EXPECT_FLOAT_EQ(fraction[1], 0.39F);
  EXPECT_FLOAT_EQ(fraction[2], 0.4F);
  EXPECT_FLOAT_EQ(fraction[3], 0.41F);
}

TEST(HtmlLaid, NothingLaidIsNull) {
  EXPECT_TRUE(PageLaidJson(verify::LaidMaterial{}, 1000, nullptr).is_null());
}

}  // namespace
}  // namespace stitchsim::run
