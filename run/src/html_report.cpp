// The HTML report (run/html_report.h): the page's data from the report, the verifier and the
// scene's MuJoCo model, put into the template with the embedded scripts (html_assets.h).
#include "stitchsim/run/html_report.h"

#include <algorithm>
#include <cmath>

#include "html_assets.h"
#include "stitchsim/common/base64.h"
#include "stitchsim/common/files.h"
#include "stitchsim/render/cell_export.h"
#include "stitchsim/render/scene_model.h"
#include "stitchsim/run/html_laid.h"
#include "stitchsim/run/snapshots.h"
#include "stitchsim/sim/robot_model.h"

namespace stitchsim::run {
namespace {

using nlohmann::json;

json JsonNumber(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }
json JsonOptional(const std::optional<double>& v) { return v ? JsonNumber(*v) : json(nullptr); }

json PageSummaryJson(const verify::Report& r, const scene::Scene& scene) {
  return json{{"program", r.program_file},
              {"scene_file", r.scene_file},
              {"scene", r.scene_name},
              {"head", r.head},
              {"verdict", r.verdict},
              {"lines", r.lines},
              {"moves", r.moves},
              {"stitches", r.stitches},
              {"cycle_time_s", JsonNumber(r.cycle_time_s)},
              {"cycle_time_timed_s", JsonNumber(r.cycle_time_timed_s)},
              {"errors", r.errors},
              {"warnings", r.warnings},
              {"tool_version", r.tool_version},
              {"kind", scene.head.kind == scene::HeadKind::kAfp ? "afp" : "stitch"}};
}

json PageRulesJson(const verify::Report& r) {
  json rules = json::array();
  for (const verify::RuleSummary& s : r.rules) {
    rules.push_back(json{{"id", s.id},
                         {"description", s.description},
                         {"unit", s.unit},
                         {"checked", s.checked},
                         {"errors", s.errors},
                         {"warnings", s.warnings},
                         {"error_limit", JsonOptional(s.error_limit)},
                         {"warning_limit", JsonOptional(s.warning_limit)},
                         {"worst_value", s.Applies() ? JsonOptional(s.worst_value) : json(nullptr)},
                         {"worst_line", s.worst_line},
                         {"worst_stitch", s.worst_stitch},
                         {"truncated", s.truncated}});
  }
  return rules;
}

json PageFindingsJson(const verify::Report& r, std::size_t max_findings) {
  std::vector<const verify::Finding*> all;
  for (const verify::RuleSummary& s : r.rules) {
    for (const verify::Finding& f : s.findings) all.push_back(&f);
  }
  // Programme order; errors first when the list must be cut.
  std::stable_sort(all.begin(), all.end(), [](const verify::Finding* a, const verify::Finding* b) {
    return a->severity != b->severity ? a->severity == verify::FindingSeverity::kError
                                      : a->line < b->line;
  });
  if (all.size() > max_findings) all.resize(max_findings);
  std::stable_sort(all.begin(), all.end(), [](const verify::Finding* a, const verify::Finding* b) {
    return a->line < b->line;
  });
  json out = json::array();
  for (const verify::Finding* f : all) {
    json position = nullptr;
    if (f->position_mm) {
      position = json::array({(*f->position_mm)[0], (*f->position_mm)[1], (*f->position_mm)[2]});
    }
    out.push_back(
        json{{"rule", f->rule},
             {"severity", f->severity == verify::FindingSeverity::kError ? "error" : "warning"},
             {"line", f->line},
             {"stitch", f->stitch},
             {"value", JsonNumber(f->value)},
             {"limit", JsonNumber(f->limit)},
             {"unit", f->unit},
             {"subject", f->subject},
             {"message", f->message},
             {"position_mm", std::move(position)}});
  }
  return out;
}

// Every flagged stitch, and clean ones evenly thinned to fill the budget.
json PageStitchesJson(const verify::Verifier& v, std::size_t max_stitches) {
  const auto& marks = v.StitchMarks();
  std::size_t flagged = 0;
  for (const auto& m : marks) flagged += m.severity > 0 ? 1 : 0;
  const std::size_t clean = marks.size() - flagged;
  const std::size_t room = max_stitches > flagged ? max_stitches - flagged : 0;
  const std::size_t clean_stride =
      room == 0 ? 0 : std::max<std::size_t>(1, (clean + room - 1) / room);
  const std::size_t flagged_stride =
      flagged > max_stitches ? (flagged + max_stitches - 1) / max_stitches : 1;
  std::vector<float> pos;
  std::vector<std::uint8_t> verdict;
  std::vector<std::int32_t> lines;
  std::size_t clean_seen = 0, flagged_seen = 0;
  for (const auto& m : marks) {
    if (m.line <= 0) continue;  // a stitch number the drive skipped
    const bool keep = m.severity > 0 ? flagged_seen++ % flagged_stride == 0
                                     : clean_stride > 0 && clean_seen++ % clean_stride == 0;
    if (!keep) continue;
    pos.insert(pos.end(), {m.position_mm.x(), m.position_mm.y(), m.position_mm.z()});
    verdict.push_back(m.severity);
    lines.push_back(m.line);
  }
  return json{{"positions", Base64Of(pos)},
              {"verdict", Base64Of(verdict)},
              {"lines", Base64Of(lines)},
              {"total", static_cast<long>(marks.size())}};
}

json PageDrawingsJson(const verify::Verifier& v) {
  json out = json::array();
  for (const auto& rule : v.Rules()) {
    for (const verify::DrawnPoints& d : rule->Drawings()) {
      if (d.points_mm.empty() || verify::CloseUpOnly(d)) continue;  // the close-up's own
      std::vector<float> pos;
      for (const auto& p : d.points_mm) {
        pos.insert(pos.end(), {static_cast<float>(p.x()), static_cast<float>(p.y()),
                               static_cast<float>(p.z())});
      }
      const std::array<float, 4> rgba = DrawnColour(d.label);
      out.push_back(json{{"label", d.label}, {"rgba", rgba}, {"positions", Base64Of(pos)}});
    }
  }
  return out;
}

json PagePosesJson(const PoseTrack& track, json& path) {
  std::vector<std::int32_t> lines;
  std::vector<float> q, t, tool;
  for (const LinePose& p : track.Poses()) {
    lines.push_back(p.line);
    q.insert(q.end(), p.q.begin(), p.q.end());
    t.push_back(p.time_s);
    tool.insert(tool.end(), p.tool.begin(), p.tool.end());
  }
  path = json{{"positions", Base64Of(tool)}, {"lines", Base64Of(lines)}};
  return json{{"lines", Base64Of(lines)}, {"q", Base64Of(q)}, {"t", Base64Of(t)}};
}

json PageSeriesJson(const verify::Verifier& v) {
  json out = json::array();
  for (const auto& rule : v.Rules()) {
    const verify::ValueSeries& s = rule->Series();
    if (s.Empty()) continue;
    const verify::RuleSummary& r = rule->Summary();
    out.push_back(json{{"rule", r.id},
                       {"subject", ""},
                       {"unit", r.unit},
                       {"error_limit", JsonOptional(r.error_limit)},
                       {"warning_limit", JsonOptional(r.warning_limit)},
                       {"lower_bound", rule->LowerBound()},
                       {"first_line", s.FirstLine()},
                       {"bucket_lines", s.BucketLines()},
                       {"min", Base64Of(s.Min())},
                       {"max", Base64Of(s.Max())}});
  }
  return out;
}

}  // namespace

json HtmlData(const HtmlInputs& in, const HtmlLimits& limits, std::string& error) {
  DiagnosticSink sink;
  render::MjModelPtr model = render::LoadSceneModel(*in.scene->scene, sink);
  if (!model) {
    error = sink.Diagnostics().empty() ? "the scene's MuJoCo model did not compile"
                                       : sink.Diagnostics().front().message;
    return nullptr;
  }
  render::CellExportOptions co;
  for (std::size_t j = 0; j < co.joints.size(); ++j) co.joints[j] = sim::kJointNames[j];
  co.max_faces = limits.max_faces;
  json cell = render::ExportCell(*model, co, error);
  if (cell.is_null()) return nullptr;
  json snapshots = json::array();
  for (const auto& [name, bytes] : in.snapshots) {
    snapshots.push_back(json{{"name", name}, {"png", Base64(bytes.data(), bytes.size())}});
  }
  json path;
  json poses = PagePosesJson(*in.poses, path);
  return json{{"format", "stitchsim-html-1"},
              {"summary", PageSummaryJson(*in.report, *in.scene->scene)},
              {"rules", PageRulesJson(*in.report)},
              {"skipped",
               [&] {
                 json s = json::array();
                 for (const auto& k : in.report->skipped)
                   s.push_back({{"id", k.id}, {"reason", k.reason}});
                 return s;
               }()},
              {"findings", PageFindingsJson(*in.report, limits.max_findings)},
              {"snapshots", std::move(snapshots)},
              {"cell", std::move(cell)},
              {"stitches", PageStitchesJson(*in.verifier, limits.max_stitches)},
              {"path", std::move(path)},
              {"drawings", PageDrawingsJson(*in.verifier)},
              {"laid", PageLaidJson(in.verifier->Laid(), limits.max_laid_values)},
              {"poses", std::move(poses)},
              {"series", PageSeriesJson(*in.verifier)}};
}

std::string HtmlPage(const json& data, std::string& error) {
  return HtmlPageOf(ReportTemplateHtml(), ReportJs(), AfpViewJs(), data, error);
}

std::string HtmlPageOf(std::string_view page_template, std::string_view app_js,
                       std::string_view afp_js, const json& data, std::string& error) {
  std::string text = data.dump(-1, ' ', false, json::error_handler_t::replace);
  // Inside <script>: "</" would end the element early.
  std::string safe;
  safe.reserve(text.size() + 64);
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '<' && i + 1 < text.size() && text[i + 1] == '/') {
      safe += "<\\/";
      ++i;
    } else {
      safe += text[i];
    }
  }
  struct Part {
    std::string_view marker;
    std::string open;
    std::string_view body;
  };
  const Part parts[] = {
      {"<!--STITCHSIM:THREE-->", "<script>", ThreeJs()},
      {"<!--STITCHSIM:ORBIT-->", "<script>", OrbitControlsJs()},
      {"<!--STITCHSIM:APP-->", "<script>", app_js},
      {"<!--STITCHSIM:AFP-->", "<script>", afp_js},
      {"<!--STITCHSIM:DATA-->", "<script id=\"stitchsim-data\" type=\"application/json\">", safe},
  };
  std::string out(page_template);
  for (const Part& p : parts) {
    if (p.marker == "<!--STITCHSIM:AFP-->" && afp_js.empty()) continue;
    if (p.body.find("</script") != std::string_view::npos) {
      error = "an embedded script contains </script> (" + std::string(p.marker) + ")";
      return "";
    }
    const std::size_t at = out.find(p.marker);
    if (at == std::string::npos || out.find(p.marker, at + 1) != std::string::npos) {
      error = "the report template needs exactly one " + std::string(p.marker);
      return "";
    }
    std::string body = p.open;
    body.append(p.body);
    body += "</script>";
    out.replace(at, p.marker.size(), body);
  }
  return out;
}

Status WriteHtmlReportFile(const std::string& path, const HtmlInputs& in) {
  std::string error;
  const json data = HtmlData(in, HtmlLimits{}, error);
  if (data.is_null()) return Status::Error("html", error);
  const std::string page = HtmlPage(data, error);
  if (page.empty()) return Status::Error("internal", "--html: " + error);
  if (std::string err = WriteFileAtomically(path, page); !err.empty()) {
    return Status::Error("io-write", "--html: " + err);
  }
  return Status::Ok();
}

}  // namespace stitchsim::run
