// Builds the collision model: bodies from the MJCF (robot, cell, head) and from the scene
// (mold, preform, constraints), the pair filter, the FCL support probe, the broad-phase lists
// and the motion bounds (docs/collision.md).
#include "detail/collision_model.h"

#include <algorithm>
#include <cmath>

#include "stitchsim/geom/surface.h"

namespace stitchsim::sim {
namespace {

using detail::Body;
using detail::Group;
using detail::MjcfShape;
using detail::PartKind;

// Largest (u, v) extent of one mold or preform tile (mm).
constexpr double kPartTileMm = 600.0;

// The link index of the rigid group `link` belongs to (links joined by fixed joints).
int RigidOf(const RobotModel& robot, int link) {
  const auto& links = robot.links();
  while (link > 0 && links[static_cast<std::size_t>(link)].joint < 0 &&
         links[static_cast<std::size_t>(link)].parent_link > 0) {
    link = links[static_cast<std::size_t>(link)].parent_link;
  }
  return link;
}

// Robot = anything moved by the rail or an arm joint (not the rotator).
bool RidesOnTheRobot(const RobotModel& robot, int link) {
  for (int l : robot.ChainTo(link)) {
    const int j = robot.links()[static_cast<std::size_t>(l)].joint;
    if (j >= kRailX && j <= kA6) return true;
  }
  return false;
}

// Marks the process contacts the head spec allows head geom `name` (head:<name> vs preform /
// mold).
void AllowProcessContacts(const scene::HeadSpec& head, const std::string& name, Body& b) {
  for (const scene::AllowedContact& c : head.allowed_contacts) {
    if (!c.Matches(name)) continue;
    b.allow_preform = b.allow_preform || c.preform;
    b.allow_mold = b.allow_mold || c.mold;
  }
}

// Every allowed contact of the head spec names a geom of the head's MJCF; else an error at
// its entry in the head file.
bool AllowedContactsNameHeadGeoms(const scene::HeadSpec& head,
                                  const std::vector<detail::MjcfGeom>& geoms,
                                  DiagnosticSink& sink) {
  std::string names;
  for (const auto& g : geoms) {
    if (g.in_head) names += (names.empty() ? "" : ", ") + g.name;
  }
  bool ok = true;
  for (const scene::AllowedContact& c : head.allowed_contacts) {
    const bool found = std::any_of(geoms.begin(), geoms.end(), [&](const detail::MjcfGeom& g) {
      return g.in_head && c.Matches(g.name);
    });
    if (found) continue;
    sink.Error("head-unknown-body", c.where,
               "allowed_contacts: no geom of " + head.mjcf.filename().string() + " is named '" +
                   c.head + "' (its geoms: " + names + ")");
    ok = false;
  }
  return ok;
}

// The body of one compiled MJCF geom (robot, cell or head).
Body BodyOfGeom(const CollisionModel& model, const scene::Scene& scene, const detail::MjcfGeom& g) {
  const RobotModel& robot = model.robot;
  Body b;
  b.link = std::max(robot.LinkIndex(g.link), 0);
  b.rigid = RigidOf(robot, b.link);
  b.local = g.pose_in_link;
  b.shape = g.shape;
  b.size = g.size;
  const bool robot_body = RidesOnTheRobot(robot, b.link);
  b.group = robot_body ? Group::kRobot : Group::kCell;
  b.moves = robot_body || b.rigid == robot.rotator_link();
  b.name = g.in_head ? "head:" + g.name : (g.link == "world" ? g.name : g.link);
  if (g.in_head) AllowProcessContacts(scene.head, g.name, b);
  if (g.shape == MjcfShape::kPlane) {
    // The floor: a thick slab below the plane (FCL halfspaces have no finite AABB).
    b.shape = MjcfShape::kBox;
    b.size = Eigen::Vector3d(std::max(g.size.x(), 50.0), std::max(g.size.y(), 50.0), 0.5);
    b.local = g.pose_in_link * Eigen::Translation3d(0, 0, -0.5);
  }
  b.geometry = detail::MakePrimitive(b.shape, b.size);
  if (b.group == Group::kRobot) b.depth = detail::PrimitiveDepthGeometry(b.shape, b.size);
  return b;
}

// A part body (mold or preform tile, constraint) riding on the table or the rotator.
Body PartBody(const CollisionModel& model, std::string name, PartKind kind) {
  Body b;
  b.name = std::move(name);
  b.group = Group::kPart;
  b.part = kind;
  b.link = model.cell.mount == scene::Mount::kRotator ? model.robot.rotator_link() : 0;
  b.rigid = b.link;
  b.moves = model.cell.mount == scene::Mount::kRotator;
  return b;
}

void AddMeshPart(CollisionModel& model, std::string name, PartKind kind,
                 const geom::TriangleMesh& mesh_mm) {
  Body b = PartBody(model, std::move(name), kind);
  b.mesh_m = std::make_shared<geom::TriangleMesh>(detail::ScaledMesh(mesh_mm, 1e-3));
  b.geometry = detail::MakeMesh(*b.mesh_m);
  b.fitted = detail::FitObb(*b.mesh_m);
  model.bodies.push_back(std::move(b));
}

// The part: mold slab below the surface, preform slab above it, constraints.
void AddPartBodies(CollisionModel& model, const scene::Scene& scene) {
  const geom::Surface& s = *scene.surface;
  const double tol_mm = 1.0;
  model.mold_slab = {&s, -scene.mold_depth_mm, 0.0};
  model.preform_slab = {&s, 0.0, scene.preform_thickness_mm};
  // Tiles of at most kPartTileMm, so the broad phase drops the far parts of a large part
  // (one mesh over a wing cover would put every head geom inside its bounding box).
  for (auto& tile :
       geom::TessellateSlabTiles(s, s.Domain(), -scene.mold_depth_mm, 0.0, tol_mm, kPartTileMm)) {
    AddMeshPart(model, "mold", PartKind::kMold, tile);
  }
  for (auto& tile : geom::TessellateSlabTiles(s, s.Domain(), 0.0, scene.preform_thickness_mm,
                                              tol_mm, kPartTileMm)) {
    AddMeshPart(model, "preform", PartKind::kPreform, tile);
  }
  for (const auto& c : scene.constraints) {
    if (c.shape == scene::Constraint::Shape::kMesh) {
      AddMeshPart(model, "constraint:" + c.name, PartKind::kConstraint, c.mesh);
      continue;
    }
    Body b = PartBody(model, "constraint:" + c.name, PartKind::kConstraint);
    b.local = c.pose_mm;
    b.local.translation() /= 1000.0;
    b.shape = MjcfShape::kBox;
    b.size = c.size_mm / 2000.0;
    b.geometry = detail::MakePrimitive(b.shape, b.size);
    model.bodies.push_back(std::move(b));
  }
}

// Whether the pair (a, b) counts: robot vs cell (not carriage vs rail), robot vs part (not
// an allowed process contact), robot vs robot (not one rigid body, not parent and child).
bool PairCounts(const RobotModel& robot, const Body& a, const Body& b) {
  if (a.group != Group::kRobot && b.group != Group::kRobot) return false;
  const auto& links = robot.links();
  const Body& r = a.group == Group::kRobot ? a : b;
  const Body& o = a.group == Group::kRobot ? b : a;
  if (o.group == Group::kRobot) {
    const int pa = RigidOf(robot, links[static_cast<std::size_t>(a.rigid)].parent_link);
    const int pb = RigidOf(robot, links[static_cast<std::size_t>(b.rigid)].parent_link);
    return a.rigid != b.rigid && !(pa == b.rigid || pb == a.rigid);
  }
  if (o.group == Group::kCell) {
    return !(links[static_cast<std::size_t>(r.rigid)].name == "carriage" &&
             links[static_cast<std::size_t>(o.rigid)].name == "rail");
  }
  return !((o.part == PartKind::kPreform && r.allow_preform) ||
           (o.part == PartKind::kMold && r.allow_mold));
}

void BuildPairFilter(CollisionModel& model) {
  const int n = model.n;
  model.pair_checked.assign(static_cast<std::size_t>(n * n), false);
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      const bool check = PairCounts(model.robot, model.bodies[static_cast<std::size_t>(i)],
                                    model.bodies[static_cast<std::size_t>(j)]);
      model.pair_checked[static_cast<std::size_t>(i * n + j)] = check;
      model.pair_checked[static_cast<std::size_t>(j * n + i)] = check;
    }
  }
}

