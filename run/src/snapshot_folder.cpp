// The snapshot folder of a finished run (run/snapshots.h): the overview, the close-ups of the
// rules with errors, the AFP coverage maps and snapshots.json.
#include <filesystem>
#include <nlohmann/json.hpp>

#include "detail/close_up_draw.h"
#include "stitchsim/common/files.h"
#include "stitchsim/render/scene_model.h"
#include "stitchsim/render/text.h"
#include "stitchsim/run/close_up.h"
#include "stitchsim/run/laid_ribbons.h"
#include "stitchsim/run/scene_render.h"
#include "stitchsim/run/snapshots.h"
#include "stitchsim/run/start_pose.h"

namespace stitchsim::run {
namespace {

namespace fs = std::filesystem;

constexpr int kCloseUpWidth = 1024;
constexpr int kCloseUpHeight = 768;
constexpr int kOverviewWidth = 1280;
constexpr int kOverviewHeight = 960;
// The overview's ribbon boxes at most (MuJoCo's scene holds 20000 geoms with the model's).
constexpr std::size_t kMaxRibbonSegments = 12000;

// "2nd", "3rd", "21st", "4th", ...
std::string Ordinal(int n) {
  const int tens = n % 100, last = n % 10;
  const char* suffix = (tens >= 11 && tens <= 13) ? "th"
                       : last == 1                ? "st"
                       : last == 2                ? "nd"
                       : last == 3                ? "rd"
                                                  : "th";
  return std::to_string(n) + suffix;
}

// Colours by verdict (overview).
constexpr std::array<float, 4> kCleanRgba = {0.1f, 0.85f, 0.2f, 1.0f};
constexpr std::array<float, 4> kWarnRgba = {1.0f, 0.65f, 0.0f, 1.0f};
constexpr std::array<float, 4> kErrorRgba = {0.95f, 0.05f, 0.05f, 1.0f};
constexpr render::Rgb kErrorAccent = {200, 30, 30};
constexpr render::Rgb kPassAccent = {40, 160, 60};

std::string OverviewLegendText(const std::string& label) {
  if (label == "stitch") return "stitch, clean";
  if (label == "stitch_warning") return "stitch with a warning";
  if (label == "stitch_error") return "stitch with an error";
  if (label == "finding_warning") return "tool point of a warning";
  if (label == "finding_error") return "tool point of an error";
  if (label == "afp_laid") return "laid tows (course edges)";
  if (label == "afp_gap") return "gap between courses";
  if (label == "afp_overlap") return "overlap of courses";
  return label;
}

std::string CountedNoun(long n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

// The stitches coloured by verdict and what the rules draw, the laid tows as ribbons coloured
// by ply (their legend entries into `ply_legend`), over the cell (robot shown clear above the
// start of the first path).
RenderRequest OverviewRequest(const SnapshotInputs& in,
                              std::vector<render::LegendEntry>& ply_legend) {
  const verify::Verifier& v = *in.verifier;
  RenderRequest req;
  req.view = "part";
  req.width = kOverviewWidth;
  req.height = kOverviewHeight;
  Eigen::Isometry3d approach = PathStartTool(*in.scene->scene, in.scene->scene->paths.front());
  approach.translation() += 400.0 * approach.linear().col(2);
  const StartPose start = SolveStartPose(*in.scene, approach);
  req.joints = start.joints;
  req.tool_world_m = start.tool_world_m;
  RenderRequest::PointSet sets[3];
  const char* labels[3] = {"stitch", "stitch_warning", "stitch_error"};
  const std::array<float, 4> colours[3] = {kCleanRgba, kWarnRgba, kErrorRgba};
  for (int i = 0; i < 3; ++i) {
    sets[i].label = labels[i];
    sets[i].rgba = colours[i];
  }
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
  // No stitches (fibre placement): the places of the findings, by severity.
  if (marks.empty()) {
    sets[1].label = "finding_warning";
    sets[2].label = "finding_error";
    for (const auto& rule : v.Rules()) {
      for (const verify::Finding& f : rule->Summary().findings) {
        auto& set = sets[f.severity == verify::FindingSeverity::kError ? 2 : 1];
        if (f.position_mm && set.points_part_mm.size() < kMaxPerSet) {
          set.points_part_mm.emplace_back((*f.position_mm)[0], (*f.position_mm)[1],
                                          (*f.position_mm)[2]);
        }
      }
    }
  }
  for (auto& s : sets) {
    if (!s.points_part_mm.empty()) req.point_sets.push_back(std::move(s));
  }
  // AFP: the laid material as ribbons coloured by ply, in place of the course edges' dots.
  LaidRibbons ribbons =
      MakeLaidRibbons(v.Laid(), kMaxRibbonSegments, in.scene->scene->preform_thickness_mm);
  const bool have_ribbons = !ribbons.sets.empty();
  for (auto& set : ribbons.sets) req.point_sets.push_back(std::move(set));
  ply_legend = std::move(ribbons.legend);
  if (have_ribbons && (ribbons.tows_per_ribbon > 1 || ribbons.station_step > 1)) {
    ply_legend.push_back(
        {{0, 0, 0},
         "thinned: " + std::to_string(ribbons.tows_per_ribbon) + " tows per ribbon, every " +
             (ribbons.station_step > 1 ? Ordinal(ribbons.station_step) + " " : "") + "station"});
  }
  for (const auto& rule : v.Rules()) {
    for (auto& drawn : rule->Drawings()) {
      if (drawn.points_mm.empty() || verify::CloseUpOnly(drawn) ||
          (have_ribbons && drawn.label == "afp_laid"))
        continue;
      RenderRequest::PointSet set;
      set.rgba = DrawnColour(drawn.label);
      set.radius_scale = drawn.label == "afp_laid" ? 0.5 : 1.0;
      set.label = std::move(drawn.label);
      set.points_part_mm = std::move(drawn.points_mm);
      req.point_sets.push_back(std::move(set));
    }
  }
  return req;
}

Status WriteOverview(const SnapshotInputs& in, const render::SnapshotFonts& fonts,
                     const fs::path& dir, DiagnosticSink& sink) {
  const verify::Report& report = *in.report;
  std::vector<render::LegendEntry> ply_legend;
  RenderRequest req = OverviewRequest(in, ply_legend);
  req.output = (dir / "overview.png").string();
  render::TitleBar title;
  title.line1 = "overview · " + std::string(report.errors == 0 ? "PASS" : "FAIL") + ": " +
                CountedNoun(report.errors, "error", "errors") + ", " +
                CountedNoun(report.warnings, "warning", "warnings");
  title.line2 = "scene " + report.scene_name + " · " +
                (report.stitches > 0 ? CountedNoun(report.stitches, "stitch", "stitches")
                                     : CountedNoun(report.moves, "move", "moves")) +
                " · " + fs::path(report.program_file).filename().string();
  title.accent = report.errors == 0 ? kPassAccent : kErrorAccent;
  std::vector<render::LegendEntry> legend;
  for (const auto& set : req.point_sets) {
    if (set.label.rfind("afp_ply_", 0) == 0) continue;  // one entry per ply, below
    legend.push_back({render::ToRgb(set.rgba), OverviewLegendText(set.label)});
  }
  legend.insert(legend.end(), ply_legend.begin(), ply_legend.end());
  if (legend.empty()) legend.push_back({render::ToRgb({0.1f, 0.9f, 0.2f, 1.0f}), "scene paths"});
  req.decorate = [&](render::Image& img) {
    render::DrawTitleBar(img, fonts, title);
    render::DrawLegend(img, fonts, legend);
  };
  return RenderScene(*in.scene, req, sink);
}

render::TitleBar CloseUpTitle(const verify::Rule& rule, const verify::Report& report) {
  const verify::RuleSummary& s = rule.Summary();
  render::TitleBar t;
  t.line1 = s.id + " · ERROR · " + CountedNoun(s.errors, "line", "lines") + " with errors";
  if (s.warnings > 0) t.line1 += ", " + CountedNoun(s.warnings, "warning", "warnings");
  const verify::Finding* f = FocusFinding(rule);
  std::string l2;
  if (f != nullptr) {
    l2 = "line " + std::to_string(f->line) + " · ";
    if (f->stitch > 0) l2 += "stitch " + std::to_string(f->stitch) + " · ";
    if (!f->subject.empty()) l2 += f->subject + " ";
    const std::string unit = f->unit.empty() ? "" : " " + f->unit;
    l2 += close_up::Fmt("%.4g", f->value) + unit + " (limit " + close_up::Fmt("%.4g", f->limit) +
          unit + ") · ";
  }
  t.line2 = l2 + fs::path(report.program_file).filename().string();
  return t;
}

std::vector<std::string> ShotGeomNames(const mjModel& m, const std::vector<int>& geoms) {
  std::vector<std::string> out;
  for (int g : geoms) {
    const char* n = mj_id2name(&m, mjOBJ_GEOM, g);
    out.emplace_back(n != nullptr ? n : "");
  }
  return out;
}

// What the picture shows, enough to render it again (the tests do, as a segmentation).
nlohmann::json ShotJson(const mjModel& m, const std::string& file, const verify::Rule& rule,
                        const CloseUpPlan& plan, const Shot& shot) {
  nlohmann::json j;
  j["file"] = file;
  j["rule"] = rule.Summary().id;
  j["family"] = verify::CloseUpFamilyName(plan.family);
  j["camera"] = {
      {"lookat_m", {shot.view.lookat_m.x(), shot.view.lookat_m.y(), shot.view.lookat_m.z()}},
      {"distance_m", shot.view.distance_m},
      {"azimuth_deg", shot.view.azimuth_deg},
      {"elevation_deg", shot.view.elevation_deg},
      {"znear_m", m.vis.map.znear * m.stat.extent}};
  nlohmann::json subjects = nlohmann::json::array();
  for (std::size_t i = 0; i < shot.pixels.size(); ++i) {
    const SubjectPixels& p = shot.pixels[i];
    subjects.push_back({{"name", p.name},
                        {"geoms", ShotGeomNames(m, plan.subjects[i].geoms)},
                        {"overlays", plan.subjects[i].overlays},
                        {"pixels", p.visible},
                        {"alone_pixels", p.alone},
                        {"hidden_pixels", p.hidden}});
  }
  j["subjects"] = subjects;
  j["joints"] = std::vector<double>(plan.joints.data(), plan.joints.data() + plan.joints.size());
  j["see_through"] = shot.see_through;
  j["transparent_geoms"] = ShotGeomNames(m, shot.transparent);
  nlohmann::json legend = nlohmann::json::array();
  for (const auto& e : plan.legend) legend.push_back(e.label);
  j["legend"] = legend;
  return j;
}

// The close-ups of the rules with errors, into `manifest`.
Status WriteCloseUps(const SnapshotInputs& in, const render::SnapshotFonts& fonts,
                     const fs::path& dir, nlohmann::json& manifest, DiagnosticSink& sink) {
  const verify::Verifier& v = *in.verifier;
  render::MjModelPtr model = render::LoadSceneModel(*in.scene->scene, sink);
  if (sink.HasErrors() || !model) return Status::InSink();
  // Close-ups come as near as a few centimetres (the needles): a near clipping plane of 1 cm.
  model->vis.map.znear = std::min<float>(model->vis.map.znear, 0.01 / model->stat.extent);
  render::MjDataPtr data(mj_makeData(model.get()));
  const CloseUpContext ctx{in.scene,   in.process,       in.cell, model.get(),
                           data.get(), &v.StitchMarks(), &v};
  for (const auto& rule : v.Rules()) {
    if (rule->Summary().errors == 0) continue;
    std::optional<CloseUpPlan> plan;
    std::string error;
    if (!PlanCloseUp(ctx, *rule, plan, error)) return Status::Error("model-missing-joint", error);
    if (!plan) continue;
    Shot shot;
    if (!ShootCloseUp(model.get(), data.get(), *plan, kCloseUpWidth, kCloseUpHeight, shot, error)) {
      return Status::Error("render-context", error);
    }
    render::DrawTitleBar(shot.image, fonts, CloseUpTitle(*rule, *in.report));
    render::DrawLegend(shot.image, fonts, plan->legend);
    const std::string file = rule->Summary().id + ".png";
    if (std::string err = render::WritePng(dir / file, shot.image); !err.empty()) {
      return Status::Error("io-write", err);
    }
    manifest["pictures"].push_back(ShotJson(*model, file, *rule, *plan, shot));
  }
  return Status::Ok();
}

}  // namespace

std::array<float, 4> DrawnColour(const std::string& label) {
  if (label == "afp_gap") return kErrorRgba;
  if (label == "afp_overlap") return {0.85f, 0.1f, 0.85f, 1.0f};
  return {0.15f, 0.45f, 0.95f, 1.0f};
}

Status WriteSnapshotFolder(const SnapshotInputs& in, const std::string& folder,
                           DiagnosticSink& sink) {
  const fs::path dir(folder);
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) {
    return Status::Error("io-write",
                         "cannot create snapshot folder " + folder + ": " + ec.message());
  }
  // The fonts first: a missing font stops before any picture is drawn.
  render::SnapshotFonts overview_fonts, close_fonts;
  std::string error;
  if (!render::OpenSnapshotFonts(kOverviewWidth, overview_fonts, error) ||
      !render::OpenSnapshotFonts(kCloseUpWidth, close_fonts, error)) {
    return Status::Error("io-missing-file", "snapshots: " + error);
  }
  if (Status st = WriteAfpCoverageSnapshots(*in.verifier, *in.scene->scene, folder); !st.ok)
    return st;
  if (Status st = WriteAfpLaminateSnapshots(*in.verifier, folder); !st.ok) return st;
  if (Status st = WriteOverview(in, overview_fonts, dir, sink); !st.ok) return st;
  nlohmann::json manifest;
  manifest["overview"] = "overview.png";
  manifest["width"] = kCloseUpWidth;
  manifest["height"] = kCloseUpHeight;
  manifest["pictures"] = nlohmann::json::array();
  if (Status st = WriteCloseUps(in, close_fonts, dir, manifest, sink); !st.ok) return st;
  if (std::string err = WriteFileAtomically(dir / "snapshots.json", manifest.dump(2) + "\n");
      !err.empty()) {
    return Status::Error("io-write", err);
  }
  return Status::Ok();
}

}  // namespace stitchsim::run
