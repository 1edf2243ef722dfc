// The inputs of a sequence run, loaded and checked (sequence_run.h, LoadSequenceInputs).
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "stitchsim/program/tool_pose.h"
#include "stitchsim/run/sequence_report.h"
#include "stitchsim/run/sequence_run.h"

namespace stitchsim::run {
namespace {

using program::AfpProgram;

std::optional<Eigen::Isometry3d> ParseSequenceHome(const std::string& text) {
  std::stringstream ss(text);
  program::MachineState st;
  std::string item;
  const program::Axis axes[] = {program::Axis::kX, program::Axis::kY, program::Axis::kZ,
                                program::Axis::kA, program::Axis::kB, program::Axis::kC};
  for (const program::Axis a : axes) {
    if (!std::getline(ss, item, ',')) return std::nullopt;
    char* end = nullptr;
    const double v = std::strtod(item.c_str(), &end);
    if (end == item.c_str() || *end != '\0' || !std::isfinite(v)) return std::nullopt;
    st.axes[static_cast<std::size_t>(a)] = v;
  }
  if (std::getline(ss, item, ',')) return std::nullopt;
  return program::ToolPoseOf(st, program::EulerOrderOf(program::Dialect::Default()));
}

// Head weights by joint name onto the model's joints; unknown names are errors at their line.
void SequenceAxisWeights(const scene::HeadSpec& head, const sim::RobotModel& robot,
                         DiagnosticSink& sink, std::vector<double>& out) {
  out.assign(trace::kNumJoints, 0.0);
  for (const auto& w : head.sequence.axis_weights) {
    int found = -1;
    for (int j = 0; j < trace::kNumJoints; ++j)
      if (robot.joint(j).name == w.joint) found = j;
    if (found < 0) {
      sink.Error("head-unknown-joint", w.where,
                 "sequence.axis_weights names '" + w.joint + "', not a joint of the cell");
      continue;
    }
    out[static_cast<std::size_t>(found)] = w.weight;
  }
}

// Every tow a programme lays must be one of the head's (a course laid backwards mirrors them).
void TowsOnHead(const AfpProgram& p, const scene::HeadSpec& head, DiagnosticSink& sink) {
  const int k = head.afp.tows;
  const std::uint64_t beyond = k >= 64 ? 0 : ~((std::uint64_t{1} << k) - 1);
  for (const auto& c : p.courses) {
    for (const auto& st : c.stations) {
      // None beyond the head's, or all of them: P0 adds every tow there is.
      const std::uint64_t high = st.tows & beyond;
      if (high == 0 || high == beyond) continue;
      sink.Error(
          "sequence-tow-beyond-head", SourceLocation{p.file_name, st.source_line, 1},
          "a tow beyond the head's " + std::to_string(k) + " lays here (head '" + head.name + "')");
      return;
    }
  }
}

// A programme's plies must name the scene's plies (M70 P<n>, n its position in `plies:`).
void PliesKnown(const AfpProgram& p, const scene::Scene& scene, DiagnosticSink& sink) {
  for (const auto& ply : p.plies) {
    if (ply.number >= 1 && ply.number <= static_cast<int>(scene.plies.size())) continue;
    sink.Error("sequence-unknown-ply", SourceLocation{p.file_name, ply.line, 1},
               "M70 P" + std::to_string(ply.number) + " names no ply of scene '" + scene.name +
                   "' (it has " + std::to_string(scene.plies.size()) + ")");
  }
}

// The programme read and checked against the scene, and the head's axis weights; nullopt
// when anything is wrong (reported into `sink`).
std::optional<AfpProgram> CheckedProgram(const SequenceOptions& o, SequenceInputs& in,
                                         DiagnosticSink& sink) {
  const scene::Scene& scene = *in.loaded.scene;
  if (scene.head.kind != scene::HeadKind::kAfp) {
    sink.Error("sequence-not-afp", SourceLocation{o.scene_file, 1, 1},
               "scene '" + scene.name + "' mounts head '" + scene.head.name +
                   "', not a fibre-placement head");
  }
  std::ifstream file(o.program_file, std::ios::binary);
  std::optional<AfpProgram> prog;
  if (!sink.HasErrors())
    prog = program::ReadAfpProgram(file, program::Dialect::Default(), o.program_file, sink);
  if (prog) PliesKnown(*prog, scene, sink);
  if (prog) TowsOnHead(*prog, scene.head, sink);
  SequenceAxisWeights(scene.head, *in.loaded.robot, sink, in.axis_weights);
  if (sink.HasErrors()) return std::nullopt;
  return prog;
}

}  // namespace

std::optional<SequenceInputs> LoadSequenceInputs(const SequenceOptions& options,
                                                 DiagnosticSink& sink, SequenceError& error) {
  const auto t0 = std::chrono::steady_clock::now();
  auto loaded = LoadScene(options.scene_file, options.scene_load, sink);
  if (!loaded || sink.HasErrors()) return std::nullopt;
  SequenceInputs in;
  in.loaded = std::move(*loaded);
  std::optional<AfpProgram> prog = CheckedProgram(options, in, sink);
  if (!prog) return std::nullopt;
  in.program = std::move(*prog);
  if (!options.home.empty()) {
    auto h = ParseSequenceHome(options.home);
    if (!h) {
      error = {"sequence-bad-home",
               "--home wants X,Y,Z,A,B,C (mm, deg), got '" + options.home + "'"};
      return std::nullopt;
    }
    in.home = *h;
  } else if (in.program.first_pose) {
    in.home = *in.program.first_pose;
  }
  if (!options.order_file.empty()) {
    auto order = ReadOrderFile(options.order_file, in.program, error);
    if (!order) return std::nullopt;
    in.given_order = std::move(*order);
  }
  in.load_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return in;
}

}  // namespace stitchsim::run
