#pragma once
// A close-up snapshot as data (what must be seen, what is drawn over the model, candidate
// viewing directions) and the camera work that turns it into a picture: the direction that
// shows the subjects largest and least hidden, then whatever still hides them made
// see-through (render/renderer.h DrawStyle), checked on a segmentation of the same view.

#include <Eigen/Geometry>
#include <array>
#include <initializer_list>
#include <string>
#include <vector>

#include "stitchsim/render/renderer.h"
#include "stitchsim/render/text.h"
#include "stitchsim/trace/joints.h"

namespace stitchsim::app {

/// Something a close-up exists to show: model geoms and/or overlays (by label).
struct ShotSubject {
  std::string name;                   ///< e.g. "head:head_body", "needles", "link_5"
  std::vector<int> geoms;             ///< model geom ids
  std::vector<std::string> overlays;  ///< overlay labels
};

/// What one close-up shows and how (filled per rule family, snapshot_families.cpp).
struct CloseUpPlan {
  std::string family;  ///< "collision", "needle", "kinematics", "constraint", "afp", "head"
  trace::JointVector joints = trace::JointVector::Zero();  ///< the robot's pose (model order)
  Eigen::Vector3d centre_m = Eigen::Vector3d::Zero();      ///< world, what the camera aims at
  double radius_m = 0.3;  ///< the sphere around centre_m the picture must hold (world, m)
  /// Viewing directions (world, from the camera towards centre_m) to try, preferred first.
  std::vector<Eigen::Vector3d> directions;
  std::vector<render::Overlay> overlays;  ///< world frame
  render::DrawStyle style;                ///< colours and see-through geoms before occlusion
  std::vector<ShotSubject> subjects;      ///< each must be visible
  std::vector<render::LegendEntry> legend;
};

/// One subject's pixels in the final view (segmentation, see-through geoms left out).
struct SubjectPixels {
  std::string name;
  long visible = 0;  ///< where it is the nearest thing
  long alone = 0;    ///< where it is when drawn alone
  long hidden = 0;   ///< of `alone`, those covered by a geom that is no subject
};

/// The picture of a plan and what the camera work measured.
struct Shot {
  render::Image image;
  render::CameraView view;
  std::vector<SubjectPixels> pixels;     ///< per plan subject, in plan order
  std::vector<std::string> see_through;  ///< geoms made see-through because they hid a subject
  std::vector<int> transparent;          ///< every see-through geom of the picture (ids)
};

/// Renders `plan` with the model posed at plan.joints: picks among plan.directions the one
/// where the subjects are largest and least hidden, makes every other geom that still covers
/// a subject see-through, and renders the picture. False with `error` set when the renderer
/// cannot be made.
bool ShootCloseUp(mjModel* model, mjData* data, const CloseUpPlan& plan, int width, int height,
                  Shot& shot, std::string& error);

/// Poses the model's joints (model order, trace::JointVector) and runs its kinematics. False
/// when the model lacks a joint (`error` names it).
bool PoseModel(const mjModel& model, mjData& data, const trace::JointVector& joints,
               std::string& error);

/// The part body's pose in the world (metres) in the model's current state.
Eigen::Isometry3d PartWorld(const mjModel& model, const mjData& data);

/// A geom's centre (world, m) in the model's current state.
Eigen::Vector3d GeomCentre(const mjData& data, int geom);

// Building plans.

/// MuJoCo RGBA in [0, 1].
using Rgba = std::array<float, 4>;
/// The close-ups' colours (the legends name them).
namespace shot_colours {
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
}  // namespace shot_colours

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

}  // namespace stitchsim::app
