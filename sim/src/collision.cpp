// FCL collision world: bodies from the MJCF (robot, cell, head) and from the scene (mold,
// preform, constraints); a pair table says which pairs count; two dynamic AABB trees (robot,
// environment) are updated in place per query.
#include "stitchsim/sim/collision.h"

#include <fcl/fcl.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "detail/collision_mjcf.h"
#include "stitchsim/geom/surface.h"
#include "stitchsim/sim/cell.h"
#include "stitchsim/sim/kinematics.h"

namespace stitchsim::sim {
namespace {

using detail::MjcfShape;
using Geometry = std::shared_ptr<fcl::CollisionGeometryd>;

enum class Group { kRobot, kCell, kPart };
enum class PartKind { kNone, kMold, kPreform, kConstraint };

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
  std::unique_ptr<fcl::CollisionObjectd> object;
};

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

 private:
  struct CollideData {
    FclWorld* world;
    CollisionResult* result;
  };
  struct DistanceData {
    FclWorld* world;
    CollisionResult* result;
    double best;
    int a = -1, b = -1;
  };
  static bool CollideCallback(fcl::CollisionObjectd* o1, fcl::CollisionObjectd* o2, void* data);
  static bool DistanceCallback(fcl::CollisionObjectd* o1, fcl::CollisionObjectd* o2, void* data,
                               double& dist);
  int IndexOf(const fcl::CollisionObjectd* o) const {
    return static_cast<int>(reinterpret_cast<std::intptr_t>(o->getUserData()));
  }
  bool Checked(int i, int j) const { return pair_checked_[static_cast<std::size_t>(i * n_ + j)]; }
  void Place(const JointVector& q);
  void CheckPair(int i, int j, CollisionResult& result) const;
  CollisionResult CheckNaive(const JointVector& q, const CollisionOptions& options);
  void AddBody(Body body) { bodies_.push_back(std::move(body)); }
  int RigidOf(int link) const;

  const RobotModel& robot_;
  CellSetup cell_;
  LinkFrames frames_;
  std::vector<Body> bodies_;
  int n_ = 0;
  std::vector<bool> pair_checked_;
  fcl::DynamicAABBTreeCollisionManagerd robot_manager_, env_manager_;
  bool env_moves_ = false;  // the rotator carries bodies
  // MaxPointTravel: per robot rigid group, metres per unit of each joint's motion.
  std::vector<JointVector> travel_coeff_;
  double rotator_reach_m_ = 0.0;
  // Recent results (the executor and three rules ask about the same joints).
  struct Cached {
    JointVector q;
    bool clearance;
    double cutoff;
    CollisionResult result;
  };
  std::vector<Cached> cache_;
  std::size_t cache_next_ = 0;
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
    AddBody(std::move(b));
  }
  (void)rs535;
  // The part: mold slab below the surface, preform slab above it, constraints.
  const geom::Surface& s = *scene.surface;
  const double tol_mm = 1.0;
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
    AddBody(std::move(b));
  };
  add_part("mold", PartKind::kMold,
           geom::TessellateSlab(s, s.Domain(), -scene.mold_depth_mm, 0.0, tol_mm),
           Eigen::Isometry3d::Identity());
  add_part("preform", PartKind::kPreform,
           geom::TessellateSlab(s, s.Domain(), 0.0, scene.preform_thickness_mm, tol_mm),
           Eigen::Isometry3d::Identity());
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

  // FCL objects, registered once; robot and environment in separate trees.
  ForwardKinematics(robot_, HomeJoints(robot_, 0.0), frames_);
  for (int i = 0; i < n_; ++i) {
    Body& b = bodies_[static_cast<std::size_t>(i)];
    b.object = std::make_unique<fcl::CollisionObjectd>(b.geometry, fcl::Transform3d::Identity());
    b.object->setUserData(reinterpret_cast<void*>(static_cast<std::intptr_t>(i)));
    if (b.group == Group::kRobot) {
      robot_manager_.registerObject(b.object.get());
    } else {
      env_manager_.registerObject(b.object.get());
      env_moves_ = env_moves_ || b.moves;
    }
  }
  Place(HomeJoints(robot_, 0.0));
  robot_manager_.setup();
  env_manager_.setup();

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
  for (Body& b : bodies_) {
    const Eigen::Isometry3d frame =
        b.group == Group::kPart ? part : frames_.world_pose[static_cast<std::size_t>(b.link)];
    b.object->setTransform(ToFcl(frame * b.local));
    b.object->computeAABB();
  }
}

