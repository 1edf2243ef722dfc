// FCL collision world: bodies from the MJCF (robot, cell, head) and from the scene (mold,
// preform, constraints); a pair table says which pairs count; two dynamic AABB trees (robot,
// environment) are updated in place per query.
#include "stitchsim/sim/collision.h"

#include <fcl/fcl.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

#include "detail/collision_mjcf.h"
#include "detail/slab_depth.h"
#include "stitchsim/geom/surface.h"
#include "stitchsim/sim/cell.h"
#include "stitchsim/sim/kinematics.h"

namespace stitchsim::sim {
namespace {

using detail::MjcfShape;
using Geometry = std::shared_ptr<fcl::CollisionGeometryd>;

// Largest (u, v) extent of one mold or preform tile (mm).
constexpr double kPartTileMm = 600.0;
// Broad-phase margin: how far a robot body may move before its candidate list is rebuilt (m).
constexpr double kNearMarginM = 0.2;

enum class Group { kRobot, kCell, kPart };
enum class PartKind { kNone, kMold, kPreform, kConstraint };

// An oriented box bounding a body at its current pose: its geometry's local bounding box
// carried by the object's transform (tight for primitives and for part tiles, whose local
// frame is the part frame).
struct Obb {
  Eigen::Vector3d c;
  Eigen::Matrix3d r;
  Eigen::Vector3d e;
};

// One FCL object: a rigid geometry fixed to a URDF link or to the part frame.
struct Body {
  std::string name;  // reported name: link, "head:<geom>", "mold", "constraint:<name>", ...
  Group group = Group::kCell;
  PartKind part = PartKind::kNone;
  int link = 0;                // URDF link the geometry is fixed to (ignored for the part)
  int rigid = 0;               // link index of the rigid group (links joined by fixed joints)
  bool allow_preform = false;  // process contact with the preform is expected
  bool allow_mold = false;     // process contact with the mold is expected
  bool moves = false;          // pose depends on q
  Eigen::Isometry3d local = Eigen::Isometry3d::Identity();  // in link (or part) frame, m
  Geometry geometry;
  // How to rebuild it (the naive baseline rebuilds every query).
  MjcfShape shape = MjcfShape::kBox;
  Eigen::Vector3d size = Eigen::Vector3d::Zero();
  std::shared_ptr<const geom::TriangleMesh> mesh_m;  // part meshes, metres
  std::optional<Obb> fitted;    // meshes: a box fitted to the vertices, geometry frame
  detail::DepthGeometry depth;  // robot bodies: where their slab depth is looked for
  std::unique_ptr<fcl::CollisionObjectd> object;
};

// A box around a mesh along its principal axes (a tile of a curved slab: thin along its
// normal, where the box of its part-frame bounds would hold all its slope).
Obb FitObb(const geom::TriangleMesh& mesh_m) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& v : mesh_m.vertices) mean += v;
  mean /= static_cast<double>(std::max<std::size_t>(1, mesh_m.vertices.size()));
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const auto& v : mesh_m.vertices) cov += (v - mean) * (v - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  Eigen::Matrix3d r = eig.eigenvectors();
  if (r.determinant() < 0) r.col(0) = -r.col(0);
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = -lo;
  for (const auto& v : mesh_m.vertices) {
    const Eigen::Vector3d p = r.transpose() * (v - mean);
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return {mean + r * (0.5 * (lo + hi)), r, 0.5 * (hi - lo)};
}

fcl::Transform3d ToFcl(const Eigen::Isometry3d& t) {
  fcl::Transform3d out = fcl::Transform3d::Identity();
  out.linear() = t.linear();
  out.translation() = t.translation();
  return out;
}

Geometry MakePrimitive(MjcfShape shape, const Eigen::Vector3d& s) {
  switch (shape) {
    case MjcfShape::kBox:
      return std::make_shared<fcl::Boxd>(2 * s.x(), 2 * s.y(), 2 * s.z());
    case MjcfShape::kSphere:
      return std::make_shared<fcl::Sphered>(s.x());
    case MjcfShape::kCapsule:
      return std::make_shared<fcl::Capsuled>(s.x(), 2 * s.y());
    case MjcfShape::kCylinder:
      return std::make_shared<fcl::Cylinderd>(s.x(), 2 * s.y());
    case MjcfShape::kPlane:
      break;
  }
  return nullptr;
}

Geometry MakeMesh(const geom::TriangleMesh& mesh_m) {
  auto model = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
  std::vector<fcl::Vector3d> points(mesh_m.vertices.begin(), mesh_m.vertices.end());
  std::vector<fcl::Triangle> tris;
  tris.reserve(mesh_m.triangles.size());
  for (const auto& t : mesh_m.triangles) {
    tris.emplace_back(static_cast<std::size_t>(t[0]), static_cast<std::size_t>(t[1]),
                      static_cast<std::size_t>(t[2]));
  }
  model->beginModel(static_cast<int>(tris.size()), static_cast<int>(points.size()));
  model->addSubModel(points, tris);
  model->endModel();
  model->computeLocalAABB();
  return model;
}

geom::TriangleMesh ScaledMesh(const geom::TriangleMesh& mm, double scale) {
  geom::TriangleMesh out = mm;
  for (auto& v : out.vertices) v *= scale;
  return out;
}

Obb ObbOf(const Body& b) {
  const fcl::Transform3d& t = b.object->getTransform();
  if (b.fitted) return {t * b.fitted->c, t.linear() * b.fitted->r, b.fitted->e};
  const auto& box = b.object->collisionGeometry()->aabb_local;
  return {t * (0.5 * (box.min_ + box.max_)), t.linear(), 0.5 * (box.max_ - box.min_)};
}

fcl::AABBd BoxOf(const Obb& o) {
  const Eigen::Vector3d half = o.r.cwiseAbs() * o.e;
  return fcl::AABBd(o.c - half, o.c + half);
}

// A lower bound on the distance between two oriented boxes: the largest gap between their
// projections on the 15 separating-axis candidates (projection never lengthens a distance).
// 0 when they may touch. Stops early once an axis shows a gap of at least `enough`.
double ObbGapLowerBound(const Obb& a, const Obb& b,
                        double enough = std::numeric_limits<double>::infinity()) {
  // In a's frame: b's axes are the columns of r, its centre is at t.
  const Eigen::Matrix3d r = a.r.transpose() * b.r;
  const Eigen::Vector3d t = a.r.transpose() * (b.c - a.c);
  const Eigen::Matrix3d abs_r = r.cwiseAbs();
  double gap = 0.0;
  for (int i = 0; i < 3; ++i) {
    gap = std::max(gap, std::abs(t[i]) - a.e[i] - b.e.dot(abs_r.row(i)));
  }
  if (gap >= enough) return gap;
  for (int j = 0; j < 3; ++j) {
    gap = std::max(gap, std::abs(t.dot(r.col(j))) - a.e.dot(abs_r.col(j)) - b.e[j]);
  }
  if (gap >= enough) return gap;
  for (int i = 0; i < 3; ++i) {
    const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
    for (int j = 0; j < 3; ++j) {
      const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
      const double len2 = 1.0 - r(i, j) * r(i, j);  // |a_i x b_j|^2
      if (len2 < 1e-12) continue;
      const double sep = std::abs(t[i2] * r(i1, j) - t[i1] * r(i2, j)) -
                         (a.e[i1] * abs_r(i2, j) + a.e[i2] * abs_r(i1, j)) -
                         (b.e[j1] * abs_r(i, j2) + b.e[j2] * abs_r(i, j1));
      gap = std::max(gap, sep / std::sqrt(len2));
    }
  }
  return gap;
}

// A closed box as a mesh (for the support probe).
geom::TriangleMesh BoxMesh(double h) {
  geom::TriangleMesh m;
  for (int i = 0; i < 8; ++i) {
    m.vertices.emplace_back((i & 1) ? h : -h, (i & 2) ? h : -h, (i & 4) ? h : -h);
  }
  const int f[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                        {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  for (const auto& t : f) m.triangles.emplace_back(t[0], t[1], t[2]);
  return m;
}

// Which (node type, node type) pairs FCL really checks: two overlapping shapes must collide
// and two apart must have a positive distance. FCL answers "no contact" for a pair it does not
// support; this makes that an error instead.
std::string ProbePair(const Geometry& a, const Geometry& b) {
  fcl::CollisionObjectd oa(a, fcl::Transform3d::Identity());
  fcl::CollisionObjectd ob(b, fcl::Transform3d::Identity());
  fcl::CollisionRequestd creq(1, true);
  fcl::CollisionResultd cres;
  fcl::collide(&oa, &ob, creq, cres);
  if (!cres.isCollision()) return "overlapping shapes reported clear";
  fcl::Transform3d far = fcl::Transform3d::Identity();
  far.translation() = fcl::Vector3d(3.0, 0.0, 0.0);
  ob.setTransform(far);
  ob.computeAABB();
  fcl::DistanceRequestd dreq;
  fcl::DistanceResultd dres;
  fcl::distance(&oa, &ob, dreq, dres);
  if (!(dres.min_distance > 1.0 && dres.min_distance < 3.0)) return "distance query failed";
  return {};
}

Geometry ProbeShape(const fcl::CollisionGeometryd& g) {
  if (g.getObjectType() == fcl::OT_BVH) return MakeMesh(BoxMesh(0.1));
  switch (g.getNodeType()) {
    case fcl::GEOM_BOX:
      return std::make_shared<fcl::Boxd>(0.2, 0.2, 0.2);
    case fcl::GEOM_SPHERE:
      return std::make_shared<fcl::Sphered>(0.1);
    case fcl::GEOM_CAPSULE:
      return std::make_shared<fcl::Capsuled>(0.1, 0.2);
    case fcl::GEOM_CYLINDER:
      return std::make_shared<fcl::Cylinderd>(0.1, 0.2);
    default:
      return nullptr;
  }
}

class FclWorld final : public CollisionWorld {
 public:
  FclWorld(const RobotModel& robot, const CellSetup& cell) : robot_(robot), cell_(cell) {
    frames_ = MakeLinkFrames(robot);
  }

  bool Build(const scene::Scene& scene, DiagnosticSink& sink);
  CollisionResult Check(const JointVector& q, const CollisionOptions& options) override;
  double MaxPointTravel(const JointVector& a, const JointVector& b) const override;
  std::vector<std::string> BodyNames() const override {
    std::vector<std::string> names;
    for (const auto& b : bodies_) names.push_back(b.name);
    return names;
  }

 private:
  struct Candidate {
    double bound;  // lower bound on the pair's distance (m)
    int i, j;
  };
  bool Checked(int i, int j) const { return pair_checked_[static_cast<std::size_t>(i * n_ + j)]; }
  void Place(const JointVector& q);
  // Calls visit(i, j) for every pair that may interact: each robot body with its near list
  // and the rotator-carried bodies, then the robot-robot pairs (near lists current).
  template <class Visit>
  void ForEachPair(Visit&& visit) const;
  void CheckPair(int i, int j, CollisionResult& result) const;
  // The mold / preform slab a part body is a tile of; nullptr for other bodies.
  const detail::Slab* SlabOf(const Body& b) const {
    if (b.part == PartKind::kMold) return &mold_slab_;
    if (b.part == PartKind::kPreform) return &preform_slab_;
    return nullptr;
  }
  // Robot body `r` (placed at r_world) against a tile `p` of `slab`: FCL's verdict `hit`
  // (triangles crossed), else a body wholly inside the slab (its centre inside, `may_be_inside`
  // from the broad phase). The depth is measured on the analytic surface (slab_depth.h).
  void SlabContact(const Body& r, const Body& p, const detail::Slab& slab,
                   const Eigen::Isometry3d& r_world, const Eigen::Isometry3d& part_world, bool hit,
                   bool may_be_inside, CollisionResult& result) const;
  // Smallest distance over the checked pairs, up to `cutoff` (m); sets result's clearance,
  // pair or error.
  void Clearance(double cutoff, CollisionResult& result);
  CollisionResult CheckNaive(const JointVector& q, const CollisionOptions& options);
  void AddBody(Body body) { bodies_.push_back(std::move(body)); }
  int RigidOf(int link) const;

  const RobotModel& robot_;
  CellSetup cell_;
  detail::Slab mold_slab_, preform_slab_;
  Eigen::Isometry3d part_world_ = Eigen::Isometry3d::Identity();  // at the last Place
  LinkFrames frames_;
  std::vector<Body> bodies_;
  int n_ = 0;
  std::vector<bool> pair_checked_;
  // Broad phase. The environment is static but for what the rotator carries; the robot
  // moves a little between queries. Each robot body keeps the fixed environment bodies whose
  // boxes were within (cutoff + kNearMarginM) of its box when the list was made at q_ref;
  // while its motion bound since q_ref (MaxPointTravel's coefficients for its rigid group)
  // stays under the margin / sqrt(3), no other fixed body can come within the cutoff, so the
  // list is all the candidates there are. Rotator-carried bodies are always candidates;
  // robot-robot pairs are tested pair by pair.
  struct NearSet {
    std::vector<int> env;
    JointVector q_ref = JointVector::Zero();
    double radius = -1.0;  // cutoff + margin the list was made for (< 0: none yet)
  };
  void UpdateNear(std::size_t k, const JointVector& q, double cutoff);
  std::vector<int> robot_bodies_;
  std::vector<int> robot_group_;  // per robot_bodies_ entry: its travel_coeff_ index
  std::vector<NearSet> near_;     // per robot_bodies_ entry
  std::vector<int> fixed_env_, moving_env_;
  // Per body, at its current placement: oriented box, and the world box around it (FCL's
  // own object box is the bounding sphere's box once a body is rotated: far too loose).
  std::vector<Obb> obb_;
  std::vector<fcl::AABBd> box_;
  std::vector<std::pair<int, int>> robot_self_pairs_;  // checked robot-robot pairs
  bool placed_ = false;                                // fixed bodies have been placed
  std::vector<Candidate> candidates_;                  // reused distance candidate list
  std::pair<int, int> last_nearest_{-1, -1};           // nearest pair of the last distance query
  // MaxPointTravel: per robot rigid group, metres per unit of each joint's motion.
  std::vector<JointVector> travel_coeff_;
  double rotator_reach_m_ = 0.0;
  // Recent results (the executor and three rules ask about the same joints).
  struct Cached {
    std::uint64_t key;  // hash of the query, compared first
    JointVector q;
    bool clearance;
    double cutoff;
    CollisionResult result;
  };
  std::vector<Cached> cache_;
  std::size_t cache_next_ = 0;  // slot of the next entry (the oldest once full)
  static constexpr std::size_t kCacheSize = 512;
};

int FclWorld::RigidOf(int link) const {
  const auto& links = robot_.links();
  while (link > 0 && links[static_cast<std::size_t>(link)].joint < 0 &&
         links[static_cast<std::size_t>(link)].parent_link > 0) {
    link = links[static_cast<std::size_t>(link)].parent_link;
  }
  return link;
}

bool FclWorld::Build(const scene::Scene& scene, DiagnosticSink& sink) {
  std::vector<std::string> link_names;
  for (const auto& l : robot_.links()) link_names.push_back(l.name);
  bool ok = false;
  const auto geoms = detail::LoadMjcfGeoms(scene.cell_mjcf, scene.head.mjcf, link_names, sink, ok);
  if (!ok) return false;
  const bool rs535 = scene.head.kind == scene::HeadKind::kSingleSidedStitch;
  const bool rs566 = scene.head.kind == scene::HeadKind::kDoubleSidedStitch;
  const bool afp = scene.head.kind == scene::HeadKind::kAfp;
  const int rotator = robot_.rotator_link();
  for (const auto& g : geoms) {
    if (!g.in_head && scene.OmitsMjcfBody(g.top_body)) continue;  // cell.omit
    Body b;
    b.link = robot_.LinkIndex(g.link);
    if (b.link < 0) b.link = 0;
    b.rigid = RigidOf(b.link);
    b.local = g.pose_in_link;
    b.shape = g.shape;
    b.size = g.size;
    // Robot = anything moved by the rail or an arm joint (not the rotator).
    bool robot_body = false;
    for (int l : robot_.ChainTo(b.link)) {
      const int j = robot_.links()[static_cast<std::size_t>(l)].joint;
      if (j >= kRailX && j <= kA6) robot_body = true;
    }
    b.group = robot_body ? Group::kRobot : Group::kCell;
    b.moves = robot_body || b.rigid == rotator;
    b.name = g.in_head ? "head:" + g.name : (g.link == "world" ? g.name : g.link);
    if (g.in_head) {
      const std::string& n = g.name;
      const bool needle = n.rfind("needle", 0) == 0 && n != "needle_bar" && n != "needle_housing";
      // Needles pierce the preform (RS535: the catcher meets the stitching-tool surface);
      // the presser foot presses the preform top; the AFP roller compacts the laminate; the
      // RS566 table and lower C-frame arm run under the preform (where the mold is open).
      b.allow_preform = needle || n == "presser_foot" || (afp && n == "roller") ||
                        (rs566 && (n == "ee_table" || n == "cframe_lower_arm"));
      b.allow_mold = (needle && (rs535 || rs566)) || (afp && n == "roller") ||
                     (rs566 && (n == "ee_table" || n == "cframe_lower_arm"));
    }
    if (g.shape == MjcfShape::kPlane) {
      // The floor: a thick slab below the plane (FCL halfspaces have no finite AABB).
      b.shape = MjcfShape::kBox;
      b.size = Eigen::Vector3d(std::max(g.size.x(), 50.0), std::max(g.size.y(), 50.0), 0.5);
      b.local = g.pose_in_link * Eigen::Translation3d(0, 0, -0.5);
    }
    b.geometry = MakePrimitive(b.shape, b.size);
    if (b.group == Group::kRobot) b.depth = detail::PrimitiveDepthGeometry(b.shape, b.size);
    AddBody(std::move(b));
  }
  (void)rs535;
  // The part: mold slab below the surface, preform slab above it, constraints.
  const geom::Surface& s = *scene.surface;
  const double tol_mm = 1.0;
  mold_slab_ = {&s, -scene.mold_depth_mm, 0.0};
  preform_slab_ = {&s, 0.0, scene.preform_thickness_mm};
  auto add_part = [&](std::string name, PartKind kind, geom::TriangleMesh mesh_mm,
                      const Eigen::Isometry3d& local) {
    Body b;
    b.name = std::move(name);
    b.group = Group::kPart;
    b.part = kind;
    b.link = cell_.mount == scene::Mount::kRotator ? rotator : 0;
    b.rigid = b.link;
    b.moves = cell_.mount == scene::Mount::kRotator;
    b.local = local;
    b.mesh_m = std::make_shared<geom::TriangleMesh>(ScaledMesh(mesh_mm, 1e-3));
    b.geometry = MakeMesh(*b.mesh_m);
    b.fitted = FitObb(*b.mesh_m);
    AddBody(std::move(b));
  };
  // Tiles of at most kPartTileMm, so the broad phase drops the far parts of a large part
  // (one mesh over a wing cover would put every head geom inside its bounding box).
  for (auto& tile :
       geom::TessellateSlabTiles(s, s.Domain(), -scene.mold_depth_mm, 0.0, tol_mm, kPartTileMm)) {
    add_part("mold", PartKind::kMold, std::move(tile), Eigen::Isometry3d::Identity());
  }
  for (auto& tile : geom::TessellateSlabTiles(s, s.Domain(), 0.0, scene.preform_thickness_mm,
                                              tol_mm, kPartTileMm)) {
    add_part("preform", PartKind::kPreform, std::move(tile), Eigen::Isometry3d::Identity());
  }
  for (const auto& c : scene.constraints) {
    if (c.shape == scene::Constraint::Shape::kMesh) {
      add_part("constraint:" + c.name, PartKind::kConstraint, c.mesh,
               Eigen::Isometry3d::Identity());
      continue;
    }
    Body b;
    b.name = "constraint:" + c.name;
    b.group = Group::kPart;
    b.part = PartKind::kConstraint;
    b.link = cell_.mount == scene::Mount::kRotator ? rotator : 0;
    b.rigid = b.link;
    b.moves = cell_.mount == scene::Mount::kRotator;
    b.local = c.pose_mm;
    b.local.translation() /= 1000.0;
    b.shape = MjcfShape::kBox;
    b.size = c.size_mm / 2000.0;
    b.geometry = MakePrimitive(b.shape, b.size);
    AddBody(std::move(b));
  }
  n_ = static_cast<int>(bodies_.size());

  // Pair table.
  pair_checked_.assign(static_cast<std::size_t>(n_ * n_), false);
  const auto& links = robot_.links();
  auto adjacent = [&](int ra, int rb) {
    const int pa = RigidOf(links[static_cast<std::size_t>(ra)].parent_link);
    const int pb = RigidOf(links[static_cast<std::size_t>(rb)].parent_link);
    return pa == rb || pb == ra;
  };
  for (int i = 0; i < n_; ++i) {
    for (int j = i + 1; j < n_; ++j) {
      const Body& a = bodies_[static_cast<std::size_t>(i)];
      const Body& b = bodies_[static_cast<std::size_t>(j)];
      bool check = false;
      if (a.group == Group::kRobot || b.group == Group::kRobot) {
        const Body& r = a.group == Group::kRobot ? a : b;
        const Body& o = a.group == Group::kRobot ? b : a;
        if (o.group == Group::kRobot) {
          check = a.rigid != b.rigid && !adjacent(a.rigid, b.rigid);
        } else if (o.group == Group::kCell) {
          check = !(links[static_cast<std::size_t>(r.rigid)].name == "carriage" &&
                    links[static_cast<std::size_t>(o.rigid)].name == "rail");
        } else {
          check = !((o.part == PartKind::kPreform && r.allow_preform) ||
                    (o.part == PartKind::kMold && r.allow_mold));
        }
      }
      pair_checked_[static_cast<std::size_t>(i * n_ + j)] = check;
      pair_checked_[static_cast<std::size_t>(j * n_ + i)] = check;
    }
  }
  // Every shape pair that will be queried must really be supported by FCL.
  std::vector<std::pair<int, int>> probed;
  for (int i = 0; i < n_; ++i) {
    for (int j = i + 1; j < n_; ++j) {
      if (!Checked(i, j)) continue;
      const auto& ga = *bodies_[static_cast<std::size_t>(i)].geometry;
      const auto& gb = *bodies_[static_cast<std::size_t>(j)].geometry;
      const std::pair<int, int> key(ga.getNodeType(), gb.getNodeType());
      if (std::find(probed.begin(), probed.end(), key) != probed.end()) continue;
      probed.push_back(key);
      const Geometry pa = ProbeShape(ga), pb = ProbeShape(gb);
      const std::string err = pa && pb ? ProbePair(pa, pb) : "shape type not mapped";
      if (!err.empty()) {
        sink.Error("collision-unsupported-pair", {scene.file.string(), 0, 0},
                   "FCL cannot check " + bodies_[static_cast<std::size_t>(i)].name + " against " +
                       bodies_[static_cast<std::size_t>(j)].name + ": " + err);
        return false;
      }
    }
  }

  // FCL objects, created once; robot bodies and the fixed and moving environment listed apart.
  for (int i = 0; i < n_; ++i) {
    Body& b = bodies_[static_cast<std::size_t>(i)];
    b.object = std::make_unique<fcl::CollisionObjectd>(b.geometry, fcl::Transform3d::Identity());
    if (b.group == Group::kRobot) {
      robot_bodies_.push_back(i);
    } else {
      (b.moves ? moving_env_ : fixed_env_).push_back(i);
    }
  }
  for (std::size_t a = 0; a < robot_bodies_.size(); ++a) {
    for (std::size_t c = a + 1; c < robot_bodies_.size(); ++c) {
      if (Checked(robot_bodies_[a], robot_bodies_[c])) {
        robot_self_pairs_.emplace_back(robot_bodies_[a], robot_bodies_[c]);
      }
    }
  }
  obb_.resize(static_cast<std::size_t>(n_));
  box_.resize(static_cast<std::size_t>(n_));
  near_.assign(robot_bodies_.size(), NearSet{});
  Place(HomeJoints(robot_, 0.0));

  // MaxPointTravel coefficients: for each robot rigid group, the reach from each joint it
  // hangs on to its farthest point (chain of link offsets + bounding sphere), q-independent.
  std::vector<int> groups;
  for (const Body& b : bodies_) {
    if (b.group == Group::kRobot &&
        std::find(groups.begin(), groups.end(), b.link) == groups.end()) {
      groups.push_back(b.link);
    }
  }
  for (int link : groups) {
    double far = 0.0;  // farthest geometry point from the link origin
    for (const Body& b : bodies_) {
      if (b.link != link || b.group != Group::kRobot) continue;
      const auto& box = b.geometry->aabb_local;
      const double r = 0.5 * (box.max_ - box.min_).norm();
      far = std::max(far, (b.local * (0.5 * (box.max_ + box.min_))).norm() + r);
    }
    JointVector coeff = JointVector::Zero();
    const auto& chain = robot_.ChainTo(link);
    for (std::size_t k = 0; k < chain.size(); ++k) {
      const auto& lk = links[static_cast<std::size_t>(chain[k])];
      if (lk.joint < 0) continue;
      if (robot_.joint(lk.joint).type == JointType::kPrismatic) {
        coeff[lk.joint] = 1.0;
        continue;
      }
      double reach = far;
      for (std::size_t m = k + 1; m < chain.size(); ++m) {
        reach += links[static_cast<std::size_t>(chain[m])].origin.translation().norm();
      }
      coeff[lk.joint] = reach;
    }
    travel_coeff_.push_back(coeff);
  }
  for (int i : robot_bodies_) {
    const int link = bodies_[static_cast<std::size_t>(i)].link;
    robot_group_.push_back(
        static_cast<int>(std::find(groups.begin(), groups.end(), link) - groups.begin()));
  }
  for (const Body& b : bodies_) {
    if (b.group == Group::kRobot || !b.moves) continue;
    const auto& box = b.geometry->aabb_local;
    for (int c = 0; c < 8; ++c) {
      const Eigen::Vector3d corner((c & 1) ? box.max_.x() : box.min_.x(),
                                   (c & 2) ? box.max_.y() : box.min_.y(),
                                   (c & 4) ? box.max_.z() : box.min_.z());
      const Eigen::Vector3d p =
          (b.part != PartKind::kNone ? cell_.mount_to_part_m : Eigen::Isometry3d::Identity()) *
          (b.local * corner);
      rotator_reach_m_ = std::max(rotator_reach_m_, p.head<2>().norm());
    }
  }
  return true;
}

void FclWorld::Place(const JointVector& q) {
  ForwardKinematics(robot_, q, frames_);
  const Eigen::Isometry3d part = PartPoseWorld(cell_, q[kRotator]);
  part_world_ = part;
  for (Body& b : bodies_) {
    if (placed_ && !b.moves) continue;  // fixed bodies keep their first placement
    const Eigen::Isometry3d frame =
        b.group == Group::kPart ? part : frames_.world_pose[static_cast<std::size_t>(b.link)];
    b.object->setTransform(ToFcl(frame * b.local));
    const std::size_t i = static_cast<std::size_t>(&b - bodies_.data());
    obb_[i] = ObbOf(b);
    box_[i] = BoxOf(obb_[i]);
  }
  placed_ = true;
}

void FclWorld::CheckPair(int i, int j, CollisionResult& result) const {
  const Body& a = bodies_[static_cast<std::size_t>(i)];
  const Body& b = bodies_[static_cast<std::size_t>(j)];
  fcl::CollisionRequestd req(1, true);
  fcl::CollisionResultd res;
  fcl::collide(a.object.get(), b.object.get(), req, res);
  const bool swap = b.group == Group::kRobot && a.group != Group::kRobot;
  const Body& r = swap ? b : a;  // the robot body (a robot-robot pair: a)
  const Body& o = swap ? a : b;
  if (const detail::Slab* slab = SlabOf(o); slab != nullptr && r.group == Group::kRobot) {
    const std::size_t ri = static_cast<std::size_t>(swap ? j : i);
    const Obb& tile = obb_[static_cast<std::size_t>(swap ? i : j)];
    const Eigen::Vector3d d = tile.r.transpose() * (obb_[ri].c - tile.c);
    const bool centre_in_tile_box = (d.cwiseAbs() - tile.e).maxCoeff() <= 0.0;
    SlabContact(r, o, *slab, Eigen::Isometry3d(r.object->getTransform().matrix()), part_world_,
                res.isCollision(), centre_in_tile_box, result);
    return;
  }
  if (!res.isCollision()) return;
  const fcl::Contactd& c = res.getContact(0);
  Contact out;
  out.kind = a.group == Group::kPart || b.group == Group::kPart ? ContactClass::kHeadPart
                                                                : ContactClass::kRobotCell;
  out.body_a = r.name;
  out.body_b = o.name;
  out.depth_measured = !a.mesh_m && !b.mesh_m;
  out.depth_m = out.depth_measured && std::isfinite(c.penetration_depth)
                    ? std::abs(c.penetration_depth)
                    : 0.0;
  out.point_world_m = c.pos;
  result.contacts.push_back(std::move(out));
}

void FclWorld::SlabContact(const Body& r, const Body& p, const detail::Slab& slab,
                           const Eigen::Isometry3d& r_world, const Eigen::Isometry3d& part_world,
                           bool hit, bool may_be_inside, CollisionResult& result) const {
  for (const Contact& c : result.contacts) {
    if (c.body_a == r.name && c.body_b == p.name) return;  // another tile of the same slab
  }
  // FCL meshes are hollow: a body wholly inside the slab crosses no triangle. A primitive's
  // centre is its frame's origin.
  if (!hit && !(may_be_inside && detail::InsideSlab(r_world.translation(), part_world, slab))) {
    return;
  }
  // The mesh detects (its chords may stand up to the tessellation tolerance proud of the
  // surface); the surface measures. No sample below the head-side face: no penetration.
  const auto deepest = detail::DeepestInSlab(r.depth, r_world, part_world, slab);
  if (!deepest || deepest->depth_m <= 0.0) return;
  Contact out;
  out.kind = ContactClass::kHeadPart;
  out.body_a = r.name;
  out.body_b = p.name;
  out.depth_m = deepest->depth_m;
  out.point_world_m = deepest->point_world_m;
  result.contacts.push_back(std::move(out));
}

template <class Visit>
void FclWorld::ForEachPair(Visit&& visit) const {
  for (std::size_t k = 0; k < robot_bodies_.size(); ++k) {
    for (int e : near_[k].env) visit(robot_bodies_[k], e);
    for (int e : moving_env_) visit(robot_bodies_[k], e);
  }
  for (const auto& [i, j] : robot_self_pairs_) visit(i, j);
}

void FclWorld::UpdateNear(std::size_t k, const JointVector& q, double cutoff) {
  NearSet& n = near_[k];
  if (n.radius >= cutoff) {
    const double travel =
        travel_coeff_[static_cast<std::size_t>(robot_group_[k])].dot((q - n.q_ref).cwiseAbs());
    if (std::sqrt(3.0) * travel < n.radius - cutoff) return;
  }
  n.env.clear();
  n.q_ref = q;
  n.radius = cutoff + kNearMarginM;
  const fcl::AABBd& box = box_[static_cast<std::size_t>(robot_bodies_[k])];
  for (int e : fixed_env_) {
    if (box.distance(box_[static_cast<std::size_t>(e)]) < n.radius) {
      n.env.push_back(e);
    }
  }
}

CollisionResult FclWorld::Check(const JointVector& q, const CollisionOptions& options) {
  if (options.naive_baseline) return CheckNaive(q, options);
  std::uint64_t key = 1469598103934665603ull;  // FNV-1a over the query's bytes
  auto mix = [&key](const void* p, std::size_t n) {
    for (std::size_t k = 0; k < n; ++k) {
      key = (key ^ static_cast<const unsigned char*>(p)[k]) * 1099511628211ull;
    }
  };
  mix(q.data(), sizeof(double) * static_cast<std::size_t>(q.size()));
  mix(&options.clearance_cutoff_m, sizeof(double));
  key ^= options.compute_clearance ? 1u : 0u;
  // Newest first: the rules ask about the sample just placed; the executor's look-ahead over
  // a long line may have placed a few hundred samples since.
  for (std::size_t n = 0; n < cache_.size(); ++n) {
    const Cached& c = cache_[(cache_next_ + cache_.size() - 1 - n) % cache_.size()];
    if (c.key == key && c.q == q && c.clearance == options.compute_clearance &&
        c.cutoff == options.clearance_cutoff_m) {
      return c.result;
    }
  }
  CollisionResult result;
  Place(q);
  const double cutoff = std::max(options.clearance_cutoff_m, 0.0);
  for (std::size_t k = 0; k < robot_bodies_.size(); ++k) UpdateNear(k, q, cutoff);
  // Overlapping world boxes of tilted or large bodies often have separated oriented boxes.
  ForEachPair([&](int i, int j) {
    const auto a = static_cast<std::size_t>(i), b = static_cast<std::size_t>(j);
    if (Checked(i, j) && box_[a].overlap(box_[b]) &&
        ObbGapLowerBound(obb_[a], obb_[b], 1e-12) <= 0.0) {
      CheckPair(i, j, result);
    }
  });
  if (options.compute_clearance) {
    if (!result.contacts.empty()) {
      result.min_clearance_m = 0.0;
      result.min_clearance_pair =
          result.contacts.front().body_a + "|" + result.contacts.front().body_b;
    } else {
      Clearance(cutoff, result);
    }
  }
  Cached entry{key, q, options.compute_clearance, options.clearance_cutoff_m, result};
  if (cache_.size() < kCacheSize) {
    cache_.push_back(std::move(entry));
    cache_next_ = cache_.size() % kCacheSize;
  } else {
    cache_[cache_next_] = std::move(entry);
    cache_next_ = (cache_next_ + 1) % kCacheSize;
  }
  return result;
}

void FclWorld::Clearance(double cutoff, CollisionResult& result) {
  double best = cutoff;
  int best_i = -1, best_j = -1;
  // Measures pair (i, j) exactly; false (and result.error) if FCL fails on it.
  auto measure = [&](int i, int j) {
    fcl::DistanceRequestd req;
    fcl::DistanceResultd res;
    fcl::distance(bodies_[static_cast<std::size_t>(i)].object.get(),
                  bodies_[static_cast<std::size_t>(j)].object.get(), req, res);
    if (!std::isfinite(res.min_distance)) {
      result.error = "FCL distance query failed for " + bodies_[static_cast<std::size_t>(i)].name +
                     "|" + bodies_[static_cast<std::size_t>(j)].name;
      return false;
    }
    if (std::max(0.0, res.min_distance) < best) {
      best = std::max(0.0, res.min_distance);
      best_i = i;
      best_j = j;
    }
    return true;
  };
  // The pair nearest at the previous query first: a true clearance, after which far fewer
  // pairs pass the bounds.
  const std::pair<int, int> seeded = last_nearest_;
  if (seeded.first >= 0 && !measure(seeded.first, seeded.second)) return;
  // Candidates: world boxes closer than the best so far, then an oriented-box lower bound.
  candidates_.clear();
  ForEachPair([&](int i, int j) {
    const auto a = static_cast<std::size_t>(i), b = static_cast<std::size_t>(j);
    if (!Checked(i, j) || box_[a].distance(box_[b]) >= best) return;
    const double lb = ObbGapLowerBound(obb_[a], obb_[b], best);
    if (lb < best) candidates_.push_back({lb, i, j});
  });
  // Exact distances nearest-bound first; a pair whose bound is no less than the best distance
  // so far cannot lower it (the result equals measuring every candidate).
  std::sort(candidates_.begin(), candidates_.end(),
            [](const Candidate& x, const Candidate& y) { return x.bound < y.bound; });
  for (const Candidate& c : candidates_) {
    if (c.bound >= best || best <= 0.0) break;
    const bool is_seed = (c.i == seeded.first && c.j == seeded.second) ||
                         (c.j == seeded.first && c.i == seeded.second);
    if (!is_seed && !measure(c.i, c.j)) return;
  }
  last_nearest_ = {best_i, best_j};
  result.min_clearance_m = best;
  if (best_i >= 0) {
    result.min_clearance_pair = bodies_[static_cast<std::size_t>(best_i)].name + "|" +
                                bodies_[static_cast<std::size_t>(best_j)].name;
  }
}

// The benchmark baseline: objects rebuilt from scratch and every checked pair queried.
CollisionResult FclWorld::CheckNaive(const JointVector& q, const CollisionOptions& options) {
  CollisionResult result;
  ForwardKinematics(robot_, q, frames_);
  const Eigen::Isometry3d part = PartPoseWorld(cell_, q[kRotator]);
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> objects;
  for (const Body& b : bodies_) {
    const Geometry g = b.mesh_m ? MakeMesh(*b.mesh_m) : MakePrimitive(b.shape, b.size);
    const Eigen::Isometry3d frame =
        b.group == Group::kPart ? part : frames_.world_pose[static_cast<std::size_t>(b.link)];
    objects.push_back(std::make_unique<fcl::CollisionObjectd>(g, ToFcl(frame * b.local)));
  }
  double best = options.clearance_cutoff_m;
  for (int i = 0; i < n_; ++i) {
    for (int j = i + 1; j < n_; ++j) {
      if (!Checked(i, j)) continue;
      fcl::CollisionRequestd req(1, true);
      fcl::CollisionResultd res;
      fcl::collide(objects[static_cast<std::size_t>(i)].get(),
                   objects[static_cast<std::size_t>(j)].get(), req, res);
      const Body& a = bodies_[static_cast<std::size_t>(i)];
      const Body& b = bodies_[static_cast<std::size_t>(j)];
      const bool swap = b.group == Group::kRobot;
      const detail::Slab* slab = SlabOf(swap ? a : b);
      if (slab != nullptr && (swap ? b : a).group == Group::kRobot) {
        const std::size_t before = result.contacts.size();
        const auto& tf = objects[static_cast<std::size_t>(swap ? j : i)]->getTransform();
        SlabContact(swap ? b : a, swap ? a : b, *slab, Eigen::Isometry3d(tf.matrix()), part,
                    res.isCollision(), true, result);
        if (res.isCollision() || result.contacts.size() > before) {
          best = 0.0;
          continue;
        }
      }
      if (res.isCollision()) {
        Contact c;
        c.body_a = bodies_[static_cast<std::size_t>(i)].name;
        c.body_b = bodies_[static_cast<std::size_t>(j)].name;
        c.depth_m = std::abs(res.getContact(0).penetration_depth);
        c.point_world_m = res.getContact(0).pos;
        result.contacts.push_back(c);
        best = 0.0;
      } else if (options.compute_clearance) {
        fcl::DistanceRequestd dreq;
        fcl::DistanceResultd dres;
        fcl::distance(objects[static_cast<std::size_t>(i)].get(),
                      objects[static_cast<std::size_t>(j)].get(), dreq, dres);
        best = std::min(best, std::max(0.0, dres.min_distance));
      }
    }
  }
  result.min_clearance_m = best;
  return result;
}

double FclWorld::MaxPointTravel(const JointVector& a, const JointVector& b) const {
  const JointVector dq = (b - a).cwiseAbs();
  double worst = 0.0;
  for (const JointVector& c : travel_coeff_) worst = std::max(worst, c.dot(dq));
  return worst + rotator_reach_m_ * dq[kRotator];
}

}  // namespace

std::unique_ptr<CollisionWorld> CollisionWorld::Create(const scene::Scene& scene,
                                                       const RobotModel& robot,
                                                       DiagnosticSink& sink) {
  auto world = std::make_unique<FclWorld>(robot, MakeCellSetup(robot, scene));
  if (!world->Build(scene, sink)) return nullptr;
  return world;
}

}  // namespace stitchsim::sim
