#pragma once
// The rule limits: one table of every limit key (rule id, key, unit, default, meaning) and
// the values in force for a scene (head spec defaults, overridden by the scene, then by a
// --limits file). Scene loading validates overrides against the table; process/, planner/
// and verify/ read values by typed key. docs/report-format.md lists the table.

#include <array>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace stitchsim::scene {

/// Every limit key, one per (rule, key) pair of the table.
enum class LimitKey : int {
  kRotationXErrorDeg,      ///< needle.rotation_in_preform x_error_deg
  kRotationYErrorDeg,      ///< needle.rotation_in_preform y_error_deg
  kRotationZErrorDeg,      ///< needle.rotation_in_preform z_error_deg
  kRotationTotalErrorDeg,  ///< needle.rotation_in_preform total_error_deg
  kSideForceErrorMm,       ///< needle.side_force error_mm
  kSideForceWarningMm,     ///< needle.side_force warning_mm
  kSideForceStiffness,     ///< needle.side_force stiffness_n_per_mm
  kWalkErrorMm,            ///< needle.walk error_mm
  kWalkWarningMm,          ///< needle.walk warning_mm
  kStitchLengthErrorPct,
  kStitchLengthWarningPct,
  kStitchLengthInsertionErrorPct,
  kStitchLengthInsertionWarningPct,
  kStitchWidthErrorPct,
  kStitchWidthWarningPct,
  kStandoffErrorMm,
  kStandoffWarningMm,
  kNormalityErrorDeg,
  kNormalityWarningDeg,
  kSingularityA5MinDeg,
  kJointSpeedMaxFraction,
  kJointSpeedWarningPct,
  kAccelerationMaxFraction,  ///< kin.acceleration max_fraction
  kTorqueMaxFraction,        ///< kin.torque max_fraction
  kTorqueWarningPct,         ///< kin.torque warning_pct
  kPayloadMaxFraction,       ///< kin.payload max_fraction
  kSyncErrorMm,
  kSyncChordAllowancePct,
  kClearanceWarningMm,
  kConstraintMarginMm,
  kAfpBMinDeg,  ///< kin.afp_axes b_min_deg (read by the AFP planner)
  kAfpBMaxDeg,
  kAfpCMinDeg,
  kAfpCMaxDeg,
  kAfpSteeringMinMm,        ///< afp.steering_radius min_mm (absent: the head's)
  kAfpGapMaxMm,             ///< afp.gap max_mm
  kAfpOverlapMaxMm,         ///< afp.overlap max_mm
  kAfpCompactionMaxLiftMm,  ///< afp.compaction max_lift_mm
  kAfpCompactionMaxPressMm,
  kAfpCompactionMaxRollDeg,
  kAfpCompactionMaxLeanDeg,
  kAfpCompactionMaxStandoffFraction,
  kAfpCoverageMaxBarePct,  ///< afp.coverage max_bare_pct
  kAfpCoverageMaxDoubledPct,
  kAfpMinTowLengthMm,     ///< afp.min_tow_length min_mm
  kAfpRestartDistanceMm,  ///< afp.restart_distance min_mm
  kAfpFiberAngleMaxDeg,   ///< afp.fiber_angle max_deg
  kTrackingErrorMm,       ///< dyn.tracking error_mm (verify --dynamics)
  kTrackingWarningMm,
  kCount
};
inline constexpr std::size_t kLimitKeyCount = static_cast<std::size_t>(LimitKey::kCount);

/// The unit of a limit's value; the key's name ends with it (_mm, _deg, _pct, _n_per_mm;
/// a fraction has none).
enum class LimitUnit { kMm, kDeg, kPct, kNPerMm, kFraction };

/// One row of the table.
struct LimitSpec {
  LimitKey key;
  std::string_view rule;  ///< rule id, e.g. "needle.side_force"
  std::string_view name;  ///< key within the rule, e.g. "error_mm"
  LimitUnit unit;
  std::optional<double> default_value;  ///< nullopt: no limit unless one is given
  bool may_be_negative;                 ///< false: a negative value is refused at load time
  std::string_view meaning;
};

/// The whole table, in LimitKey order (rules in report order).
std::span<const LimitSpec> LimitTable();
/// The row of `key`.
const LimitSpec& SpecOf(LimitKey key);
/// The row of `rule`.`name`, or nullptr.
const LimitSpec* FindLimit(std::string_view rule, std::string_view name);
/// True when some row has rule id `rule`.
bool IsLimitRule(std::string_view rule);
/// "mm", "deg", "%", "N/mm", "fraction".
std::string_view LimitUnitName(LimitUnit unit);
/// The table as the Markdown docs/report-format.md holds between its limit-table markers.
std::string LimitTableMarkdown();

/// The limit values in force: those given (head spec, scene, limits file), else the table's
/// defaults. Cheap to copy; read at rule construction, never per sample.
class RuleLimits {
 public:
  /// The value given for `key`, else its default; nullopt when neither (no limit).
  std::optional<double> Get(LimitKey key) const;
  /// Get(key) for a key with a default (asserted).
  double Value(LimitKey key) const;
  /// True when a value was given for `key` (not just the default).
  bool IsGiven(LimitKey key) const { return given_[Index(key)].has_value(); }
  /// Gives `key` the value `value` (in the key's unit), over any earlier one.
  void Set(LimitKey key, double value) { given_[Index(key)] = value; }

 private:
  static std::size_t Index(LimitKey key) { return static_cast<std::size_t>(key); }
  std::array<std::optional<double>, kLimitKeyCount> given_{};
};

}  // namespace stitchsim::scene
