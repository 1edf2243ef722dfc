#pragma once
// Interference checking with FCL: the robot (arm links, carriage), the head, the cell (rail,
// rotator, table, floor), the mold, the preform and the constraints. Contacts the process
// needs are listed in the head file (`allowed_contacts`: needles in the preform, the AFP
// roller on the laminate, the RS566 table under the preform); everything else counts. A
// geometry pair FCL cannot check is an error, never "clear".

#include <Eigen/Geometry>
#include <memory>
#include <string>
#include <vector>

#include "stitchsim/common/diagnostics.h"
#include "stitchsim/scene/scene.h"
#include "stitchsim/sim/robot_model.h"
#include "stitchsim/trace/trace.h"

namespace stitchsim::sim {

/// Which family of bodies a contact belongs to (a trace type: samples carry contacts).
using trace::ContactClass;

struct Contact {
  ContactClass kind = ContactClass::kHeadPart;
  std::string body_a;  ///< e.g. "head:presser_foot", "link_3", "constraint:stringer_left"
  std::string body_b;
  /// Penetration depth (docs/collision.md, "Depth"). Against the mold or the preform: how far
  /// the body reaches under the slab's head-side face along the surface normal (> 0). Between
  /// primitives: FCL's depth along the separating direction. 0 when not measured.
  double depth_m = 0.0;
  /// False against a mesh constraint: FCL's mesh contact depth is one triangle's, not the
  /// body's, so none is reported.
  bool depth_measured = true;
  Eigen::Vector3d point_world_m = Eigen::Vector3d::Zero();  ///< deepest point (slabs) or FCL's
};

struct CollisionResult {
  std::vector<Contact> contacts;  ///< empty = clear
  /// Smallest distance between checked pairs (>= 0; 0 with contacts). Capped at
  /// CollisionOptions::clearance_cutoff_m (nothing closer than the cutoff), or 1e9 when
  /// clearance was not computed.
  double min_clearance_m = 1e9;
  std::string min_clearance_pair;  ///< "a|b" of that distance
  std::string error;               ///< non-empty: a pair could not be checked
};

struct CollisionOptions {
  bool compute_clearance = true;     ///< distance queries (needed for collision.clearance)
  double clearance_cutoff_m = 0.05;  ///< distances above this are not refined
  /// Benchmark baseline only: every checked pair, no broadphase, objects rebuilt per query.
  bool naive_baseline = false;
};

class MujocoCell;      // mujoco_cell.h
class CollisionModel;  // immutable: bodies, geometry, pair filter (sim/src/detail/)
class CollisionData;   // one caller's per-query state

/// The collision world of one scene: a shared, immutable model and this caller's per-query
/// data (docs/collision.md, "Model and data"). The scene and the robot model it was made from
/// must outlive it. One world per thread; Share() makes another on the same model.
class CollisionWorld {
 public:
  ~CollisionWorld();
  /// Builds FCL objects for the cell, the head and the part; diagnostics on failure.
  static std::unique_ptr<CollisionWorld> Create(const scene::Scene& scene, const RobotModel& robot,
                                                DiagnosticSink& sink);
  /// Another world on the same model with its own per-query data, for another thread. Make
  /// it before other threads query (FCL rewrites each shared geometry's local box, with the
  /// same values, when it makes an object).
  std::unique_ptr<CollisionWorld> Share() const;
  /// Takes the link frames and the part's pose from MuJoCo's kinematics of the cell (the
  /// executor's, kinematic mode) instead of the URDF forward kinematics; null: the URDF.
  /// `kinematics` must outlive the world's queries.
  void UseKinematics(MujocoCell* kinematics);
  /// Checks the cell at joints `q` (model order).
  CollisionResult Check(const JointVector& q, const CollisionOptions& options);
  /// Largest distance any point of a moving body travels between `a` and `b` (metres); the
  /// executor bounds its step with it so no contact slips between samples.
  double MaxPointTravel(const JointVector& a, const JointVector& b) const;
  /// Names of the bodies, in a fixed order (the trace's body table, CellDescription::bodies);
  /// every name in a CollisionResult is one of them.
  std::vector<std::string> BodyNames() const;

 private:
  explicit CollisionWorld(std::shared_ptr<const CollisionModel> model);
  std::shared_ptr<const CollisionModel> model_;
  std::unique_ptr<CollisionData> data_;
};

}  // namespace stitchsim::sim
