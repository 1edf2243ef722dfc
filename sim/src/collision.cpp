// Collision queries (docs/collision.md, "Queries"): a function of the immutable model, the
// caller's data, the joints and the options; CollisionWorld pairs one model with one data.
#include "stitchsim/sim/collision.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "detail/collision_model.h"
#include "stitchsim/sim/mujoco_cell.h"

namespace stitchsim::sim {
namespace {

using detail::Body;
using detail::Group;
using detail::Obb;

// Broad-phase margin: how far a robot body may move before its candidate list is rebuilt (m).
constexpr double kNearMarginM = 0.2;

// The contacts of a result, built in one place (the value types may move to another target).
// A pair of primitives, or a primitive and a mesh constraint: FCL's first contact.
Contact FclContact(const Body& a, const Body& b, const Body& r, const Body& o,
                   const fcl::Contactd& c) {
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
  return out;
}

// A robot body `r` in a slab tile `p`, at its deepest point.
Contact SlabContactOf(const Body& r, const Body& p, const detail::SlabDepth& deepest) {
  Contact out;
  out.kind = ContactClass::kHeadPart;
  out.body_a = r.name;
  out.body_b = p.name;
  out.depth_m = deepest.depth_m;
  out.point_world_m = deepest.point_world_m;
  return out;
}

// The naive baseline's contact: the pair as listed, FCL's depth as given.
Contact NaiveContact(const Body& a, const Body& b, const fcl::Contactd& c) {
  Contact out;
  out.body_a = a.name;
  out.body_b = b.name;
  out.depth_m = std::abs(c.penetration_depth);
  out.point_world_m = c.pos;
  return out;
}

// Sets the clearance of a result in contact: 0, the first contact's pair.
void ClearanceInContact(CollisionResult& result) {
  result.min_clearance_m = 0.0;
  result.min_clearance_pair = result.contacts.front().body_a + "|" + result.contacts.front().body_b;
}

const Body& BodyAt(const CollisionModel& model, int i) {
  return model.bodies[static_cast<std::size_t>(i)];
}

// Every body at the first placement; after that only the moving ones (fixed bodies keep
// their first placement).
void Place(const CollisionModel& model, CollisionData& data, const JointVector& q) {
  Eigen::Isometry3d part;
  if (data.kinematics != nullptr) {
    data.kinematics->SetJoints(q);
    data.kinematics->LinkFramesOut(data.frames);
    part = data.kinematics->PartWorld();
  } else {
    ForwardKinematics(model.robot, q, data.frames);
    part = PartPoseWorld(model.cell, q[kRotator]);
  }
  data.part_world = part;
  const bool all = !data.placed;
  const std::size_t count = all ? model.bodies.size() : model.moving_bodies.size();
  for (std::size_t k = 0; k < count; ++k) {
    const std::size_t i = all ? k : static_cast<std::size_t>(model.moving_bodies[k]);
    const Body& b = model.bodies[i];
    const Eigen::Isometry3d frame =
        b.group == Group::kPart ? part : data.frames.world_pose[static_cast<std::size_t>(b.link)];
    fcl::CollisionObjectd& object = *data.objects[i];
    object.setTransform(detail::ToFcl(frame * b.local));
    data.obb[i] = detail::ObbOf(object, b.fitted ? &*b.fitted : nullptr);
    data.box[i] = detail::BoxOf(data.obb[i]);
  }
  data.placed = true;
}

// Robot body `r` (placed at r_world) against a tile `p` of `slab`: FCL's verdict `hit`
// (triangles crossed), else a body wholly inside the slab (its centre inside, `may_be_inside`
// from the broad phase). The depth is measured on the analytic surface (slab_depth.h).
void SlabContact(const Body& r, const Body& p, const detail::Slab& slab,
                 const Eigen::Isometry3d& r_world, const Eigen::Isometry3d& part_world, bool hit,
                 bool may_be_inside, CollisionResult& result) {
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
  result.contacts.push_back(SlabContactOf(r, p, *deepest));
}

void CheckPair(const CollisionModel& model, const CollisionData& data, int i, int j,
               CollisionResult& result) {
  const Body& a = BodyAt(model, i);
  const Body& b = BodyAt(model, j);
  const fcl::CollisionObjectd& oa = *data.objects[static_cast<std::size_t>(i)];
  const fcl::CollisionObjectd& ob = *data.objects[static_cast<std::size_t>(j)];
  fcl::CollisionRequestd req(1, true);
  fcl::CollisionResultd res;
  fcl::collide(&oa, &ob, req, res);
  const bool swap = b.group == Group::kRobot && a.group != Group::kRobot;
  const Body& r = swap ? b : a;  // the robot body (a robot-robot pair: a)
  const Body& o = swap ? a : b;
  if (const detail::Slab* slab = model.SlabOf(o); slab != nullptr && r.group == Group::kRobot) {
    const Obb& body = data.obb[static_cast<std::size_t>(swap ? j : i)];
    const Obb& tile = data.obb[static_cast<std::size_t>(swap ? i : j)];
    const Eigen::Vector3d d = tile.r.transpose() * (body.c - tile.c);
    const bool centre_in_tile_box = (d.cwiseAbs() - tile.e).maxCoeff() <= 0.0;
    const fcl::CollisionObjectd& r_object = swap ? ob : oa;
    SlabContact(r, o, *slab, Eigen::Isometry3d(r_object.getTransform().matrix()), data.part_world,
                res.isCollision(), centre_in_tile_box, result);
    return;
  }
  if (!res.isCollision()) return;
  result.contacts.push_back(FclContact(a, b, r, o, res.getContact(0)));
}

// Calls visit(i, j) for every pair that may interact: each robot body with its near list
// and the rotator-carried bodies, then the robot-robot pairs (near lists current).
template <class Visit>
void ForEachPair(const CollisionModel& model, const CollisionData& data, Visit&& visit) {
  for (std::size_t k = 0; k < model.robot_bodies.size(); ++k) {
    for (int e : data.near[k].env) visit(model.robot_bodies[k], e);
    for (int e : model.moving_env) visit(model.robot_bodies[k], e);
  }
  for (const auto& [i, j] : model.robot_self_pairs) visit(i, j);
}

// Broad phase. The environment is static but for what the rotator carries; the robot moves a
// little between queries. Robot body k's list is remade when its motion bound since the list
// was made may have used up the margin (CollisionData::NearSet).
void UpdateNear(const CollisionModel& model, CollisionData& data, std::size_t k,
                const JointVector& q, double cutoff) {
  CollisionData::NearSet& n = data.near[k];
  if (n.radius >= cutoff) {
    const double travel = model.travel_coeff[static_cast<std::size_t>(model.robot_group[k])].dot(
        (q - n.q_ref).cwiseAbs());
    if (std::sqrt(3.0) * travel < n.radius - cutoff) return;
  }
  n.env.clear();
  n.q_ref = q;
  n.radius = cutoff + kNearMarginM;
  const int r = model.robot_bodies[k];
  const fcl::AABBd& box = data.box[static_cast<std::size_t>(r)];
  for (int e : model.fixed_env) {
    // Only checked pairs: the list's order is kept, so the pairs are visited as before.
    if (model.Checked(r, e) &&
        detail::BoxDistance(box, data.box[static_cast<std::size_t>(e)]) < n.radius) {
      n.env.push_back(e);
    }
  }
}

// FNV-1a over the query's bytes (compared before the joints themselves).
std::uint64_t QueryKey(const JointVector& q, const CollisionOptions& options) {
  std::uint64_t key = 1469598103934665603ull;
  auto mix = [&key](const void* p, std::size_t n) {
    for (std::size_t k = 0; k < n; ++k) {
      key = (key ^ static_cast<const unsigned char*>(p)[k]) * 1099511628211ull;
    }
  };
  mix(q.data(), sizeof(double) * static_cast<std::size_t>(q.size()));
  mix(&options.clearance_cutoff_m, sizeof(double));
  key ^= options.compute_clearance ? 1u : 0u;
  return key;
}

const CollisionResult* FindCached(const CollisionData& data, std::uint64_t key,
                                  const JointVector& q, const CollisionOptions& options) {
  // Newest first: the rules ask about the sample just placed; the executor's look-ahead over
  // a long line may have placed a few hundred samples since.
  const auto& cache = data.cache;
  for (std::size_t n = 0; n < cache.size(); ++n) {
    const CollisionData::Cached& c = cache[(data.cache_next + cache.size() - 1 - n) % cache.size()];
    if (c.key == key && c.q == q && c.clearance == options.compute_clearance &&
        c.cutoff == options.clearance_cutoff_m) {
      return &c.result;
    }
  }
  return nullptr;
}

void Remember(CollisionData& data, CollisionData::Cached entry) {
  constexpr std::size_t kSize = CollisionData::kCacheSize;
  if (data.cache.size() < kSize) {
    data.cache.push_back(std::move(entry));
    data.cache_next = data.cache.size() % kSize;
  } else {
    data.cache[data.cache_next] = std::move(entry);
    data.cache_next = (data.cache_next + 1) % kSize;
  }
}

// Smallest distance over the checked pairs, up to `cutoff` (m); sets result's clearance,
// pair or error.
void Clearance(const CollisionModel& model, CollisionData& data, double cutoff,
               CollisionResult& result) {
  double best = cutoff;
  int best_i = -1, best_j = -1;
  // Measures pair (i, j) exactly; false (and result.error) if FCL fails on it.
  auto measure = [&](int i, int j) {
    fcl::DistanceRequestd req;
    fcl::DistanceResultd res;
    fcl::distance(data.objects[static_cast<std::size_t>(i)].get(),
                  data.objects[static_cast<std::size_t>(j)].get(), req, res);
    if (!std::isfinite(res.min_distance)) {
      result.error =
          "FCL distance query failed for " + BodyAt(model, i).name + "|" + BodyAt(model, j).name;
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
  const std::pair<int, int> seeded = data.last_nearest;
  if (seeded.first >= 0 && !measure(seeded.first, seeded.second)) return;
  // Candidates: world boxes closer than the best so far, then an oriented-box lower bound.
  auto& candidates = data.candidates;
  candidates.clear();
  const fcl::AABBd* box = data.box.data();
  const Obb* obb = data.obb.data();
  ForEachPair(model, data, [&](int i, int j) {
    if (!model.Checked(i, j) || detail::BoxDistance(box[i], box[j]) >= best) return;
    const double lb = detail::ObbGapLowerBound(obb[i], obb[j], best);
    if (lb < best) candidates.push_back({lb, i, j});
  });
  // Exact distances nearest-bound first; a pair whose bound is no less than the best distance
  // so far cannot lower it (the result equals measuring every candidate).
  std::sort(candidates.begin(), candidates.end(),
            [](const CollisionData::Candidate& x, const CollisionData::Candidate& y) {
              return x.bound < y.bound;
            });
  for (const CollisionData::Candidate& c : candidates) {
    if (c.bound >= best || best <= 0.0) break;
    const bool is_seed = (c.i == seeded.first && c.j == seeded.second) ||
                         (c.j == seeded.first && c.i == seeded.second);
    if (!is_seed && !measure(c.i, c.j)) return;
  }
  data.last_nearest = {best_i, best_j};
  result.min_clearance_m = best;
  if (best_i >= 0) {
    result.min_clearance_pair = BodyAt(model, best_i).name + "|" + BodyAt(model, best_j).name;
  }
}

// The benchmark baseline's pair (i, j) on freshly built `objects`; lowers `best`.
void CheckPairNaive(const CollisionModel& model,
                    const std::vector<std::unique_ptr<fcl::CollisionObjectd>>& objects,
                    const Eigen::Isometry3d& part, const CollisionOptions& options, int i, int j,
                    double& best, CollisionResult& result) {
  const fcl::CollisionObjectd* oi = objects[static_cast<std::size_t>(i)].get();
  const fcl::CollisionObjectd* oj = objects[static_cast<std::size_t>(j)].get();
  fcl::CollisionRequestd req(1, true);
  fcl::CollisionResultd res;
  fcl::collide(oi, oj, req, res);
  const Body& a = BodyAt(model, i);
  const Body& b = BodyAt(model, j);
  const bool swap = b.group == Group::kRobot;
  const detail::Slab* slab = model.SlabOf(swap ? a : b);
  if (slab != nullptr && (swap ? b : a).group == Group::kRobot) {
    const std::size_t before = result.contacts.size();
    const auto& tf = (swap ? oj : oi)->getTransform();
    SlabContact(swap ? b : a, swap ? a : b, *slab, Eigen::Isometry3d(tf.matrix()), part,
                res.isCollision(), true, result);
    if (res.isCollision() || result.contacts.size() > before) {
      best = 0.0;
      return;
    }
  }
  if (res.isCollision()) {
    result.contacts.push_back(NaiveContact(a, b, res.getContact(0)));
    best = 0.0;
  } else if (options.compute_clearance) {
    fcl::DistanceRequestd dreq;
    fcl::DistanceResultd dres;
    fcl::distance(oi, oj, dreq, dres);
    best = std::min(best, std::max(0.0, dres.min_distance));
  }
}

// The benchmark baseline: objects rebuilt from scratch and every checked pair queried.
CollisionResult CheckNaive(const CollisionModel& model, CollisionData& data, const JointVector& q,
                           const CollisionOptions& options) {
  CollisionResult result;
  ForwardKinematics(model.robot, q, data.frames);
  const Eigen::Isometry3d part = PartPoseWorld(model.cell, q[kRotator]);
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> objects;
  for (const Body& b : model.bodies) {
    const detail::Geometry g =
        b.mesh_m ? detail::MakeMesh(*b.mesh_m) : detail::MakePrimitive(b.shape, b.size);
    const Eigen::Isometry3d frame =
        b.group == Group::kPart ? part : data.frames.world_pose[static_cast<std::size_t>(b.link)];
    objects.push_back(std::make_unique<fcl::CollisionObjectd>(g, detail::ToFcl(frame * b.local)));
  }
  double best = options.clearance_cutoff_m;
  for (int i = 0; i < model.n; ++i) {
    for (int j = i + 1; j < model.n; ++j) {
      if (model.Checked(i, j)) CheckPairNaive(model, objects, part, options, i, j, best, result);
    }
  }
  result.min_clearance_m = best;
  return result;
}

}  // namespace

CollisionData::CollisionData(const CollisionModel& model)
    : frames(MakeLinkFrames(model.robot)),
      obb(model.bodies.size()),
      box(model.bodies.size()),
      near(model.robot_bodies.size()) {
  objects.reserve(model.bodies.size());
  for (const Body& b : model.bodies) {
    objects.push_back(
        std::make_unique<fcl::CollisionObjectd>(b.geometry, fcl::Transform3d::Identity()));
  }
  Place(model, *this, HomeJoints(model.robot, 0.0));
}

CollisionResult CheckCollision(const CollisionModel& model, CollisionData& data,
                               const JointVector& q, const CollisionOptions& options) {
  if (options.naive_baseline) return CheckNaive(model, data, q, options);
  const std::uint64_t key = QueryKey(q, options);
  if (const CollisionResult* cached = FindCached(data, key, q, options)) return *cached;
  CollisionResult result;
  Place(model, data, q);
  const double cutoff = std::max(options.clearance_cutoff_m, 0.0);
  for (std::size_t k = 0; k < model.robot_bodies.size(); ++k) UpdateNear(model, data, k, q, cutoff);
  // Overlapping world boxes of tilted or large bodies often have separated oriented boxes.
  const fcl::AABBd* box = data.box.data();
  const Obb* obb = data.obb.data();
  ForEachPair(model, data, [&](int i, int j) {
    if (model.Checked(i, j) && detail::BoxesOverlap(box[i], box[j]) &&
        detail::ObbGapLowerBound(obb[i], obb[j], 1e-12) <= 0.0) {
      CheckPair(model, data, i, j, result);
    }
  });
  if (options.compute_clearance) {
    if (!result.contacts.empty()) {
      ClearanceInContact(result);
    } else {
      Clearance(model, data, cutoff, result);
    }
  }
  Remember(data, {key, q, options.compute_clearance, options.clearance_cutoff_m, result});
  return result;
}

double MaxPointTravel(const CollisionModel& model, const JointVector& a, const JointVector& b) {
  const JointVector dq = (b - a).cwiseAbs();
  double worst = 0.0;
  for (const JointVector& c : model.travel_coeff) worst = std::max(worst, c.dot(dq));
  return worst + model.rotator_reach_m * dq[kRotator];
}

CollisionWorld::CollisionWorld(std::shared_ptr<const CollisionModel> model)
    : model_(std::move(model)), data_(std::make_unique<CollisionData>(*model_)) {}

CollisionWorld::~CollisionWorld() = default;

std::unique_ptr<CollisionWorld> CollisionWorld::Create(const scene::Scene& scene,
                                                       const RobotModel& robot,
                                                       DiagnosticSink& sink) {
  std::shared_ptr<const CollisionModel> model = BuildCollisionModel(scene, robot, sink);
  if (!model) return nullptr;
  return std::unique_ptr<CollisionWorld>(new CollisionWorld(std::move(model)));
}

std::unique_ptr<CollisionWorld> CollisionWorld::Share() const {
  return std::unique_ptr<CollisionWorld>(new CollisionWorld(model_));
}

void CollisionWorld::UseKinematics(MujocoCell* kinematics) { data_->kinematics = kinematics; }

CollisionResult CollisionWorld::Check(const JointVector& q, const CollisionOptions& options) {
  return CheckCollision(*model_, *data_, q, options);
}

double CollisionWorld::MaxPointTravel(const JointVector& a, const JointVector& b) const {
  return sim::MaxPointTravel(*model_, a, b);
}

std::vector<std::string> CollisionWorld::BodyNames() const {
  std::vector<std::string> names;
  names.reserve(model_->bodies.size());
  for (const auto& b : model_->bodies) names.push_back(b.name);
  return names;
}

}  // namespace stitchsim::sim
