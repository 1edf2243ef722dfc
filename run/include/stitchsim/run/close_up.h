#pragma once
// A close-up snapshot of a rule with errors (docs/report-format.md, "Snapshots"): planned per
// the rule's close-up family (verify::Rule::CloseUp(): collisions framed on the two bodies in
// contact, needle and stitch rules on the needles with the preform as a section, kinematic
// rules on the whole arm with the offending joint's link, constraint crossings from above, AFP
// rules on their worst finding's place on the part, else the roller) as data, then shot: the
// direction that shows the subjects largest and least hidden, whatever still hides them made
// see-through, checked on a segmentation.

#include <mujoco/mujoco.h>

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "stitchsim/process/stitch_cycle.h"
#include "stitchsim/render/renderer.h"
#include "stitchsim/render/text.h"
#include "stitchsim/run/loaded_scene.h"
#include "stitchsim/trace/joints.h"
#include "stitchsim/trace/trace.h"
#include "stitchsim/verify/rule.h"
#include "stitchsim/verify/verifier.h"

namespace stitchsim::run {

/// Something a close-up exists to show: model geoms and/or overlays (by label).
struct ShotSubject {
  std::string name;                   ///< e.g. "head:head_body", "needles", "link_5"
  std::vector<int> geoms;             ///< model geom ids
  std::vector<std::string> overlays;  ///< overlay labels
};

/// What one close-up shows and how (filled per rule family by PlanCloseUp).
struct CloseUpPlan {
  verify::CloseUpFamily family = verify::CloseUpFamily::kNone;  ///< the rule's
  trace::JointVector joints = trace::JointVector::Zero();       ///< the robot's pose (model order)
  Eigen::Vector3d centre_m = Eigen::Vector3d::Zero();           ///< world, what the camera aims at
  double radius_m = 0.3;  ///< the sphere around centre_m the picture must hold (world, m)
  /// Viewing directions (world, from the camera towards centre_m) to try, preferred first.
  std::vector<Eigen::Vector3d> directions;
  std::vector<render::Overlay> overlays;  ///< world frame
  render::DrawStyle style;                ///< colours and see-through geoms before occlusion
  std::vector<ShotSubject> subjects;      ///< each must be visible
  std::vector<render::LegendEntry> legend;
};

/// What the planners read besides the rule.
struct CloseUpContext {
  const LoadedScene* ls = nullptr;                 ///< not owned; the scene and its robot
  const process::ProcessModel* process = nullptr;  ///< not owned; the needles (stitching)
  const trace::CellDescription* cell = nullptr;    ///< not owned; collision body names
  mjModel* model = nullptr;  ///< not owned; the scene's MuJoCo model (render::LoadSceneModel)
  mjData* data = nullptr;    ///< not owned; posed by PlanCloseUp at the picture's joints
  /// Not owned; every stitch by verdict (part frame, mm), for the constraint close-up.
  const std::vector<verify::StitchMark>* stitches = nullptr;
  /// Not owned, may be null; the finished verifier: its rules' drawings (afp close-ups).
  const verify::Verifier* verifier = nullptr;
};

/// The finding a rule's close-up is about: the error at the worst sample's line (an afp rule
/// without a sample: at its worst line), else the first error, else the first finding; null
/// when the rule kept none.
const verify::Finding* FocusFinding(const verify::Rule& rule);

/// The close-up of `rule` (which has errors), the model posed in ctx.data; nullopt for a rule
/// without a close-up (family kNone, or nothing to place it: no worst sample). False with
/// `error` set when the model cannot be posed (a joint missing).
bool PlanCloseUp(const CloseUpContext& ctx, const verify::Rule& rule,
                 std::optional<CloseUpPlan>& plan, std::string& error);

/// One subject's pixels in the final view (segmentation, see-through geoms left out).
struct SubjectPixels {
  std::string name;  ///< the subject's
  long visible = 0;  ///< pixels where it is the nearest thing
  long alone = 0;    ///< pixels where it is when drawn alone
  long hidden = 0;   ///< of `alone`, those covered by a geom that is no subject
};

/// The picture of a plan and what the camera work measured.
struct Shot {
  render::Image image;                   ///< the close-up, undecorated
  render::CameraView view;               ///< world, m
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

}  // namespace stitchsim::run