bool FclWorld::CollideCallback(fcl::CollisionObjectd* o1, fcl::CollisionObjectd* o2, void* data) {
  auto* d = static_cast<CollideData*>(data);
  const int i = d->world->IndexOf(o1), j = d->world->IndexOf(o2);
  if (d->world->Checked(i, j)) d->world->CheckPair(i, j, *d->result);
  return false;
}

void FclWorld::CheckPair(int i, int j, CollisionResult& result) const {
  const Body& a = bodies_[static_cast<std::size_t>(i)];
  const Body& b = bodies_[static_cast<std::size_t>(j)];
  fcl::CollisionRequestd req(1, true);
  fcl::CollisionResultd res;
  fcl::collide(a.object.get(), b.object.get(), req, res);
  if (!res.isCollision()) return;
  const fcl::Contactd& c = res.getContact(0);
  Contact out;
  out.kind = a.group == Group::kPart || b.group == Group::kPart ? ContactClass::kHeadPart
                                                                : ContactClass::kRobotCell;
  const bool swap = b.group == Group::kRobot && a.group != Group::kRobot;
  out.body_a = swap ? b.name : a.name;
  out.body_b = swap ? a.name : b.name;
  out.depth_m = std::isfinite(c.penetration_depth) ? std::abs(c.penetration_depth) : 0.0;
  out.point_world_m = c.pos;
  result.contacts.push_back(std::move(out));
}

bool FclWorld::DistanceCallback(fcl::CollisionObjectd* o1, fcl::CollisionObjectd* o2, void* data,
                                double& dist) {
  auto* d = static_cast<DistanceData*>(data);
  const int i = d->world->IndexOf(o1), j = d->world->IndexOf(o2);
  if (d->world->Checked(i, j)) {
    fcl::DistanceRequestd req;
    fcl::DistanceResultd res;
    fcl::distance(o1, o2, req, res);
    if (!std::isfinite(res.min_distance)) {
      d->result->error = "FCL distance query failed for " +
                         d->world->bodies_[static_cast<std::size_t>(i)].name + "|" +
                         d->world->bodies_[static_cast<std::size_t>(j)].name;
      return true;
    }
    const double v = std::max(0.0, res.min_distance);
    if (v < d->best) {
      d->best = v;
      d->a = i;
      d->b = j;
    }
  }
  dist = std::min(dist, d->best);
  return d->best <= 0.0;
}

CollisionResult FclWorld::Check(const JointVector& q, const CollisionOptions& options) {
  if (options.naive_baseline) return CheckNaive(q, options);
  for (const Cached& c : cache_) {
    if (c.q == q && c.clearance == options.compute_clearance &&
        c.cutoff == options.clearance_cutoff_m) {
      return c.result;
    }
  }
  CollisionResult result;
  Place(q);
  robot_manager_.update();
  if (env_moves_) env_manager_.update();
  CollideData cd{this, &result};
  robot_manager_.collide(&env_manager_, &cd, &FclWorld::CollideCallback);
  robot_manager_.collide(&cd, &FclWorld::CollideCallback);
  if (options.compute_clearance) {
    if (!result.contacts.empty()) {
      result.min_clearance_m = 0.0;
      result.min_clearance_pair =
          result.contacts.front().body_a + "|" + result.contacts.front().body_b;
    } else {
      DistanceData dd{this, &result, options.clearance_cutoff_m};
      robot_manager_.distance(&env_manager_, &dd, &FclWorld::DistanceCallback);
      robot_manager_.distance(&dd, &FclWorld::DistanceCallback);
      result.min_clearance_m = dd.best;
      if (dd.a >= 0) {
        result.min_clearance_pair = bodies_[static_cast<std::size_t>(dd.a)].name + "|" +
                                    bodies_[static_cast<std::size_t>(dd.b)].name;
      }
    }
  }
  Cached entry{q, options.compute_clearance, options.clearance_cutoff_m, result};
  if (cache_.size() < 64) {
    cache_.push_back(std::move(entry));
  } else {
    cache_[cache_next_] = std::move(entry);
    cache_next_ = (cache_next_ + 1) % cache_.size();
  }
  return result;
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
