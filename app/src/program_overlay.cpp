// Stitch points of a programme for drawing: the end point of every line that advances the
// drive axis, in the part frame.
#include <fstream>

#include "commands.h"
#include "stitchsim/common/thinned.h"
#include "stitchsim/program/modal_state.h"
#include "stitchsim/program/reader.h"
#include "stitchsim/program/tool_pose.h"

namespace stitchsim::app {
namespace {

// More points than a picture can show are thinned (every other one dropped, then every
// fourth taken, ...): each drawn point costs the software renderer ~100 KB, so a programme of
// any length draws in bounded memory (3000 points: ~600 MB at most).
constexpr std::size_t kMaxOverlayPoints = 3000;

}  // namespace

std::optional<ProgramOverlay> ProgramStitchOverlay(const LoadedScene& /*ls*/,
                                                   const std::string& program_file) {
  if (!ProgramInputOk(program_file)) return std::nullopt;
  std::ifstream in(program_file, std::ios::binary);
  if (!in) {
    PrintError("io-missing-file", "cannot open programme " + program_file);
    return std::nullopt;
  }
  const program::Dialect& dialect = program::Dialect::Default();
  const geom::EulerOrder order = program::EulerOrderOf(dialect);
  BoundedDiagnosticSink sink(50);
  program::ProgramReader reader(in, dialect, program_file, sink);
  program::ModalState state(dialect, program_file, sink);
  program::Block block;
  ProgramOverlay out;
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
  if (PrintDiagnostics(sink)) return std::nullopt;
  if (out.stitch_points_part_mm.empty()) {
    PrintError("program-empty", program_file + ": the programme has no moves to draw");
    return std::nullopt;
  }
  return out;
}

}  // namespace stitchsim::app
