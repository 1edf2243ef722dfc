// Chunked runs (verifier.h): a programme verified in parts, each by its own verifier, merged
// in programme order into the one verifier's report; accumulated state as JSON for parts
// verified in other processes; the carry that tells whether a part started exact.
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "detail/carry_bytes.h"
#include "stitchsim/verify/verifier.h"

namespace stitchsim::verify {
namespace {

constexpr const char* kPartialFormat = "stitchsim-verifier-partial";
constexpr int kPartialVersion = 1;

}  // namespace

bool Verifier::SawAnything() const {
  if (saw_input_) return true;
  for (const auto& r : rules_) {
    if (r->SawAnything()) return true;
  }
  return false;
}

void Verifier::ResetAccumulators() {
  for (const auto& r : rules_) {
    if (!r->Mergeable() && r->SawAnything()) {
      throw std::logic_error(r->Summary().id + " judges the programme as a whole: " +
                             "AFP programmes are verified in one part");
    }
  }
  for (auto& r : rules_) r->ResetAccumulators();
  if (laydown_) laydown_ = std::make_unique<LaydownMeter>(LaydownFor(ctx_));
  stitches_ = 0;
  // The marks' places stay (a later sample may still mark the last stitch entered).
  for (StitchMark& m : marks_) m.severity = 0;
  saw_input_ = false;
}

std::string Verifier::Carry() const {
  using detail::AppendBytes;
  std::string out;
  AppendBytes(out, window_.Active());
  if (window_.Active()) {
    AppendBytes(out, window_stitch_);
    AppendBytes(out, window_entry_line_);
    const process::WindowMetrics& m = window_.Metrics();
    for (const double v : m.side_force_mm) AppendBytes(out, v);
    AppendBytes(out, m.walk_demand_mm);
    detail::AppendMatrix(out, m.rotation_rad);
    AppendBytes(out, m.rotation_total_rad);
    detail::AppendPose(out, last_in_sample_.tool_part);
    AppendBytes(out, last_in_sample_.source_line);
    AppendBytes(out, last_in_sample_.time_s);
  }
  detail::AppendPose(out, line_from_);
  detail::AppendPose(out, line_to_);
  // The stitches a later sample may mark (those entered so far).
  if (keep_marks_) AppendBytes(out, marks_.size());
  bool whole_programme = false;
  for (const auto& r : rules_) {
    std::string bytes;
    r->SaveCarry(bytes);
    detail::AppendString(out, r->Summary().id);
    detail::AppendString(out, bytes);
    whole_programme = whole_programme || (!r->Mergeable() && r->SawAnything());
  }
  if (whole_programme) AppendBytes(out, instance_);
  return out;
}

void Verifier::Absorb(Verifier& later) {
  if (&later == this) throw std::logic_error("Verifier::Absorb: a verifier into itself");
  if (later.rules_.size() != rules_.size())
    throw std::logic_error("Verifier::Absorb: another rule set");
  for (std::size_t i = 0; i < rules_.size(); ++i) {
    const Rule &mine = *rules_[i], &theirs = *later.rules_[i];
    if (mine.Summary().id != theirs.Summary().id ||
        mine.Summary().subjects.size() != theirs.Summary().subjects.size())
      throw std::logic_error("Verifier::Absorb: another rule set (" + theirs.Summary().id +
                             " where " + mine.Summary().id + " is)");
    if (!mine.Mergeable() && mine.SawAnything() && theirs.SawAnything())
      throw std::logic_error(mine.Summary().id + " judges the programme as a whole: " +
                             "AFP programmes are verified in one part");
  }
  if (laydown_ && later.laydown_ && laydown_->SawAnything() && later.laydown_->SawAnything())
    throw std::logic_error(
        "the laydown figures judge an AFP programme whole: "
        "AFP programmes are verified in one part");
  if (window_.Active() && later.SawAnything())
    throw std::logic_error("Verifier::Absorb: this part ends with the needles in the preform");
  if (laydown_ && later.laydown_ && !laydown_->SawAnything()) laydown_.swap(later.laydown_);
  for (std::size_t i = 0; i < rules_.size(); ++i) {
    if (rules_[i]->Mergeable()) {
      rules_[i]->Absorb(*later.rules_[i]);
    } else if (!rules_[i]->SawAnything() && later.rules_[i]->SawAnything()) {
      rules_[i].swap(later.rules_[i]);  // only the later part saw it: take it over whole
    }
  }
  stitches_ += later.stitches_;
  const std::size_t had = marks_.size();
  if (later.marks_.size() > had) marks_.resize(later.marks_.size());
  for (std::size_t i = 0; i < later.marks_.size(); ++i) {
    if (i >= had) {
      marks_[i].position_mm = later.marks_[i].position_mm;
      marks_[i].line = later.marks_[i].line;
    }
    marks_[i].severity = std::max(marks_[i].severity, later.marks_[i].severity);
  }
  if (later.saw_input_) {  // the carry is the later part's
    window_ = later.window_;
    window_stitch_ = later.window_stitch_;
    window_entry_line_ = later.window_entry_line_;
    last_in_sample_ = later.last_in_sample_;
    line_from_ = later.line_from_;
    line_to_ = later.line_to_;
    commanded_ = later.commanded_;
  }
  saw_input_ = saw_input_ || later.saw_input_;
}

nlohmann::json Verifier::SavePartial() const {
  if (window_.Active()) {
    throw std::logic_error(
        "Verifier::SavePartial: the needles are in the preform (CloseNeedleWindow first)");
  }
  nlohmann::json rules = nlohmann::json::array();
  for (const auto& r : rules_) rules.push_back(r->SavePartial());
  return nlohmann::json{{"format", kPartialFormat},  {"version", kPartialVersion},
                        {"scene", ctx_.scene->name}, {"head", ctx_.scene->head.name},
                        {"stitches", stitches_},     {"saw_input", saw_input_},
                        {"rules", std::move(rules)}};
}

bool Verifier::LoadPartial(const nlohmann::json& j, std::string& error) {
  // The header and the rule list are checked before any rule changes.
  const auto check = [&]() -> std::string {
    if (j.is_discarded()) return "not valid JSON (cut short?)";
    if (!j.is_object() || !j.contains("format") || j.at("format") != kPartialFormat)
      return std::string("not a ") + kPartialFormat + " (format)";
    if (j.at("version") != kPartialVersion)
      return "version " + j.at("version").dump() + ", this build reads " +
             std::to_string(kPartialVersion);
    if (j.at("scene") != ctx_.scene->name || j.at("head") != ctx_.scene->head.name)
      return "scene " + j.at("scene").dump() + " with head " + j.at("head").dump() +
             ", this verifier's is '" + ctx_.scene->name + "' with '" + ctx_.scene->head.name + "'";
    const nlohmann::json& rules = j.at("rules");
    if (!rules.is_array() || rules.size() != rules_.size())
      return "it holds " + std::to_string(rules.size()) + " rules, this verifier runs " +
             std::to_string(rules_.size()) + " (other rules, or cut short)";
    for (std::size_t i = 0; i < rules_.size(); ++i) {
      const std::string id = rules[i].at("id").get<std::string>();
      if (id != rules_[i]->Summary().id)
        return "rule " + std::to_string(i + 1) + " is " + id + ", this verifier's " +
               rules_[i]->Summary().id + " (other rules)";
    }
    return "";
  };
  const auto load = [&]() -> std::string {
    const long stitches = j.at("stitches").get<long>();
    const bool saw_input = j.at("saw_input").get<bool>();
    for (std::size_t i = 0; i < rules_.size(); ++i) {
      std::string why;
      if (!rules_[i]->LoadPartial(j.at("rules")[i], why)) return why;
    }
    stitches_ = stitches;
    saw_input_ = saw_input;
    return "";
  };
  try {
    error = check();
    if (error.empty()) error = load();
  } catch (const std::exception& e) {
    error = std::string("malformed: ") + e.what();
  }
  if (error.empty()) return true;
  error = "verifier partial: " + error;
  ResetAccumulators();
  return false;
}

}  // namespace stitchsim::verify
