#pragma once
// The collision world as a model and per-query data, as MuJoCo's mjModel / mjData
// (docs/collision.md, "Model and data"): `CollisionModel` is built once and never changes
// (bodies, their FCL geometry, the links they ride on, the pair filter with the head's
// allowed contacts, broad-phase lists and motion bounds), so threads may share it;
// `CollisionData` is one caller's scratch (FCL objects at their current poses, link frames,
// boxes, near lists, the distance seed, the result cache). A query is
// CheckCollision(model, data, q, options).

#include <fcl/fcl.h>

#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "detail/collision_geometry.h"
#include "detail/collision_mjcf.h"
#include "detail/slab_depth.h"
#include "stitchsim/common/diagnostics.h"
#include "stitchsim/scene/scene.h"
#include "stitchsim/sim/cell.h"
#include "stitchsim/sim/collision.h"
#include "stitchsim/sim/kinematics.h"
#include "stitchsim/sim/robot_model.h"

namespace stitchsim::sim {
namespace detail {

enum class Group { kRobot, kCell, kPart };
enum class PartKind { kNone, kMold, kPreform, kConstraint };

/// One collision body: a rigid geometry fixed to a URDF link or to the part frame.
struct Body {
  std::string name;  ///< reported name: link, "head:<geom>", "mold", "constraint:<name>", ...
  Group group = Group::kCell;
  PartKind part = PartKind::kNone;
  int link = 0;                ///< URDF link the geometry is fixed to (ignored for the part)
  int rigid = 0;               ///< link index of the rigid group (links joined by fixed joints)
  bool allow_preform = false;  ///< the head spec allows its contact with the preform
  bool allow_mold = false;     ///< the head spec allows its contact with the mold
  bool moves = false;          ///< pose depends on q
  Eigen::Isometry3d local = Eigen::Isometry3d::Identity();  ///< in link (or part) frame, m
  Geometry geometry;                                        ///< shared, read-only during queries
  // How to rebuild it (the naive baseline rebuilds every query).
  MjcfShape shape = MjcfShape::kBox;
  Eigen::Vector3d size = Eigen::Vector3d::Zero();
  std::shared_ptr<const geom::TriangleMesh> mesh_m;  ///< part meshes, metres
  std::optional<Obb> fitted;  ///< meshes: a box fitted to the vertices, geometry frame
  DepthGeometry depth;        ///< robot bodies: where their slab depth is looked for
};

}  // namespace detail

/// Immutable after BuildCollisionModel. The scene and robot model it was made from must
/// outlive it.
class CollisionModel {
 public:
  explicit CollisionModel(const RobotModel& robot_model) : robot(robot_model) {}

  const RobotModel& robot;
  CellSetup cell;
  detail::Slab mold_slab, preform_slab;
  std::vector<detail::Body> bodies;
  int n = 0;                       ///< bodies.size()
  std::vector<bool> pair_checked;  ///< n x n: the pair filter
  std::vector<int> robot_bodies;   ///< indices of the robot bodies
  std::vector<int> robot_group;    ///< per robot_bodies entry: its travel_coeff index
  std::vector<int> fixed_env;      ///< environment bodies that never move
  std::vector<int> moving_env;     ///< environment bodies the rotator carries
  std::vector<int> moving_bodies;  ///< every body whose pose depends on q
  std::vector<std::pair<int, int>> robot_self_pairs;  ///< checked robot-robot pairs
  /// MaxPointTravel: per robot rigid group, metres per unit of each joint's motion.
  std::vector<JointVector> travel_coeff;
  double rotator_reach_m = 0.0;  ///< farthest rotator-carried point from its axis

  bool Checked(int i, int j) const { return pair_checked[static_cast<std::size_t>(i * n + j)]; }
  /// The mold / preform slab a part body is a tile of; nullptr for other bodies.
  const detail::Slab* SlabOf(const detail::Body& b) const {
    if (b.part == detail::PartKind::kMold) return &mold_slab;
    if (b.part == detail::PartKind::kPreform) return &preform_slab;
    return nullptr;
  }
};

/// One caller's per-query state for one model (not shared between threads).
class CollisionData {
 public:
  /// FCL objects for every body of `model`, placed at the home pose.
  explicit CollisionData(const CollisionModel& model);

  /// A robot body's broad-phase list: the fixed environment bodies whose boxes were within
  /// `radius` of its box at q_ref. While its motion bound since q_ref stays under
  /// (radius - cutoff) / sqrt(3), no other fixed body can have come within the cutoff.
  struct NearSet {
    std::vector<int> env;
    JointVector q_ref = JointVector::Zero();
    double radius = -1.0;  ///< cutoff + margin the list was made for (< 0: none yet)
  };
  struct Candidate {
    double bound;  ///< lower bound on the pair's distance (m)
    int i, j;
  };
  struct Cached {
    std::uint64_t key;  ///< hash of the query, compared first
    JointVector q;
    bool clearance;
    double cutoff;
    CollisionResult result;
  };
  static constexpr std::size_t kCacheSize = 512;

  std::vector<std::unique_ptr<fcl::CollisionObjectd>> objects;  ///< per body
  LinkFrames frames;
  /// Where the link frames come from: MuJoCo's kinematics when set (CollisionWorld::
  /// UseKinematics), else the URDF forward kinematics.
  MujocoCell* kinematics = nullptr;
  Eigen::Isometry3d part_world = Eigen::Isometry3d::Identity();  ///< at the last placement
  /// Per body, at its current placement: oriented box, and the world box around it (FCL's
  /// own object box is the bounding sphere's box once a body is rotated: far too loose).
  std::vector<detail::Obb> obb;
  std::vector<fcl::AABBd> box;
  std::vector<NearSet> near;                 ///< per model.robot_bodies entry
  bool placed = false;                       ///< fixed bodies have been placed
  std::vector<Candidate> candidates;         ///< reused distance candidate list
  std::pair<int, int> last_nearest{-1, -1};  ///< nearest pair of the last distance query
  /// Recent results (the executor and three rules ask about the same joints).
  std::vector<Cached> cache;
  std::size_t cache_next = 0;  ///< slot of the next entry (the oldest once full)
};

/// Builds the model of `scene` (MJCF robot, cell and head; the scene's part and constraints;
/// the head spec's allowed contacts); diagnostics and nullptr on failure.
std::shared_ptr<const CollisionModel> BuildCollisionModel(const scene::Scene& scene,
                                                          const RobotModel& robot,
                                                          DiagnosticSink& sink);

/// Checks the cell at joints `q` (model order) with `data`'s state.
CollisionResult CheckCollision(const CollisionModel& model, CollisionData& data,
                               const JointVector& q, const CollisionOptions& options);

/// CollisionWorld::MaxPointTravel of `model`.
double MaxPointTravel(const CollisionModel& model, const JointVector& a, const JointVector& b);

}  // namespace stitchsim::sim
