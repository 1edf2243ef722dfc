#pragma once
// A head's process description (models/heads/<name>.yaml): tool frame, needles, stitch
// cycle parameters and default rule limits. Lengths mm, angles radians inside.

#include <Eigen/Geometry>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "stitchsim/common/diagnostics.h"
#include "stitchsim/scene/rule_limits.h"

namespace stitchsim::scene {

enum class HeadKind { kSingleSidedStitch, kDoubleSidedStitch, kAfp };

/// A needle as a line in the tool frame.
struct NeedleSpec {
  std::string name;
  Eigen::Vector3d through_mm = Eigen::Vector3d::Zero();   ///< axis crossing of the plane z = 0
  Eigen::Vector3d direction = -Eigen::Vector3d::UnitZ();  ///< unit, into the preform
};

/// Stitch-cycle parameters (stitching heads).
struct StitchProcessSpec {
  double nominal_length_mm = 5.0;
  double width_mm = 17.0;         ///< insertion-catcher spacing on the surface (RS535)
  double phase_in = 0.15;         ///< cycle fraction when the needles enter the preform
  double phase_out = 0.85;        ///< cycle fraction when they leave it
  double walk_capacity_mm = 4.0;  ///< needle walk available per stitch
  double preform_thickness_mm = 12.0;
  double stitch_rate_per_min = 300.0;
  double rotation_speed_deg_s = 30.0;
  double settle_time_s = 0.15;
  double rapid_speed_mm_s = 500.0;
};

struct AfpSpec {
  int tows = 16;
  double tow_width_mm = 6.35;
  double roller_radius_mm = 40.0;
  double min_steering_radius_mm = 635.0;
  double layup_speed_mm_s = 200.0;
  double rapid_speed_mm_s = 500.0;
  /// Distance from the cutter to the compaction roller's nip, mm: the shortest tow piece the
  /// head can lay (afp.min_tow_length's limit when the scene gives none). Absent: not given.
  std::optional<double> cut_to_roller_mm;
  /// Shortest distance along the course between a tow's cut and its restart (add), mm.
  /// Absent: not given.
  std::optional<double> min_restart_mm;
  /// Feed schedule around cuts and adds: the controller lays at most `cut_add_feed_mm_s`
  /// (mm/s) within `cut_add_zone_mm` (mm, along the course) either side of every cut and every
  /// add. 0 (not given): no slow-down.
  double cut_add_feed_mm_s = 0.0;
  double cut_add_zone_mm = 0.0;
};

/// Off-part sequencing of AFP programmes (the head's `sequence:` block; docs/sequence.md).
struct SequenceSpec {
  double retract_mm = 100.0;     ///< retract along the head axis after a lay-up / approach before
  double clearance_mm = 100.0;   ///< travel keeps the tool point this far from the part surface
  double min_overlap_mm2 = 1.0;  ///< courses sharing more surface than this overlap (precedence)
  /// Weight of each machine axis in the seed's eq. 3.4 cost, per mm (prismatic) or per degree
  /// (revolute), by URDF joint name; a joint not listed weighs 0. The CLI checks the names.
  struct AxisWeight {
    std::string joint;
    double weight = 0.0;
    SourceLocation where;
  };
  std::vector<AxisWeight> axis_weights;
};

/// The head near the work, for planners' keep-out margins: every part of the head lower than
/// `height_mm` above the tool point (along tool z) lies within `radius_mm` of the tool z axis.
/// A test checks it against the head's MJCF geometry.
struct HeadEnvelope {
  double height_mm = 0.0;
  double radius_mm = 0.0;
};

/// A contact the process needs (`allowed_contacts:`, docs/collision.md "Allowed contacts"):
/// the head geoms named `head` (`*` matches any run of characters) against the part's preform
/// and / or mold slab. The collision world checks that each pattern names a geom of the head's
/// MJCF; every contact not allowed here counts.
struct AllowedContact {
  std::string head;      ///< geom name pattern in the head MJCF ("needle_catcher", "needle_*")
  bool preform = false;  ///< may touch the preform slab
  bool mold = false;     ///< may touch the mold slab
  SourceLocation where;  ///< the entry in the head file
  /// True when `geom_name` matches the pattern.
  bool Matches(const std::string& geom_name) const;
};

/// The head's mass properties (head spec `inertial:`), flange frame.
struct HeadInertial {
  double mass_kg = 0.0;
  Eigen::Vector3d com_m = Eigen::Vector3d::Zero();          ///< flange frame, metres
  Eigen::Matrix3d inertia_kg_m2 = Eigen::Matrix3d::Zero();  ///< about the CoM, flange axes
};

struct HeadSpec {
  std::filesystem::path file;
  std::string name;
  std::string description;
  HeadKind kind = HeadKind::kSingleSidedStitch;
  int tool_number = 1;
  std::filesystem::path mjcf;  ///< absolute path of the head's MJCF fragment
  Eigen::Isometry3d flange_to_tool_m = Eigen::Isometry3d::Identity();  ///< metres
  std::vector<NeedleSpec> needles;
  StitchProcessSpec stitch;
  AfpSpec afp;
  SequenceSpec sequence;                         ///< defaults when the spec has no `sequence:`
  std::optional<HeadEnvelope> envelope;          ///< absent: the head spec gives none
  RuleLimits limits;                             ///< the spec's `limits`, over the table's defaults
  std::vector<AllowedContact> allowed_contacts;  ///< absent: none (every contact counts)
  std::optional<HeadInertial> inertial;          ///< absent: the head spec gives none
  bool IsStitching() const { return kind != HeadKind::kAfp; }
};

/// How scene and head-spec files may name other files.
struct LoadOptions {
  /// Files named by a scene must lie in the scene's folder tree or the models folder
  /// (ModelsDir()), those named by a head spec in its folder tree or the models folder,
  /// symlinks resolved; true lifts that (`--allow-outside-paths`).
  bool allow_outside_paths = false;
};

/// Loads a head spec; diagnostics (file:line:col, codes "head-...") on bad input.
std::optional<HeadSpec> LoadHeadSpec(const std::filesystem::path& file, DiagnosticSink& sink,
                                     const LoadOptions& options = {});

/// models/heads/<name>.yaml under the data dir, or `name_or_path` itself if it is a path.
std::filesystem::path ResolveHeadFile(const std::string& name_or_path,
                                      const std::filesystem::path& relative_to);

}  // namespace stitchsim::scene
