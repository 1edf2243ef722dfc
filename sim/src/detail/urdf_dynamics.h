#pragma once
// The URDF's dynamics data for RobotModel: <inertial>, <limit effort>, <dynamics damping> (read
// by urdfdom) and the stitchsim extensions urdfdom drops (<limit acceleration>,
// <payload_rating>), read with TinyXML. Each reader reports bad values to the sink.

#include <tinyxml.h>
#include <urdf_model/joint.h>
#include <urdf_model/link.h>

#include <map>
#include <optional>
#include <string>

#include "stitchsim/common/diagnostics.h"
#include "stitchsim/sim/robot_model.h"

namespace stitchsim::sim::detail {

/// The stitchsim extension data of a URDF, as text with its source lines.
struct UrdfExtensions {
  /// Joint name -> the text of its <limit acceleration="..."> attribute, when present.
  std::map<std::string, std::string, std::less<>> joint_acceleration;
  /// The <payload_rating> elements under <robot> (more than one is an error).
  struct PayloadElement {
    int line = 0;
    std::map<std::string, std::string, std::less<>> attributes;
  };
  std::vector<PayloadElement> payload;
};

/// Collects the extension data of one direct child of <robot>.
void CollectUrdfExtensions(const TiXmlElement& element, UrdfExtensions& out);

/// The link's <inertial> in the link frame; nullopt when absent or bad (bad: urdf-bad-inertial
/// at `where`).
std::optional<LinkInertial> ReadLinkInertial(const urdf::Link& link, const SourceLocation& where,
                                             DiagnosticSink& sink);

/// Fills info.effort, info.damping and info.max_acceleration (`acceleration_text`: the
/// extension attribute, or null); bad values give urdf-bad-limits at `where`.
void ReadJointDynamics(const urdf::Joint& joint, const std::string* acceleration_text,
                       const SourceLocation& where, DiagnosticSink& sink, JointInfo& info);

/// The <payload_rating>; all zero when absent. Bad values give urdf-bad-payload.
PayloadRating ReadPayloadRating(const UrdfExtensions& extensions, const std::string& file,
                                DiagnosticSink& sink);

}  // namespace stitchsim::sim::detail
