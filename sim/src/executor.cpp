#include "stitchsim/sim/executor.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <istream>
#include <string>
#include <unordered_map>
#include <vector>

#include "detail/executor_core.h"
#include "detail/start_branch.h"
#include "stitchsim/common/limits.h"
#include "stitchsim/geom/rotation.h"
#include "stitchsim/program/modal_state.h"
#include "stitchsim/program/tool_pose.h"

namespace stitchsim::sim {

using detail::Executor;
using program::Axis;

ExecuteOptions ExecuteOptionsFor(const scene::Scene& scene) {
  ExecuteOptions o;
  o.mounted_head = scene.head.name;
  if (scene.head.IsStitching()) {
    o.rapid_speed_mm_s = scene.head.stitch.rapid_speed_mm_s;
    o.rotation_speed_rad_s = scene.head.stitch.rotation_speed_deg_s * kDeg;
    o.stitch_rate_per_min = scene.head.stitch.stitch_rate_per_min;
    o.settle_time_s = scene.head.stitch.settle_time_s;
  } else {
    o.rapid_speed_mm_s = scene.head.afp.rapid_speed_mm_s;
  }
  return o;
}

ProgramInput::ProgramInput(std::istream& in, const program::Dialect& dialect, std::string file_name,
                           DiagnosticSink& diagnostics)
    : in_(in),
      origin_(in.tellg()),
      dialect_(dialect),
      file_name_(std::move(file_name)),
      reader_(in, dialect, file_name_, diagnostics) {}

namespace detail {

// `T<n> M6` must mount the cell's head.
bool HeadMatches(const program::Dialect& dialect, const program::MachineState& st,
                 const program::Block& block, const ExecuteOptions& options,
                 const std::string& file_name, DiagnosticSink& diagnostics) {
  if (options.mounted_head.empty() || options.allow_head_mismatch || !st.active_tool) return true;
  const program::ToolEntry* tool = dialect.FindTool(*st.active_tool);
  if (tool == nullptr || tool->head == options.mounted_head) return true;
  diagnostics.Error("exec-head-mismatch", {file_name, block.source_line, 1},
                    "T" + std::to_string(*st.active_tool) + " M6 mounts head '" + tool->head +
                        "', but the cell carries '" + options.mounted_head +
                        "' (the scene's head); --allow-mismatch verifies it anyway");
  return false;
}

}  // namespace detail

ExecutionSummary ExecuteProgram(const CellSetup& cell, const process::ProcessModel& process,
                                const program::Dialect& dialect, std::istream& in,
                                const std::string& file_name, const ExecuteOptions& options,
                                DiagnosticSink& diagnostics, TraceSink& sink) {
  ProgramInput input(in, dialect, file_name, diagnostics);
  return ExecuteProgram(cell, process, input, options, diagnostics, sink);
}

namespace detail {

bool RunBlocks(program::ProgramReader& reader, program::ModalState& state, Executor& exec,
               const program::Dialect& dialect, const std::string& file_name,
               const ExecuteOptions& options, DiagnosticSink& diagnostics,
               ExecutionSummary& summary, const BlockHooks& hooks) {
  program::Block block;
  const std::size_t errors_before = diagnostics.ErrorCount();
  while (reader.Next(block)) {
    if (hooks.before && !hooks.before(block)) return false;
    const program::Step& step = state.Update(block);
    if (diagnostics.ErrorCount() > errors_before) break;
    if (step.tool_changed &&
        !HeadMatches(dialect, state.State(), block, options, file_name, diagnostics)) {
      break;
    }
    if (step.is_move) {
      const auto& st = state.State();
      for (Axis a : {Axis::kX, Axis::kY, Axis::kZ, Axis::kA, Axis::kB, Axis::kC}) {
        if (!st[a]) {
          diagnostics.Error("exec-incomplete-pose", {file_name, block.source_line, 1},
                            "the first move must give the whole tool pose (X Y Z A B C); " +
                                std::string(program::RoleName(a)) + " is not known yet");
          break;
        }
      }
      if (diagnostics.ErrorCount() > errors_before) break;
      const auto& u_before = state.Previous()[Axis::kDrive];
      const auto& u_after = st[Axis::kDrive];
      if (u_before && u_after && *u_after < *u_before - 1e-9) {
        diagnostics.Error("exec-drive-reversed", {file_name, block.source_line, 1},
                          "the drive axis U runs backwards");
        break;
      }
      if (hooks.dry) {
        exec.Advance(st, step, block.source_line);
      } else {
        exec.Move(state.Previous(), st, step, block.source_line, summary);
      }
      ++summary.moves;
    }
    if (hooks.after) hooks.after(block, step);
  }
  return true;
}

}  // namespace detail

ExecutionSummary ExecuteProgram(const CellSetup& cell, const process::ProcessModel& process,
                                ProgramInput& input, const ExecuteOptions& options,
                                DiagnosticSink& diagnostics, TraceSink& sink) {
  const program::Dialect& dialect = input.dialect_;
  const std::string& file_name = input.file_name_;
  program::ProgramReader& reader = input.reader_;
  ExecutionSummary summary;
  std::optional<JointVector> start;
  if (options.choose_start_branch) {
    start = detail::StartBranchLookAhead(cell, input.in_, input.origin_, dialect, file_name);
  }
  program::ModalState state(dialect, file_name, diagnostics);
  Executor exec(cell, process, dialect, options, sink);
  if (start) exec.SeedJoints(*start);
  const std::size_t errors_before = diagnostics.ErrorCount();
  detail::RunBlocks(reader, state, exec, dialect, file_name, options, diagnostics, summary, {});
  // Drain the reader so its end-of-file checks (missing '%', ...) run.
  program::Block block;
  while (diagnostics.ErrorCount() == errors_before && reader.Next(block)) {
    state.Update(block);
  }
  if (diagnostics.ErrorCount() == errors_before && options.require_program_end &&
      !state.State().program_ended) {
    diagnostics.Error("exec-missing-program-end", {file_name, reader.LineCount(), 1},
                      "the programme stops here without its end (M" +
                          std::to_string(dialect.m.program_end) + "): cut short?");
  }
  summary.lines = reader.LineCount();
  summary.header = reader.Header();
  summary.time_s = exec.Time();
  summary.ok = diagnostics.ErrorCount() == errors_before;
  return summary;
}

}  // namespace stitchsim::sim
