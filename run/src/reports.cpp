#include "stitchsim/run/reports.h"

#include <filesystem>
#include <optional>
#include <utility>

#include "stitchsim/common/files.h"

namespace stitchsim::run {

std::vector<trace::FileFingerprint> SceneFingerprints(const scene::Scene& scene) {
  const std::pair<const char*, const std::filesystem::path*> files[] = {
      {"scene", &scene.file},
      {"head spec", &scene.head.file},
      {"cell URDF", &scene.cell_urdf},
      {"cell MJCF", &scene.cell_mjcf},
      {"head MJCF", &scene.head.mjcf}};
  std::vector<trace::FileFingerprint> out;
  for (const auto& [role, path] : files) {
    if (path->empty()) continue;
    const std::optional<std::string> bytes = ReadFile(*path);
    // An unreadable file fingerprints as 0: it matches nothing a readable file gives.
    out.push_back({role, path->string(), bytes ? trace::Fnv1a64(*bytes) : 0});
  }
  return out;
}

verify::Report RunReport(const std::string& program_file, const std::string& scene_file,
                         const scene::Scene& scene, double stitch_length_mm,
                         const trace::TraceFileSummary& run) {
  verify::Report report;
  report.program_file = program_file;
  report.scene_file = scene_file;
  report.scene_name = scene.name;
  report.head = scene.head.name;
  report.lines = run.lines;
  report.moves = run.moves;
  report.stitch_length_mm = stitch_length_mm;
  report.cycle_time_s = run.cycle_time_s;
  report.cycle_time_timed_s = run.cycle_time_timed_s;
  return report;
}

std::string WriteReportFiles(const verify::Report& report, const std::string& json_path,
                             const std::string& junit_path) {
  std::vector<std::pair<std::filesystem::path, std::string>> reports;
  if (!json_path.empty()) reports.emplace_back(json_path, verify::ReportToJson(report));
  if (!junit_path.empty()) reports.emplace_back(junit_path, verify::ReportToJunit(report));
  return WriteFilesAtomically(reports);
}

}  // namespace stitchsim::run
