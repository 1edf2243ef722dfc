#pragma once
// Private pieces of programme text shared by the planners: the opening (mark, header, units,
// head), the ending, and the pose words.

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <utility>

#include "stitchsim/common/units.h"
#include "stitchsim/geom/rotation.h"
#include "stitchsim/program/block.h"
#include "stitchsim/program/dialect.h"
#include "stitchsim/program/tool_pose.h"
#include "stitchsim/program/writer.h"

namespace stitchsim::planner::detail {

/// What every planned programme starts with: the mark, the STITCHSIM header, millimetres and
/// absolute, then the head (`T<tool> M6`). `b` is scratch space, left cleared.
inline void WriteOpening(program::ProgramWriter& w, program::Block& b,
                         const program::Dialect& dialect, const program::ProgramHeader& header,
                         int tool_number) {
  w.WriteMark();
  w.WriteHeader(header);
  b.Clear();
  b.units = LengthUnit::kMillimetre;
  b.absolute = true;
  w.Write(b);
  b.Clear();
  b.tool = tool_number;
  b.m_codes = {dialect.m.tool_change};
  w.Write(b);
  b.Clear();
}

/// One block of an M code with an optional P word and comment (a ply, course or tow mark).
inline void WriteCode(program::ProgramWriter& w, program::Block& b, int m_code,
                      std::optional<int> param, std::string comment = {}) {
  b.Clear();
  b.m_codes = {m_code};
  b.param = param;
  b.comment = std::move(comment);
  w.Write(b);
}

/// What every planned programme ends with: the programme end code, the mark, flushed.
inline void WriteEnding(program::ProgramWriter& w, program::Block& b,
                        const program::Dialect& dialect) {
  b.Clear();
  b.m_codes = {dialect.m.program_end};
  w.Write(b);
  w.WriteMark();
  w.Flush();
}

/// Tool poses as X Y Z A B C words in the dialect's Euler order, each rotation on the Euler
/// branch nearest the previous one. The same rotation again (a straight row, a decoupled
/// translation) reuses its angles: EulerFromRotation with its own result as hint returns that
/// result, so this only saves the work.
class PoseWords {
 public:
  explicit PoseWords(const program::Dialect& dialect) : order_(program::EulerOrderOf(dialect)) {}

  void Set(program::Block& b, const Eigen::Vector3d& p, const Eigen::Matrix3d& r) {
    if (!have_ || r != rotation_) {
      const Eigen::Vector3d e = geom::EulerFromRotation(order_, r, have_ ? &rad_ : nullptr);
      rad_ = e;
      deg_ = e * kRadToDeg;
      rotation_ = r;
      have_ = true;
    }
    b[program::Axis::kX] = p.x();
    b[program::Axis::kY] = p.y();
    b[program::Axis::kZ] = p.z();
    b[program::Axis::kA] = deg_.x();
    b[program::Axis::kB] = deg_.y();
    b[program::Axis::kC] = deg_.z();
  }
  void Set(program::Block& b, const Eigen::Isometry3d& pose) {
    Set(b, pose.translation(), pose.linear());
  }
  /// The rotation of the last pose written (identity before the first).
  const Eigen::Matrix3d& Rotation() const { return rotation_; }

 private:
  geom::EulerOrder order_;
  Eigen::Vector3d rad_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d deg_ = Eigen::Vector3d::Zero();
  Eigen::Matrix3d rotation_ = Eigen::Matrix3d::Identity();
  bool have_ = false;
};

}  // namespace stitchsim::planner::detail
