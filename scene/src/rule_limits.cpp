#include "stitchsim/scene/rule_limits.h"

#include <cassert>
#include <cstdio>

namespace stitchsim::scene {
namespace {

using K = LimitKey;
using U = LimitUnit;
constexpr std::optional<double> kNone = std::nullopt;

// Rules in report order; within a rule, error before warning. A change here changes
// docs/report-format.md (a test keeps them equal).
constexpr LimitSpec kTable[] = {
    {K::kRotationXErrorDeg, "needle.rotation_in_preform", "x_error_deg", U::kDeg, kNone, false,
     "head rotation about tool x while the needles are in the preform"},
    {K::kRotationYErrorDeg, "needle.rotation_in_preform", "y_error_deg", U::kDeg, kNone, false,
     "head rotation about tool y while the needles are in the preform"},
    {K::kRotationZErrorDeg, "needle.rotation_in_preform", "z_error_deg", U::kDeg, kNone, false,
     "head rotation about tool z while the needles are in the preform (the rule's error limit; "
     "else total_error_deg)"},
    {K::kRotationTotalErrorDeg, "needle.rotation_in_preform", "total_error_deg", U::kDeg, kNone,
     false, "total head rotation while the needles are in the preform"},
    {K::kSideForceErrorMm, "needle.side_force", "error_mm", U::kMm, kNone, false,
     "side-force proxy (lateral shaft drift in the preform), error"},
    {K::kSideForceWarningMm, "needle.side_force", "warning_mm", U::kMm, kNone, false,
     "side-force proxy, warning"},
    {K::kSideForceStiffness, "needle.side_force", "stiffness_n_per_mm", U::kNPerMm, kNone, false,
     "preform stiffness: findings also give the force in N"},
    {K::kWalkErrorMm, "needle.walk", "error_mm", U::kMm, kNone, false,
     "needle walk demand, error (absent: the head's walk capacity)"},
    {K::kWalkWarningMm, "needle.walk", "warning_mm", U::kMm, kNone, false,
     "needle walk demand, warning"},
    {K::kStitchLengthErrorPct, "stitch.length", "error_pct", U::kPct, kNone, false,
     "stitch length deviation of the needle at the tool point, error"},
    {K::kStitchLengthWarningPct, "stitch.length", "warning_pct", U::kPct, kNone, false,
     "stitch length deviation of the needle at the tool point, warning"},
    {K::kStitchLengthInsertionErrorPct, "stitch.length", "insertion_error_pct", U::kPct, kNone,
     false, "stitch length deviation of the other needles, error"},
    {K::kStitchLengthInsertionWarningPct, "stitch.length", "insertion_warning_pct", U::kPct, kNone,
     false, "stitch length deviation of the other needles, warning"},
    {K::kStitchWidthErrorPct, "stitch.width", "error_pct", U::kPct, kNone, false,
     "stitch width deviation from nominal, error"},
    {K::kStitchWidthWarningPct, "stitch.width", "warning_pct", U::kPct, kNone, false,
     "stitch width deviation from nominal, warning"},
    {K::kStandoffErrorMm, "stitch.standoff", "error_mm", U::kMm, kNone, false,
     "tool point distance from the surface at needle entry, error"},
    {K::kStandoffWarningMm, "stitch.standoff", "warning_mm", U::kMm, kNone, false,
     "tool point distance from the surface at needle entry, warning"},
    {K::kNormalityErrorDeg, "stitch.normality", "error_deg", U::kDeg, kNone, false,
     "head z tilt from the surface normal at needle entry, error"},
    {K::kNormalityWarningDeg, "stitch.normality", "warning_deg", U::kDeg, kNone, false,
     "head z tilt from the surface normal at needle entry, warning"},
    {K::kSingularityA5MinDeg, "kin.singularity", "a5_min_deg", U::kDeg, 1.0, false,
     "wrist singularity band: a5 nearer 0 deg than this is an error (also the IK threshold)"},
    {K::kJointSpeedMaxFraction, "kin.joint_speed", "max_fraction", U::kFraction, 1.0, false,
     "joint speed error limit, as a fraction of the URDF maximum"},
    {K::kJointSpeedWarningPct, "kin.joint_speed", "warning_pct", U::kPct, kNone, false,
     "joint speed warning limit, percent of the URDF maximum"},
    {K::kAccelerationMaxFraction, "kin.acceleration", "max_fraction", U::kFraction, 1.0, false,
     "joint acceleration on the timed trajectory, error limit as a fraction of the URDF's"},
    {K::kTorqueMaxFraction, "kin.torque", "max_fraction", U::kFraction, 1.0, false,
     "joint torque (inverse dynamics on the timed trajectory), error limit as a fraction of the "
     "URDF effort"},
    {K::kTorqueWarningPct, "kin.torque", "warning_pct", U::kPct, kNone, false,
     "joint torque warning limit, percent of the URDF effort"},
    {K::kPayloadMaxFraction, "kin.payload", "max_fraction", U::kFraction, 1.0, false,
     "head mass and moments about a5 and a6, error limit as a fraction of the load diagram's"},
    {K::kSyncErrorMm, "program.sync", "error_mm", U::kMm, 0.01, false,
     "largest U / V / tool-travel inconsistency of a line"},
    {K::kSyncChordAllowancePct, "program.sync", "chord_allowance_pct", U::kPct, 2.0, false,
     "how far V may exceed the straight tool travel (a chord is shorter than its arc)"},
    {K::kClearanceWarningMm, "collision.clearance", "warning_mm", U::kMm, 10.0, false,
     "smallest clearance between bodies that must not touch, warning"},
    {K::kConstraintMarginMm, "constraint.crossing", "margin_mm", U::kMm, 1.0, false,
     "margin around each constraint footprint"},
    {K::kAfpBMinDeg, "kin.afp_axes", "b_min_deg", U::kDeg, -90.0, true,
     "AFP head B axis travel, lower end (read by `plan afp`)"},
    {K::kAfpBMaxDeg, "kin.afp_axes", "b_max_deg", U::kDeg, 90.0, true,
     "AFP head B axis travel, upper end"},
    {K::kAfpCMinDeg, "kin.afp_axes", "c_min_deg", U::kDeg, -180.0, true,
     "AFP head C axis travel, lower end"},
    {K::kAfpCMaxDeg, "kin.afp_axes", "c_max_deg", U::kDeg, 180.0, true,
     "AFP head C axis travel, upper end"},
    {K::kAfpSteeringMinMm, "afp.steering_radius", "min_mm", U::kMm, kNone, false,
     "smallest steering radius of a laid tow's centre line (absent: the head's "
     "`afp.min_steering_radius_mm`)"},
    {K::kAfpGapMaxMm, "afp.gap", "max_mm", U::kMm, 0.76, false,
     "largest gap between neighbouring courses of a ply, or left by a tow cut inside a course "
     "(0.03 in)"},
    {K::kAfpOverlapMaxMm, "afp.overlap", "max_mm", U::kMm, 0.76, false,
     "largest overlap of neighbouring courses of a ply (0.03 in)"},
    {K::kAfpCompactionMaxLiftMm, "afp.compaction", "max_lift_mm", U::kMm, 0.25, false,
     "tool point (roller contact) above the laid surface (the tool raised by the plies below) "
     "while laying"},
    {K::kAfpCompactionMaxPressMm, "afp.compaction", "max_press_mm", U::kMm, 1.0, false,
     "tool point below the laid surface while laying (roller compliance)"},
    {K::kAfpCompactionMaxRollDeg, "afp.compaction", "max_roll_deg", U::kDeg, 2.0, false,
     "roller axis (tool x) out of the tangent plane while laying"},
    {K::kAfpCompactionMaxLeanDeg, "afp.compaction", "max_lean_deg", U::kDeg, 15.0, false,
     "head axis leaning along the travel (tool y out of the tangent plane) while laying"},
    {K::kAfpCompactionMaxStandoffFraction, "afp.compaction", "max_standoff_fraction", U::kFraction, 0.5,
     false,
     "programmed tool point off the laid surface (outside the stack thickness within a tow width "
     "of its "
     "foot), as a fraction of the laying ply's thickness: the path does not follow the plies "
     "below (planned on the bare tool, or on a ply that is missing)"},
    {K::kAfpCoverageMaxBarePct, "afp.coverage", "max_bare_pct", U::kPct, 2.0, false,
     "area of a ply left bare, beyond the band of one tow width along its boundary, percent"},
    {K::kAfpCoverageMaxDoubledPct, "afp.coverage", "max_doubled_pct", U::kPct, 5.0, false,
     "area of a ply covered twice or more, beyond the band along its boundary, percent"},
    {K::kAfpMinTowLengthMm, "afp.min_tow_length", "min_mm", U::kMm, std::nullopt, false,
     "shortest tow piece the head can lay, from its add to its cut: the distance from the "
     "cutter to the compaction roller (none given: the head's `cut_to_roller_mm`; neither: the "
     "rule is skipped)"},
    {K::kAfpRestartDistanceMm, "afp.restart_distance", "min_mm", U::kMm, std::nullopt, false,
     "shortest distance the head travels along a tow's centre line, within a course, between "
     "cutting the tow and adding it again (none given: the head's `min_restart_mm`; neither: the "
     "rule is skipped)"},
    {K::kAfpFiberAngleMaxDeg, "afp.fiber_angle", "max_deg", U::kDeg, 5.0, false,
     "laid tow direction off its ply's design fibre direction (rosette projected onto the "
     "surface, turned by the ply angle); 5 deg an assumption, designers hold 3 to 5"},
    {K::kTrackingErrorMm, "dyn.tracking", "error_mm", U::kMm, 2.0, false,
     "tool point lagging its command in a dynamic run (`verify --dynamics`), error"},
    {K::kTrackingWarningMm, "dyn.tracking", "warning_mm", U::kMm, 0.5, false,
     "tool point lagging its command in a dynamic run, warning"},
};
static_assert(std::size(kTable) == kLimitKeyCount, "one row per LimitKey");

constexpr bool RowsInKeyOrder() {
  for (std::size_t i = 0; i < std::size(kTable); ++i) {
    if (static_cast<std::size_t>(kTable[i].key) != i) return false;
  }
  return true;
}
static_assert(RowsInKeyOrder(), "kTable rows in LimitKey order");

std::string Number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%g", v);
  return buf;
}

}  // namespace