// Every shape pair that will be queried must really be supported by FCL.
bool ProbeCheckedPairs(const CollisionModel& model, const scene::Scene& scene,
                       DiagnosticSink& sink) {
  std::vector<std::pair<int, int>> probed;
  for (int i = 0; i < model.n; ++i) {
    for (int j = i + 1; j < model.n; ++j) {
      if (!model.Checked(i, j)) continue;
      const auto& ga = *model.bodies[static_cast<std::size_t>(i)].geometry;
      const auto& gb = *model.bodies[static_cast<std::size_t>(j)].geometry;
      const std::pair<int, int> key(ga.getNodeType(), gb.getNodeType());
      if (std::find(probed.begin(), probed.end(), key) != probed.end()) continue;
      probed.push_back(key);
      const std::string err = detail::ProbeFclSupport(ga, gb);
      if (!err.empty()) {
        sink.Error("collision-unsupported-pair", {scene.file.string(), 0, 0},
                   "FCL cannot check " + model.bodies[static_cast<std::size_t>(i)].name +
                       " against " + model.bodies[static_cast<std::size_t>(j)].name + ": " + err);
        return false;
      }
    }
  }
  return true;
}

// Robot bodies and the fixed and moving environment listed apart; the checked robot pairs.
void ListBroadPhaseGroups(CollisionModel& model) {
  for (int i = 0; i < model.n; ++i) {
    const Body& b = model.bodies[static_cast<std::size_t>(i)];
    if (b.moves) model.moving_bodies.push_back(i);
    if (b.group == Group::kRobot) {
      model.robot_bodies.push_back(i);
    } else {
      (b.moves ? model.moving_env : model.fixed_env).push_back(i);
    }
  }
  const auto& robot = model.robot_bodies;
  for (std::size_t a = 0; a < robot.size(); ++a) {
    for (std::size_t c = a + 1; c < robot.size(); ++c) {
      if (model.Checked(robot[a], robot[c]))
        model.robot_self_pairs.emplace_back(robot[a], robot[c]);
    }
  }
}

