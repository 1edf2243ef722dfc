#pragma once
// What the close-up planners share (close_up_plan.cpp, close_up_arm.cpp): posing the MuJoCo
// model, the palette, overlays and viewing directions; and the planners of close_up_arm.cpp.

#include <mujoco/mujoco.h>

#include <Eigen/Geometry>
#include <array>
#include <initializer_list>
#include <string>
#include <vector>

#include "stitchsim/run/close_up.h"

namespace stitchsim::run::close_up {

/// Poses the model's joints (model order, trace::JointVector) and runs its kinematics. False
/// when the model lacks a joint (`error` names it).
bool PoseModel(const mjModel& model, mjData& data, const trace::JointVector& joints,
               std::string& error);

/// The part body's pose in the world (metres) in the model's current state.
Eigen::Isometry3d PartWorld(const mjModel& model, const mjData& data);

/// A geom's centre (world, m) in the model's current state.
Eigen::Vector3d GeomCentre(const mjData& data, int geom);

/// MuJoCo RGBA in [0, 1].
using Rgba = std::array<float, 4>;
/// The close-ups' colours (the legends name them).
namespace colours {
inline constexpr Rgba kBodyA = {0.95f, 0.4f, 0.05f, 0.6f};  ///< first body in contact
inline constexpr Rgba kBodyB = {0.1f, 0.45f, 0.95f, 0.6f};  ///< second body in contact
inline constexpr Rgba kMarker = {1.0f, 0.9f, 0.0f, 1.0f};   ///< contact / tool point
inline constexpr Rgba kDepth = {0.9f, 0.0f, 0.9f, 1.0f};    ///< depth bar
inline constexpr Rgba kNeedles = {0.0f, 0.85f, 0.95f, 1.0f};
inline constexpr Rgba kFoot = {0.2f, 0.3f, 0.8f, 1.0f};
inline constexpr Rgba kPreformTop = {0.85f, 0.6f, 0.1f, 1.0f};
inline constexpr Rgba kMoldLine = {0.3f, 0.35f, 0.45f, 1.0f};
inline constexpr Rgba kDrift = {0.95f, 0.05f, 0.05f, 1.0f};
inline constexpr Rgba kHighlight = {1.0f, 0.3f, 0.05f, 1.0f};  ///< joint's link, constraint
inline constexpr Rgba kGrey = {0.74f, 0.74f, 0.76f, 1.0f};     ///< the rest, greyed
inline constexpr Rgba kAxis = {0.1f, 0.75f, 0.2f, 1.0f};       ///< joint axis
}  // namespace colours

/// An overlay: a polyline (capsules) or one sphere per point (world, m).
render::Overlay MakeOverlay(const std::string& label, const Rgba& rgba, double radius_m,
                            std::vector<Eigen::Vector3d> points_m, bool polyline);
/// Draws `geoms` in `rgba` in the plan's picture.
void Recolour(CloseUpPlan& plan, const std::vector<int>& geoms, const Rgba& rgba);
/// Viewing directions (unit, world) on a ring of `azimuths` at each elevation (degrees,
/// negative: looking down).
std::vector<Eigen::Vector3d> Ring(int azimuths, std::initializer_list<double> elevations_deg);
/// A pose in millimetres (part frame) as metres.
inline Eigen::Isometry3d ToMetres(Eigen::Isometry3d t_mm) {
  t_mm.translation() /= 1000.0;
  return t_mm;
}
/// `v` formatted with printf's `format`.
std::string Fmt(const char* format, double v);

// The family planners of close_up_arm.cpp; each fills `plan` for the model posed at the
// picture's joints, false when it finds nothing to frame.

/// kin.* and dyn.*: the whole arm, the offending joint's link highlighted, its axis drawn.
bool PlanKinematics(const CloseUpContext& ctx, const verify::Rule& rule,
                    const trace::TraceSample& s, CloseUpPlan& plan);
/// constraint.*: from above the stitch, the constraint highlighted, the crossings marked
/// (`s` may be null: a line crossing has no sample).
bool PlanConstraint(const CloseUpContext& ctx, const verify::Rule& rule,
                    const trace::TraceSample* s, CloseUpPlan& plan);
/// afp.* and any other rule: the head at the sample, the roller or the tool point in view.
bool PlanHead(const CloseUpContext& ctx, const trace::TraceSample& s, CloseUpPlan& plan);
/// afp.* with a finding placed on the part (close_up_afp.cpp): the finding's place from
/// above, the rule's drawn points near it as the subject, the laid course edges around it,
/// the head lifted clear (the model posed); false with `error` when the model cannot be posed.
bool PlanAfp(const CloseUpContext& ctx, const verify::Rule& rule, const verify::Finding& focus,
             CloseUpPlan& plan, std::string& error);

}  // namespace stitchsim::run::close_up