std::span<const LimitSpec> LimitTable() { return kTable; }

const LimitSpec& SpecOf(LimitKey key) { return kTable[static_cast<std::size_t>(key)]; }

const LimitSpec* FindLimit(std::string_view rule, std::string_view name) {
  for (const LimitSpec& s : kTable) {
    if (s.rule == rule && s.name == name) return &s;
  }
  return nullptr;
}

bool IsLimitRule(std::string_view rule) {
  for (const LimitSpec& s : kTable) {
    if (s.rule == rule) return true;
  }
  return false;
}

std::string_view LimitUnitName(LimitUnit unit) {
  switch (unit) {
    case LimitUnit::kMm:
      return "mm";
    case LimitUnit::kDeg:
      return "deg";
    case LimitUnit::kPct:
      return "%";
    case LimitUnit::kNPerMm:
      return "N/mm";
    case LimitUnit::kFraction:
      return "fraction";
  }
  return "";
}

std::string LimitTableMarkdown() {
  std::string out =
      "| rule | key | unit | default | meaning |\n"
      "|---|---|---|---|---|\n";
  for (const LimitSpec& s : kTable) {
    out += "| `" + std::string(s.rule) + "` | `" + std::string(s.name) + "` | " +
           std::string(LimitUnitName(s.unit)) + " | " +
           (s.default_value ? Number(*s.default_value) : std::string("none")) + " | " +
           std::string(s.meaning) + " |\n";
  }
  return out;
}

std::optional<double> RuleLimits::Get(LimitKey key) const {
  const std::optional<double>& given = given_[Index(key)];
  return given ? given : SpecOf(key).default_value;
}

double RuleLimits::Value(LimitKey key) const {
  const std::optional<double> v = Get(key);
  assert(v && "Value() of a limit key without a default; use Get()");
  return v.value_or(0.0);
}

}  // namespace stitchsim::scene
