// Stitch points of a programme for drawing: the end point of every line that advances the
// drive axis, in the part frame.
#include "stitchsim/run/program_overlay.h"

#include <fstream>

#include "stitchsim/common/files.h"
#include "stitchsim/common/thinned.h"
#include "stitchsim/program/modal_state.h"
#include "stitchsim/program/reader.h"
#include "stitchsim/program/tool_pose.h"

namespace stitchsim::run {
namespace {

// More points than a picture can show are thinned (every other one dropped, then every
// fourth taken, ...): each drawn point costs the software renderer ~100 KB, so a programme of
// any length draws in bounded memory (3000 points: ~600 MB at most).
constexpr std::size_t kMaxOverlayPoints = 3000;

}  // namespace

ProgramOverlay ProgramStitchOverlay(const std::string& program_file, DiagnosticSink& diagnostics) {
  ProgramOverlay out;
  if (std::string err = CheckStreamInput(program_file); !err.empty()) {
    out.status = Status::Error("io-missing-file", err);
    return out;
  }
  std::ifstream in(program_file, std::ios::binary);
  if (!in) {
    out.status = Status::Error("io-missing-file", "cannot open programme " + program_file);
    return out;
  }
  const program::Dialect& dialect = program::Dialect::Default();
  const geom::EulerOrder order = program::EulerOrderOf(dialect);
  BoundedDiagnosticSink sink(50);
  program::ProgramReader reader(in, dialect, program_file, sink);
  program::ModalState state(dialect, program_file, sink);
  program::Block block;
  Thinned<Eigen::Vector3d> points(kMaxOverlayPoints);
  while (reader.Next(block)) {
    const program::Step& step = state.Update(block);
    if (!step.is_move) continue;
    const auto& s = state.State();
    const auto& x = s[program::Axis::kX];
    const auto& y = s[program::Axis::kY];
    const auto& z = s[program::Axis::kZ];
    if (!x || !y || !z) continue;
    const Eigen::Vector3d p(*x, *y, *z);
    if (!out.first_tool_in_part_mm) out.first_tool_in_part_mm = program::ToolPoseOf(s, order);
    const auto& u_now = s[program::Axis::kDrive];
    const auto& u_before = state.Previous()[program::Axis::kDrive];
    if (points.Items().empty() || (u_now && (!u_before || *u_now != *u_before))) points.Add(p);
  }
  out.stitch_points_part_mm = std::move(points.Items());
  for (const Diagnostic& d : sink.Diagnostics()) diagnostics.Report(d);
  if (sink.HasErrors()) {
    out.status = Status::InSink();
  } else if (out.stitch_points_part_mm.empty()) {
    out.status =
        Status::Error("program-empty", program_file + ": the programme has no moves to draw");
  }
  return out;
}

}  // namespace stitchsim::run
