// The thickness laid below, verify's own (afp.compaction's map; issue 29, done-when 3), against
// closed forms on a flat plate: n plies of thickness t laid over one area read n t there (the
// laydown figures, per ply k t); a smaller pad-up ply on top reads its own t as the step
// (whole: min n t, max (n + 1) t). afp.compaction judges the roller against the raised
// surface: a ply planned on the bare tool under an earlier ply presses by the thickness below
// (t), a ply planned at +t with nothing laid below lifts by t, each on its own line; the ply
// raised by exactly what lies below passes. The laminate maps read the same numbers, and a
// course turned 4 deg reads 4 deg as its ply's worst fibre angle and on the angle map.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "afp_test_support.h"
#include "stitchsim/verify/afp_laminate_maps.h"

namespace stitchsim::verify {
namespace {

using testing::AfpScene;
using testing::LayLine;
using testing::RuleOf;
using testing::ToolAt;

constexpr double kT = 0.18;  // ply thickness, mm (the default material's)

std::unique_ptr<scene::Scene> Plate(int plies, double t = kT) {
  auto scene = AfpScene(geom::MakePlane(1200, 1200));
  for (int i = 0; i < plies; ++i) {
    scene::PlySpec p;
    p.name = "p" + std::to_string(i + 1);
    p.thickness_mm = t;
    scene->plies.push_back(p);
  }
  return scene;
}

// A course of ply `ply` along u from u0 to u1 at v = 0, the tool `lift` mm above the tool
// surface, laying `tows`; lines numbered from `line`.
trace::LineRecord Course(const geom::Surface& s, int line, int ply, double u0, double u1,
                         double lift, std::uint64_t tows = testing::kAllTows) {
  const Eigen::Vector2d x(1, 0);
  return LayLine(line, ToolAt(s, {u0, 0}, x, lift), ToolAt(s, {u1, 0}, x, lift), tows, 1, ply);
}

struct Verified {
  Report report;
  std::vector<LaminateMap> maps;
};

Verified Verify(const scene::Scene& scene, const std::vector<trace::LineRecord>& lines) {
  Verified run;
  run.report =
      testing::RunLines(scene, lines, [&](const Verifier& v) { run.maps = LaminateMaps(v, 400); });
  return run;
}

const LaydownFigures& PlyFigures(const Report& r, int ply) {
  for (const LaydownFigures& f : r.laydown) {
    if (f.ply == ply) return f;
  }
  ADD_FAILURE() << "no laydown figures of ply " << ply;
  return r.laydown.front();
}

const LaminateMap* MapNamed(const Verified& run, const std::string& name) {
  for (const LaminateMap& m : run.maps) {
    if (m.name == name) return &m;
  }
  return nullptr;
}

TEST(AfpThickness, NPliesReadNTimesTheirThicknessAndAPadUpItsStep) {
  const int n = 3;
  auto scene = Plate(n + 1);
  const geom::Surface& s = *scene->surface;
  std::vector<trace::LineRecord> lines;
  // Plies 1..n over u 0..300 (16 tows, v -50.8..50.8), each raised by the k - 1 below it.
  for (int k = 1; k <= n; ++k) lines.push_back(Course(s, 10 * k, k, 0, 300, (k - 1) * kT));
  // The pad-up: tows 5..12 (v -25.4..25.4) over u 100..200, on the n plies.
  lines.push_back(Course(s, 100, n + 1, 100, 200, n * kT, 0x0FF0));
  const Verified run = Verify(*scene, lines);
  for (int k = 1; k <= n + 1; ++k) {
    const LaydownFigures& f = PlyFigures(run.report, k);
    ASSERT_TRUE(f.thickness_min_mm && f.thickness_max_mm) << "ply " << k;
    EXPECT_NEAR(*f.thickness_min_mm, k * kT, 1e-9) << "ply " << k;
    EXPECT_NEAR(*f.thickness_max_mm, k * kT, 1e-9) << "ply " << k;
  }
  const LaydownFigures& whole = PlyFigures(run.report, 0);
  ASSERT_TRUE(whole.thickness_min_mm && whole.thickness_max_mm);
  EXPECT_NEAR(*whole.thickness_min_mm, n * kT, 1e-9);
  EXPECT_NEAR(*whole.thickness_max_mm - *whole.thickness_min_mm, kT, 1e-9);  // the step
  // Every ply was raised by what lies below it: the roller sits on the laid surface.
  const RuleSummary* compaction = RuleOf(run.report, "afp.compaction");
  ASSERT_NE(compaction, nullptr);
  EXPECT_EQ(compaction->errors, 0);
  EXPECT_NEAR(*testing::SubjectOf(*compaction, "lift").worst_value, 0.0, 1e-6);
  EXPECT_NEAR(*testing::SubjectOf(*compaction, "press").worst_value, 0.0, 1e-6);
  // The thickness map reads the same stack; its box is the laid area's (u 0..300, v +-50.8,
  // within a cell of 2 mm).
  const LaminateMap* map = MapNamed(run, "thickness");
  ASSERT_NE(map, nullptr);
  EXPECT_NEAR(map->min_value, n * kT, 1e-6);
  EXPECT_NEAR(map->max_value, (n + 1) * kT, 1e-6);
  EXPECT_NEAR(map->lo_uv.x(), 0.0, 2.0);
  EXPECT_NEAR(map->hi_uv.x(), 300.0, 4.0);
  EXPECT_NEAR(map->lo_uv.y(), -50.8, 2.0);
}

TEST(AfpThickness, ATowOverlappingAnotherOfItsPlyCountsOnce) {
  auto scene = Plate(2);
  scene->limits.Set(scene::LimitKey::kAfpCompactionMaxPressMm, 0.1);
  scene->limits.Set(scene::LimitKey::kAfpCompactionMaxLiftMm, 0.1);
  const geom::Surface& s = *scene->surface;
  const Eigen::Vector2d x(1, 0);
  // Ply 1: two courses on the bare tool, the second 8 tows over (half of it on the first).
  auto shifted = [&](int line, int course, int ply, double lift) {
    return LayLine(line, ToolAt(s, {0, 8 * testing::kTowWidth}, x, lift),
                   ToolAt(s, {300, 8 * testing::kTowWidth}, x, lift), testing::kAllTows, course,
                   ply);
  };
  const Verified run = Verify(
      *scene, {Course(s, 10, 1, 0, 300, 0.0), shifted(11, 2, 1, 0.0), shifted(20, 1, 2, kT)});
  EXPECT_NEAR(*PlyFigures(run.report, 1).thickness_max_mm, kT, 1e-9);
  EXPECT_NEAR(*PlyFigures(run.report, 1).thickness_min_mm, kT, 1e-9);
  EXPECT_NEAR(*PlyFigures(run.report, 2).thickness_max_mm, 2 * kT, 1e-9);
  // Ply 1's second course lies on the bare tool, ply 2 on the one ply below: no finding.
  const RuleSummary* rule = RuleOf(run.report, "afp.compaction");
  ASSERT_NE(rule, nullptr);
  EXPECT_EQ(rule->errors, 0);
}

// The findings of `rule` about `subject`.
std::vector<Finding> SubjectFindings(const RuleSummary& rule, const std::string& subject) {
  std::vector<Finding> out;
  for (const Finding& f : rule.findings) {
    if (f.subject == subject) out.push_back(f);
  }
  return out;
}

TEST(AfpThickness, APlyPlannedOnTheBareToolUnderAnEarlierPlyPressesByItsThickness) {
  auto scene = Plate(2);
  scene->limits.Set(scene::LimitKey::kAfpCompactionMaxPressMm, 0.1);
  const geom::Surface& s = *scene->surface;
  const Verified run =
      Verify(*scene, {Course(s, 10, 1, 0, 300, 0.0), Course(s, 20, 2, 0, 300, 0.0)});
  const RuleSummary* rule = RuleOf(run.report, "afp.compaction");
  ASSERT_NE(rule, nullptr);
  // One line from u 0 to 300: its programmed points lie at the ends of the ply below, where
  // standoff reads both sides; the chord between them presses by t.
  ASSERT_EQ(rule->findings.size(), 1U);
  const Finding& f = rule->findings[0];
  EXPECT_EQ(f.line, 20);
  EXPECT_EQ(f.subject, "press");
  EXPECT_NEAR(f.value, kT / 0.1 * 100.0, 1e-6);  // percent of the limit: 0.18 mm below
  EXPECT_NE(f.message.find("ply 2 course 1 (tows 1-16)"), std::string::npos) << f.message;
  EXPECT_NE(f.message.find("0.18 mm"), std::string::npos) << f.message;
}

// At the default limits (press 1 mm, lift 0.25 mm, standoff half a ply; plies of 0.18 mm) a
// ply planned on the bare tool is off the laid surface under one ply already: standoff by
// below x 0.18 mm against 0.09 mm (200 % a ply below); press fires once more than 5 plies lie
// below it (6 x 0.18 = 1.08 mm > 1 mm), not under 5 (0.9 mm).
TEST(AfpThickness, AtTheDefaultLimitsTheBareToolFiresUnderOnePly) {
  for (const int below : {1, 5, 6}) {
    auto scene = Plate(below + 1);
    const geom::Surface& s = *scene->surface;
    std::vector<trace::LineRecord> lines;
    for (int k = 1; k <= below; ++k) lines.push_back(Course(s, 10 * k, k, 0, 300, (k - 1) * kT));
    // On the bare tool, in 30 mm lines (standoff is judged at the programmed points; the
    // course's two ends, within a tow width of the plies' ends, read both sides).
    for (int i = 0; i < 10; ++i)
      lines.push_back(Course(s, 100 + i, below + 1, 30 * i, 30 * i + 30, 0.0));
    const Verified run = Verify(*scene, lines);
    const RuleSummary* rule = RuleOf(run.report, "afp.compaction");
    ASSERT_NE(rule, nullptr);
    const SubjectFigure& press = testing::SubjectOf(*rule, "press");
    const SubjectFigure& standoff = testing::SubjectOf(*rule, "standoff");
    EXPECT_NEAR(*press.worst_value, below * kT / 1.0 * 100.0, 1e-6);
    EXPECT_NEAR(*standoff.worst_value, below * 200.0, 1e-6);
    EXPECT_EQ(standoff.worst_line, 100);
    // Every line has a programmed point inside (u 30 .. 270): 10 findings, standoff (the
    // worst subject of each line), 200 % per ply below.
    ASSERT_EQ(rule->findings.size(), 10U) << below;
    for (const Finding& f : rule->findings) {
      EXPECT_EQ(f.subject, "standoff");
      EXPECT_NEAR(f.value, below * 200.0, 1e-6);
      EXPECT_NE(f.message.find("limit 0.09 mm: 0.5 of the ply's 0.18 mm"), std::string::npos)
          << f.message;
    }
    // Press is within the roller's compliance under 5 plies (0.9 mm), past it under 6.
    EXPECT_EQ(*press.worst_value > 100.0, below == 6) << below;
  }
}

// Standoff against its limit by hand: ply 2 planned 0.08 mm above ply 1's top passes (0.08 /
// 0.09 = 88.9 %), 0.10 mm fires (111.1 %) on its line; lift (0.25 mm) fires on neither. A ply
// the scene gives no thickness is not judged for standoff.
TEST(AfpThickness, StandoffIsAFractionOfTheLayingPlysThickness) {
  for (const double off : {0.08, 0.10}) {
    auto scene = Plate(2);
    const geom::Surface& s = *scene->surface;
    const Verified run =
        Verify(*scene, {Course(s, 10, 1, 0, 300, 0.0), Course(s, 20, 2, 0, 150, kT + off),
                        Course(s, 21, 2, 150, 300, kT + off)});
    const RuleSummary* rule = RuleOf(run.report, "afp.compaction");
    ASSERT_NE(rule, nullptr);
    EXPECT_NEAR(*testing::SubjectOf(*rule, "standoff").worst_value, off / 0.09 * 100.0, 1e-6);
    EXPECT_EQ(*testing::SubjectOf(*rule, "lift").worst_value > 100.0, false);
    if (off > 0.09) {
      ASSERT_EQ(rule->findings.size(), 2U);  // u = 150 ends line 20 and starts line 21
      EXPECT_EQ(rule->findings[0].line, 20);
      EXPECT_EQ(rule->findings[0].subject, "standoff");
    } else {
      EXPECT_TRUE(rule->findings.empty());
    }
  }
  auto weightless = Plate(2);
  weightless->plies[1].thickness_mm = 0.0;
  const geom::Surface& s = *weightless->surface;
  const Verified run =
      Verify(*weightless, {Course(s, 10, 1, 0, 300, 0.0), Course(s, 20, 2, 0, 150, 0.0),
                           Course(s, 21, 2, 150, 300, 0.0)});
  const RuleSummary* rule = RuleOf(run.report, "afp.compaction");
  ASSERT_NE(rule, nullptr);
  EXPECT_TRUE(SubjectFindings(*rule, "standoff").empty());
}

TEST(AfpThickness, ARollerLiftedByAMissingPlyFiresAndTheRaisedPlyPasses) {
  auto scene = Plate(2);
  scene->limits.Set(scene::LimitKey::kAfpCompactionMaxLiftMm, 0.1);
  const geom::Surface& s = *scene->surface;
  // Ply 2 planned at +t with no ply 1 laid below it.
  const Verified missing = Verify(*scene, {Course(s, 20, 2, 0, 300, kT)});
  const RuleSummary* rule = RuleOf(missing.report, "afp.compaction");
  ASSERT_NE(rule, nullptr);
  // Lifted by t: 180 % of 0.1 mm; the line's finding is its worst subject, standoff (off by t,
  // twice half a ply: 200 %).
  ASSERT_EQ(rule->findings.size(), 1U);
  EXPECT_EQ(rule->findings[0].line, 20);
  EXPECT_EQ(rule->findings[0].subject, "standoff");
  EXPECT_NEAR(rule->findings[0].value, 200.0, 1e-6);
  EXPECT_NEAR(*testing::SubjectOf(*rule, "lift").worst_value, kT / 0.1 * 100.0, 1e-6);
  EXPECT_EQ(testing::SubjectOf(*rule, "lift").worst_line, 20);
  // Ply 1 laid first: ply 2 at +t sits on it.
  const Verified raised =
      Verify(*scene, {Course(s, 10, 1, 0, 300, 0.0), Course(s, 20, 2, 0, 300, kT)});
  const RuleSummary* clean = RuleOf(raised.report, "afp.compaction");
  ASSERT_NE(clean, nullptr);
  EXPECT_EQ(clean->errors, 0);
  EXPECT_NEAR(*testing::SubjectOf(*clean, "lift").worst_value, 0.0, 1e-6);
  // A roller bridges a step narrower than a tow: ply 2 at +t runs 5 mm past the end of ply 1
  // (u 0..150) without a finding: the stack within a tow width of its foot holds t and 0.
  const Verified step =
      Verify(*scene, {Course(s, 10, 1, 0, 150, 0.0), Course(s, 20, 2, 0, 155, kT)});
  EXPECT_EQ(RuleOf(step.report, "afp.compaction")->errors, 0);
  // Ply 1 over u 0..150; ply 2 on it to its end (the edge within a tow width reads both
  // sides), then beyond it from u 160: only that line lifts, by t (and is off by it).
  const Verified half = Verify(*scene, {Course(s, 10, 1, 0, 150, 0.0), Course(s, 20, 2, 0, 150, kT),
                                        Course(s, 21, 2, 160, 300, kT)});
  const RuleSummary* part = RuleOf(half.report, "afp.compaction");
  ASSERT_NE(part, nullptr);
  ASSERT_EQ(part->findings.size(), 1U);
  EXPECT_EQ(part->findings[0].line, 21);
  EXPECT_EQ(testing::SubjectOf(*part, "lift").worst_line, 21);
  EXPECT_NEAR(*testing::SubjectOf(*part, "lift").worst_value, kT / 0.1 * 100.0, 1e-6);
}

TEST(AfpThickness, ACourseTurnedFourDegreesIsItsPlysWorstFibreAngleAndOnTheMap) {
  auto scene = Plate(2);
  const geom::Surface& s = *scene->surface;
  const double a = DegToRad(4.0);
  const Eigen::Vector2d dir(std::cos(a), std::sin(a));
  const Verified run =
      Verify(*scene, {Course(s, 10, 1, 0, 300, 0.0),
                      LayLine(20, ToolAt(s, {0, 0}, dir, kT), ToolAt(s, 200 * dir, dir, kT),
                              testing::kAllTows, 1, 2)});
  ASSERT_TRUE(PlyFigures(run.report, 1).worst_fiber_angle_deg);
  EXPECT_NEAR(*PlyFigures(run.report, 1).worst_fiber_angle_deg, 0.0, 1e-9);
  ASSERT_TRUE(PlyFigures(run.report, 2).worst_fiber_angle_deg);
  EXPECT_NEAR(*PlyFigures(run.report, 2).worst_fiber_angle_deg, 4.0, 1e-9);
  EXPECT_NEAR(*PlyFigures(run.report, 0).worst_fiber_angle_deg, 4.0, 1e-9);
  const LaminateMap* map = MapNamed(run, "fiber_angle");
  ASSERT_NE(map, nullptr);
  EXPECT_NEAR(map->min_value, 0.0, 1e-6);
  EXPECT_NEAR(map->max_value, 4.0, 1e-5);  // stored as float
}

}  // namespace
}  // namespace stitchsim::verify
