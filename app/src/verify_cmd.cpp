// `stitchsim verify`: execute a programme on the cell, check every stitch and pose, report.

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>

#include "chunked_cmd.h"
#include "cli_common.h"
#include "commands.h"
#include "html_report.h"
#include "pose_track.h"
#include "stitchsim/common/files.h"
#include "stitchsim/common/progress.h"
#include "stitchsim/geom/rotation.h"
#include "stitchsim/process/stitch_cycle.h"
#include "stitchsim/program/dialect.h"
#include "stitchsim/program/identity.h"
#include "stitchsim/sim/dynamics.h"
#include "stitchsim/sim/executor.h"
#include "stitchsim/sim/mujoco_cell.h"
#include "stitchsim/sim/timing.h"
#include "stitchsim/trace/trace_file.h"
#include "stitchsim/verify/verifier.h"
#include "verify_run.h"
#include "verify_session.h"

namespace stitchsim::app {
namespace {

struct VerifyArgs {
  std::string program;
  std::string dialect;
  std::string scene;
  std::string report_json;
  std::string junit;
  std::string snapshots;
  std::string html;
  std::string save_trace;
  bool no_collision = false;
  bool allow_mismatch = false;
  bool dynamics = false;
  bool quiet = false;
  int jobs = 0;       ///< 0: the number of cores
  std::string shard;  ///< "I/N"
  std::string part;   ///< --shard: the partial result file
  int chunk_lines = 16384;
  int warm_lines = 128;
};

// Colours by verdict.
constexpr std::array<float, 4> kClean = {0.1f, 0.85f, 0.2f, 1.0f};
constexpr std::array<float, 4> kWarn = {1.0f, 0.65f, 0.0f, 1.0f};
constexpr std::array<float, 4> kError = {0.95f, 0.05f, 0.05f, 1.0f};

// Overview: every stitch coloured by its verdict (clean stitches thinned to keep the
// picture within the renderer's geometry budget; flagged ones all drawn).
// Laid tows in blue, gaps in red, overlaps in magenta.
std::array<float, 4> DrawnColour(const std::string& label) {
  if (label == "afp_gap") return kError;
  if (label == "afp_overlap") return {0.85f, 0.1f, 0.85f, 1.0f};
  return {0.15f, 0.45f, 0.95f, 1.0f};
}

int WriteOverview(const LoadedScene& ls, const verify::Verifier& v, const std::string& dir,
                  const sim::JointVector& joints, const Eigen::Isometry3d& tool_world) {
  RenderRequest req;
  req.output = (std::filesystem::path(dir) / "overview.png").string();
  req.view = "part";
  req.joints = joints;
  req.tool_world_m = tool_world;
  RenderRequest::PointSet sets[3];
  sets[0].label = "stitch";
  sets[0].rgba = kClean;
  sets[1].label = "stitch_warning";
  sets[1].rgba = kWarn;
  sets[2].label = "stitch_error";
  sets[2].rgba = kError;
  const auto& marks = v.StitchMarks();
  // Each drawn point costs the software renderer ~100 KB: at most kMaxPerSet per verdict.
  constexpr std::size_t kMaxPerSet = 1000;
  const std::size_t stride = std::max<std::size_t>(1, marks.size() / kMaxPerSet);
  for (std::size_t i = 0; i < marks.size(); ++i) {
    const auto& m = marks[i];
    if (m.severity == 0 && i % stride != 0) continue;
    auto& set = sets[std::min<int>(m.severity, 2)];
    if (set.points_part_mm.size() < kMaxPerSet)
      set.points_part_mm.push_back(m.position_mm.cast<double>());
  }
  for (auto& s : sets) {
    if (!s.points_part_mm.empty()) req.point_sets.push_back(std::move(s));
  }
  // What the rules draw (AFP: the laid courses' edges, gaps and overlaps).
  for (const auto& rule : v.Rules()) {
    for (auto& drawn : rule->Drawings()) {
      if (drawn.points_mm.empty()) continue;
      RenderRequest::PointSet set;
      set.rgba = DrawnColour(drawn.label);
      set.radius_scale = drawn.label == "afp_laid" ? 0.5 : 1.0;
      set.label = std::move(drawn.label);
      set.points_part_mm = std::move(drawn.points_mm);
      req.point_sets.push_back(std::move(set));
    }
  }
  if (req.point_sets.empty()) return kExitOk;
  return RunRenderScene(ls, req);
}

// Close-up of the head at a rule's worst sample, the offending stitch highlighted.
int WriteCloseUp(const LoadedScene& ls, const sim::CellSetup& cell, const verify::Rule& rule,
                 const std::string& dir) {
  const auto& s = rule.WorstSample();
  if (!s) return kExitOk;
  RenderRequest req;
  req.output = (std::filesystem::path(dir) / (rule.Summary().id + ".png")).string();
  req.view = "head";
  req.width = 1024;
  req.height = 768;
  req.joints = s->has_joints ? s->joints : SolveStartPose(ls, s->tool_part).joints;
  req.tool_world_m = sim::PartPoseWorld(cell, req.joints[sim::kRotator]) * [&] {
    Eigen::Isometry3d t = s->tool_part;
    t.translation() /= 1000.0;
    return t;
  }();
  // The offending stitch: a red ring on the preform around the tool point (the presser
  // foot hides the stitch itself) and a red dot at the tool point.
  const Eigen::Vector3d centre = s->tool_part.translation();
  const Eigen::Vector3d up = s->tool_part.linear().col(2);
  const Eigen::Vector3d ex = s->tool_part.linear().col(0), ey = s->tool_part.linear().col(1);
  RenderRequest::PointSet ring;
  ring.label = "stitch_error";
  ring.rgba = kError;
  ring.polyline = true;
  for (int k = 0; k <= 48; ++k) {
    const double a = 2 * 3.14159265358979 * k / 48;
    ring.points_part_mm.push_back(centre + (ls.scene->preform_thickness_mm + 1.0) * up +
                                  70.0 * (std::cos(a) * ex + std::sin(a) * ey));
  }
  req.point_sets.push_back(std::move(ring));
  RenderRequest::PointSet hit;
  hit.label = "stitch_error";
  hit.rgba = kError;
  hit.radius_scale = 2.0;
  hit.points_part_mm.push_back(centre);
  req.point_sets.push_back(std::move(hit));
  return RunRenderScene(ls, req);
}

// The snapshots: the AFP coverage maps, the overview, a close-up per rule with errors.
int WriteSnapshots(const LoadedScene& ls, const sim::CellSetup& cell,
                   const verify::Verifier& verifier, const std::string& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) {
    PrintError("io-write", "cannot create snapshot folder " + dir + ": " + ec.message());
    return kExitBadInput;
  }
  if (WriteAfpCoverageSnapshots(verifier, dir) != kExitOk) return kExitBadInput;
  // The overview shows the robot clear above the start of the scene's first path.
  Eigen::Isometry3d approach = PathStartTool(*ls.scene, ls.scene->paths.front());
  approach.translation() += 400.0 * approach.linear().col(2);
  const StartPose start = SolveStartPose(ls, approach);
  if (WriteOverview(ls, verifier, dir, start.joints, start.tool_world_m) != kExitOk) {
    return kExitBadInput;
  }
  for (const auto& rule : verifier.Rules()) {
    if (rule->Summary().errors == 0) continue;
    if (WriteCloseUp(ls, cell, *rule, dir) != kExitOk) return kExitBadInput;
  }
  return kExitOk;
}

// --html: the snapshots (into --snapshots' folder, or a scratch folder removed afterwards)
// read back, then the page.
int WriteHtml(const VerifyArgs& a, const VerifySession& vs, const verify::Report& report,
              const verify::Verifier& verifier, PoseTrack& poses) {
  namespace fs = std::filesystem;
  const bool scratch = a.snapshots.empty();
  const fs::path dir =
      scratch ? fs::temp_directory_path() / ("stitchsim-html-" + std::to_string(::getpid()))
              : fs::path(a.snapshots);
  if (scratch && WriteSnapshots(vs.ls, vs.cell, verifier, dir.string()) != kExitOk) {
    return kExitBadInput;
  }
  HtmlInputs in;
  std::vector<fs::path> pngs;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    if (e.path().extension() == ".png") pngs.push_back(e.path());
  }
  std::sort(pngs.begin(), pngs.end(), [](const fs::path& x, const fs::path& y) {
    const bool ox = x.filename() == "overview.png", oy = y.filename() == "overview.png";
    return ox != oy ? ox : x.filename() < y.filename();
  });
  for (const fs::path& png : pngs) {
    std::ifstream f(png, std::ios::binary);
    in.snapshots.emplace_back(png.filename().string(),
                              std::string(std::istreambuf_iterator<char>(f), {}));
  }
  if (scratch) fs::remove_all(dir, ec);
  poses.SetMaxPoses(HtmlLimits{}.max_poses);
  poses.Thin(PointedLines(verifier), INT_MAX);
  in.report = &report;
  in.verifier = &verifier;
  in.scene = &vs.ls;
  in.poses = &poses;
  return WriteHtmlReport(a.html, in);
}