// For the robot bodies on `link`: the reach from each joint the link hangs on to their
// farthest point (chain of link offsets + bounding sphere), q-independent; 1 for a prismatic
// joint.
JointVector TravelCoefficients(const CollisionModel& model, int link) {
  double far = 0.0;  // farthest geometry point from the link origin
  for (const Body& b : model.bodies) {
    if (b.link != link || b.group != Group::kRobot) continue;
    const auto& box = b.geometry->aabb_local;
    const double r = 0.5 * (box.max_ - box.min_).norm();
    far = std::max(far, (b.local * (0.5 * (box.max_ + box.min_))).norm() + r);
  }
  const auto& links = model.robot.links();
  JointVector coeff = JointVector::Zero();
  const auto& chain = model.robot.ChainTo(link);
  for (std::size_t k = 0; k < chain.size(); ++k) {
    const auto& lk = links[static_cast<std::size_t>(chain[k])];
    if (lk.joint < 0) continue;
    if (model.robot.joint(lk.joint).type == JointType::kPrismatic) {
      coeff[lk.joint] = 1.0;
      continue;
    }
    double reach = far;
    for (std::size_t m = k + 1; m < chain.size(); ++m) {
      reach += links[static_cast<std::size_t>(chain[m])].origin.translation().norm();
    }
    coeff[lk.joint] = reach;
  }
  return coeff;
}

// MaxPointTravel's terms: coefficients per robot rigid group, and the rotator's reach.
void ComputeMotionBounds(CollisionModel& model) {
  std::vector<int> groups;
  for (const Body& b : model.bodies) {
    if (b.group == Group::kRobot &&
        std::find(groups.begin(), groups.end(), b.link) == groups.end()) {
      groups.push_back(b.link);
    }
  }
  for (int link : groups) model.travel_coeff.push_back(TravelCoefficients(model, link));
  for (int i : model.robot_bodies) {
    const int link = model.bodies[static_cast<std::size_t>(i)].link;
    model.robot_group.push_back(
        static_cast<int>(std::find(groups.begin(), groups.end(), link) - groups.begin()));
  }
  for (const Body& b : model.bodies) {
    if (b.group == Group::kRobot || !b.moves) continue;
    const auto& box = b.geometry->aabb_local;
    for (int c = 0; c < 8; ++c) {
      const Eigen::Vector3d corner((c & 1) ? box.max_.x() : box.min_.x(),
                                   (c & 2) ? box.max_.y() : box.min_.y(),
                                   (c & 4) ? box.max_.z() : box.min_.z());
      const Eigen::Vector3d p =
          (b.part != PartKind::kNone ? model.cell.mount_to_part_m : Eigen::Isometry3d::Identity()) *
          (b.local * corner);
      model.rotator_reach_m = std::max(model.rotator_reach_m, p.head<2>().norm());
    }
  }
}

}  // namespace

std::shared_ptr<const CollisionModel> BuildCollisionModel(const scene::Scene& scene,
                                                          const RobotModel& robot,
                                                          DiagnosticSink& sink) {
  auto model = std::make_shared<CollisionModel>(robot);
  model->cell = MakeCellSetup(robot, scene);
  std::vector<std::string> link_names;
  for (const auto& l : robot.links()) link_names.push_back(l.name);
  bool ok = false;
  const auto geoms = detail::LoadMjcfGeoms(scene.cell_mjcf, scene.head.mjcf, link_names, sink, ok);
  if (!ok || !AllowedContactsNameHeadGeoms(scene.head, geoms, sink)) return nullptr;
  for (const auto& g : geoms) {
    if (!g.in_head && scene.OmitsMjcfBody(g.top_body)) continue;  // cell.omit
    model->bodies.push_back(BodyOfGeom(*model, scene, g));
  }
  AddPartBodies(*model, scene);
  model->n = static_cast<int>(model->bodies.size());
  BuildPairFilter(*model);
  if (!ProbeCheckedPairs(*model, scene, sink)) return nullptr;
  ListBroadPhaseGroups(*model);
  ComputeMotionBounds(*model);
  return model;
}

}  // namespace stitchsim::sim
