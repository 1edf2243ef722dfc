#include "stitchsim/trace/joints.h"

namespace stitchsim::trace {

std::string ToString(const ArmConfiguration& c) {
  std::string out = c.shoulder == Shoulder::kFront ? "front" : "back";
  out += c.elbow == Elbow::kUp ? "/up" : "/down";
  out += c.wrist == Wrist::kNoFlip ? "/noflip" : "/flip";
  return out;
}

std::string_view ToString(IkStatus status) {
  switch (status) {
    case IkStatus::kOk:
      return "ok";
    case IkStatus::kUnreachable:
      return "unreachable";
    case IkStatus::kJointLimit:
      return "joint-limit";
    case IkStatus::kWristSingularity:
      return "wrist-singularity";
    case IkStatus::kShoulderSingularity:
      return "shoulder-singularity";
    case IkStatus::kConfigFlip:
      return "config-flip";
  }
  return "unknown";
}

}  // namespace stitchsim::trace
