#include "stitchsim/verify/verifier.h"

#include <algorithm>
#include <atomic>

#include "afp_laid_material_builder.h"
#include "detail/rule_registry.h"

namespace stitchsim::verify {

Verifier::Verifier(const RuleContext& ctx, bool keep_stitch_marks)
    : ctx_(ctx), window_(*ctx_.process), keep_marks_(keep_stitch_marks) {
  static std::atomic<std::uint64_t> instances{0};
  instance_ = ++instances;
  // From the verifier's copy: rules keep references to it (never to the caller's `ctx`).
  detail::RuleMaking making;
  rules_ = MakeRules(ctx_, making);
  if (!ctx_.scene->head.IsStitching()) {
    laydown_ = std::make_unique<LaydownMeter>(LaydownFor(ctx_));
    // The rules' own sampler (made here when no rule made it): each line is sampled once.
    if (keep_marks_) laid_ = std::make_unique<detail::LaidMaterialBuilder>(making.Laid(ctx_));
  }
}

Verifier::~Verifier() = default;

const LaidMaterial& Verifier::Laid() const {
  static const LaidMaterial kEmpty;
  return laid_ ? laid_->Material() : kEmpty;
}

namespace {

std::pair<long, long> Totals(const std::vector<std::unique_ptr<Rule>>& rules) {
  long e = 0, w = 0;
  for (const auto& r : rules) {
    e += r->Summary().errors;
    w += r->Summary().warnings;
  }
  return {e, w};
}

}  // namespace

void Verifier::MarkStitch(long stitch, std::size_t errors_before, std::size_t warnings_before) {
  if (!keep_marks_ || stitch <= 0 || marks_.empty()) return;
  const auto [e, w] = Totals(rules_);
  std::uint8_t sev = 0;
  if (static_cast<std::size_t>(e) > errors_before) {
    sev = 2;
  } else if (static_cast<std::size_t>(w) > warnings_before) {
    sev = 1;
  }
  const std::size_t idx = static_cast<std::size_t>(stitch - 1);
  if (idx < marks_.size()) marks_[idx].severity = std::max(marks_[idx].severity, sev);
}

void Verifier::OnLine(const trace::LineRecord& line) {
  line_from_ = line.from;
  line_to_ = line.to;
  saw_input_ = true;
  if (laydown_) laydown_->OnLine(line);
  // Before the rules: it samples the line, they reuse the sampling and hand it their figures.
  if (laid_) laid_->OnLine(line);
  for (auto& r : rules_) {
    r->saw_input_ = true;
    r->OnLine(line);
  }
}

// A dynamic run's sample: the commanded pose the walk follows (tool_part is the actual one).
const Eigen::Isometry3d* Verifier::WalkReference(const trace::TraceSample& s) {
  if (!s.tracked) return nullptr;
  commanded_ = process::InterpolatePose(line_from_, line_to_, s.line_fraction);
  return &commanded_;
}

void Verifier::OnSample(const trace::TraceSample& s) {
  const auto [e0, w0] = Totals(rules_);
  saw_input_ = true;
  for (auto& r : rules_) {
    r->saw_input_ = true;
    r->OnSample(s);
  }
  MarkStitch(s.stitch, static_cast<std::size_t>(e0), static_cast<std::size_t>(w0));

  if (s.event == trace::SampleEvent::kNeedleEntry) {
    if (window_.Active()) CloseWindow();
    ++stitches_;
    window_.Enter(s.tool_part, WalkReference(s));
    window_stitch_ = s.stitch;
    window_entry_line_ = s.source_line;
    last_in_sample_ = s;
    if (keep_marks_) {
      // Stitches are numbered by the drive; keep the vector indexable by stitch number.
      const std::size_t idx = static_cast<std::size_t>(std::max(0L, s.stitch - 1));
      if (marks_.size() <= idx) marks_.resize(idx + 1);
      marks_[idx].position_mm = s.tool_part.translation().cast<float>();
      marks_[idx].line = s.source_line;
    }
    PenetrationRecord p;
    p.stitch = s.stitch;
    p.line = s.source_line;
    p.tool = s.tool_part;
    p.points = process::PenetrationPoints(*ctx_.process, *ctx_.scene->surface, s.tool_part);
    p.foot = ctx_.scene->surface->Project(s.tool_part.translation());
    p.sample = s;
    const auto [e1, w1] = Totals(rules_);
    for (auto& r : rules_) r->OnPenetration(p);
    MarkStitch(s.stitch, static_cast<std::size_t>(e1), static_cast<std::size_t>(w1));
    return;
  }
  if (!window_.Active()) return;
  if (s.needles_in) {
    window_.Update(s.tool_part, WalkReference(s));
    last_in_sample_ = s;
    if (s.event == trace::SampleEvent::kNeedleExit) CloseWindow();
  } else {
    CloseWindow();
  }
}

void Verifier::CloseWindow() {
  WindowRecord w;
  w.stitch = window_stitch_;
  w.entry_line = window_entry_line_;
  w.exit_line = last_in_sample_.source_line;
  w.metrics = window_.Metrics();
  w.exit_sample = last_in_sample_;
  w.entry_tool = window_.Entry();
  window_ = process::NeedleWindow(*ctx_.process);
  const auto [e0, w0] = Totals(rules_);
  for (auto& r : rules_) {
    r->window_entry_ = &w.entry_tool;
    r->OnWindow(w);
    r->window_entry_ = nullptr;
  }
  MarkStitch(w.stitch, static_cast<std::size_t>(e0), static_cast<std::size_t>(w0));
}

void Verifier::Finish(Report& report) {
  if (window_.Active()) CloseWindow();
  for (auto& r : rules_) r->Finish(ctx_);
  if (laid_) laid_->Finish();
  report.rules.clear();
  report.errors = 0;
  report.warnings = 0;
  for (const auto& r : rules_) {
    RuleSummary s = r->Summary();
    std::stable_sort(s.findings.begin(), s.findings.end(),
                     [](const Finding& a, const Finding& b) { return a.line < b.line; });
    report.errors += s.errors;
    report.warnings += s.warnings;
    report.rules.push_back(std::move(s));
  }
  report.skipped = SkippedRules(ctx_);
  report.laydown.clear();
  if (laydown_) {
    laydown_->Finish();
    if (laydown_->SawAnything()) report.laydown = laydown_->Figures();
    for (const auto& r : rules_) r->AddLaydownFigures(report.laydown);
  }
  report.stitches = stitches_;
  report.verdict = report.errors == 0 ? "pass" : "fail";
}

}  // namespace stitchsim::verify