int RunVerify(const VerifyArgs& a) {
  if (!OutputsDistinct({{"--report", a.report_json},
                        {"--junit", a.junit},
                        {"--save-trace", a.save_trace},
                        {"--html", a.html},
                        {"--part", a.part}})) {
    return kExitBadInput;
  }
  int shard = 0, shards = 0;
  if (!a.shard.empty() && !ParseShard(a.shard, shard, shards)) return kExitBadInput;
  if (a.shard.empty() != a.part.empty()) {
    PrintError("cli-usage", "--shard I/N and --part FILE go together");
    return kExitBadInput;
  }
  if (!a.shard.empty() && (a.dynamics || !a.save_trace.empty() || !a.report_json.empty() ||
                           !a.junit.empty() || !a.snapshots.empty() || !a.html.empty())) {
    PrintError("cli-usage",
               "--shard writes a partial result (--part) only: reports come from `stitchsim "
               "report merge`; --dynamics and --save-trace run in one process");
    return kExitBadInput;
  }
  VerifyRunOptions run_options;
  run_options.program = a.program;
  run_options.dialect = a.dialect;
  run_options.scene = a.scene;
  run_options.save_trace = a.save_trace;
  run_options.no_collision = a.no_collision;
  run_options.allow_mismatch = a.allow_mismatch;
  run_options.dynamics = a.dynamics;
  run_options.quiet = a.quiet;
  run_options.keep_stitch_marks = !a.snapshots.empty() || !a.html.empty();
  run_options.record_poses = !a.html.empty();
  run_options.jobs = a.jobs;
  run_options.shard = a.shard;
  run_options.part = a.part;
  run_options.chunk_lines = a.chunk_lines;
  run_options.warm_lines = a.warm_lines;
  VerifyRun run;
  const int rc = RunVerification(run_options, run);
  if (rc != kExitOk || !a.shard.empty()) return rc;
  if (WriteReports(run.report, a.report_json, a.junit) != kExitOk) return kExitBadInput;
  if (!a.snapshots.empty() &&
      WriteSnapshots(run.session->ls, run.session->cell, *run.verifier, a.snapshots) != kExitOk) {
    return kExitBadInput;
  }
  if (!a.html.empty() &&
      WriteHtml(a, *run.session, run.report, *run.verifier, run.poses) != kExitOk) {
    return kExitBadInput;
  }
  return run.report.errors == 0 ? kExitOk : kExitFindings;
}

}  // namespace

void AddVerifyCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<VerifyArgs>();
  CLI::App* cmd = app.add_subcommand(
      "verify", "Execute a programme on the cell and check every stitch and pose");
  cmd->add_option("program", args->program, "Programme file (G-code)")->required();
  cmd->add_option("--scene", args->scene, "Scene YAML file")->required();
  cmd->add_option("--report", args->report_json, "Write the JSON report here");
  cmd->add_option("--junit", args->junit, "Write a JUnit XML report here");
  cmd->add_option("--dialect", args->dialect,
                  "Dialect YAML file (default: the built-in dialect, models/dialect/default.yaml)");
  cmd->add_option("--save-trace", args->save_trace,
                  "Write the trace the rules read here, to check again with `stitchsim recheck`");
  cmd->add_option("--snapshots", args->snapshots,
                  "Write overview.png and <rule>.png close-ups into this folder");
  cmd->add_option("--html", args->html,
                  "Write one self-contained HTML report here: findings, snapshots, a 3D view of "
                  "the cell posed at any line, plots of every rule along the programme");
  AddScenePathFlag(*cmd);
  cmd->add_flag("--no-collision", args->no_collision,
                "Skip the FCL collision checks (collision.* rules)");
  cmd->add_flag("--dynamics", args->dynamics,
                "Step MuJoCo's physics with the joint servos tracking the timed trajectory: the "
                "needle rules see the arm's lag, dyn.tracking reports it");
  cmd->add_option("--jobs,-j", args->jobs,
                  "Worker threads (default: the number of cores); reports are the same for any "
                  "number")
      ->check(CLI::Range(0, 256));
  cmd->add_option("--shard", args->shard,
                  "I/N: verify the I-th of N shares of the programme (I = 1..N) into --part; "
                  "`stitchsim report merge` makes the report (docs/ci.md)");
  cmd->add_option("--part", args->part, "--shard: write the partial result here");
  cmd->add_option("--chunk-lines", args->chunk_lines,
                  "--jobs/--shard: cut the programme at the first safe point after every this "
                  "many lines (reports do not depend on it; shards of one run must agree)")
      ->check(CLI::Range(1, 1 << 30));
  cmd->add_option("--warm-lines", args->warm_lines,
                  "--jobs/--shard: lines each chunk runs before its own to rebuild the state a "
                  "serial run carries there (a chunk that rebuilt it wrong runs again)")
      ->check(CLI::Range(0, 1 << 30));
  cmd->add_flag("--quiet,-q", args->quiet, "No progress on stderr");
  cmd->add_flag("--allow-mismatch", args->allow_mismatch,
                "Verify a programme whose header names another scene or head, or that mounts "
                "another head (T.. M6), on this scene's cell anyway");
  cmd->callback([args, &exit_code] { exit_code = RunVerify(*args); });
}

}  // namespace stitchsim::app
