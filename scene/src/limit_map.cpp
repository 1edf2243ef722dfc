#include "limit_map.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <vector>

#include "stitchsim/common/edit_distance.h"
#include "stitchsim/common/units.h"

namespace stitchsim::scene::detail {
namespace {

std::string_view TrimView(std::string_view s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string_view::npos) return {};
  return s.substr(b, s.find_last_not_of(" \t") - b + 1);
}

// The candidate nearest to `name` (the first of equals).
std::string_view Nearest(std::string_view name, const std::vector<std::string_view>& candidates) {
  std::string_view best;
  std::size_t best_distance = static_cast<std::size_t>(-1);
  for (std::string_view c : candidates) {
    const std::size_t d = EditDistance(name, c);
    if (d < best_distance) {
      best = c;
      best_distance = d;
    }
  }
  return best;
}

std::vector<std::string_view> RuleIds() {
  std::vector<std::string_view> ids;
  for (const LimitSpec& s : LimitTable()) {
    if (std::find(ids.begin(), ids.end(), s.rule) == ids.end()) ids.push_back(s.rule);
  }
  return ids;
}

std::vector<std::string_view> KeysOf(std::string_view rule) {
  std::vector<std::string_view> keys;
  for (const LimitSpec& s : LimitTable()) {
    if (s.rule == rule) keys.push_back(s.name);
  }
  return keys;
}

// Value of one `unit` in the key's unit, when `unit` measures what the key does.
std::optional<double> UnitFactor(LimitUnit key_unit, std::string_view unit) {
  switch (key_unit) {
    case LimitUnit::kMm:
      if (auto u = ParseLengthUnit(unit)) return MmPer(*u);
      return std::nullopt;
    case LimitUnit::kDeg:
      if (unit == "deg") return 1.0;
      if (unit == "rad") return RadToDeg(1.0);
      return std::nullopt;
    case LimitUnit::kPct:
      if (unit == "%") return 1.0;
      return std::nullopt;
    case LimitUnit::kNPerMm:
      if (unit == "N/mm") return 1.0;
      return std::nullopt;
    case LimitUnit::kFraction:
      if (unit == "%") return 0.01;
      return std::nullopt;
  }
  return std::nullopt;
}

std::string_view UnitsAccepted(LimitUnit unit) {
  switch (unit) {
    case LimitUnit::kMm:
      return "a length: a number in mm, or '<n> mm|in|m'";
    case LimitUnit::kDeg:
      return "an angle: a number in deg, or '<n> deg|rad'";
    case LimitUnit::kPct:
      return "a percentage: a number, or '<n> %'";
    case LimitUnit::kNPerMm:
      return "a stiffness: a number in N/mm, or '<n> N/mm'";
    case LimitUnit::kFraction:
      return "a fraction: a number (1 = 100 %), or '<n> %'";
  }
  return "";
}

// The value of limit `spec` at `node` in the key's unit: a bare number, or a number and a
// unit of the same kind (converted). Problems reported; nullopt then.
std::optional<double> LimitValue(YamlReader& r, const YAML::Node& node, const LimitSpec& spec) {
  const std::string what = std::string(spec.rule) + "." + std::string(spec.name);
  if (!node.IsScalar()) {
    r.Error(node, "type", what + " must be " + std::string(UnitsAccepted(spec.unit)));
    return std::nullopt;
  }
  const std::string_view text = TrimView(node.Scalar());
  std::size_t end = text.size();
  while (end > 0 && (std::isalpha(static_cast<unsigned char>(text[end - 1])) ||
                     text[end - 1] == '%' || text[end - 1] == '/')) {
    --end;
  }
  const std::string_view number = TrimView(text.substr(0, end));
  const std::string_view unit = text.substr(end);
  // Bare numbers (and words such as "nan", "-inf") are read exactly as any other number.
  std::string lower(unit);
  for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (unit.empty() || number.empty() || lower.find("nan") != std::string::npos ||
      lower.find("inf") != std::string::npos) {
    return r.Number(node, what);
  }
  std::optional<double> v = r.NumberText(node, number, what);
  if (!v) return std::nullopt;
  const std::optional<double> factor = UnitFactor(spec.unit, unit);
  if (!factor) {
    r.Error(node, "limit-unit",
            what + " is in " + std::string(LimitUnitName(spec.unit)) + ": '" + node.Scalar() +
                "' has the unit '" + std::string(unit) + "'; write " +
                std::string(UnitsAccepted(spec.unit)));
    return std::nullopt;
  }
  *v *= *factor;
  if (!std::isfinite(*v)) {
    r.Error(node, "not-finite", what + " must be finite, got '" + node.Scalar() + "'");
    return std::nullopt;
  }
  return v;
}

// The row for `rule`.`name` at `key_node`, or reported (unknown limit) and nullptr.
const LimitSpec* KnownLimit(YamlReader& r, const YAML::Node& key_node, const std::string& rule,
                            const std::string& name) {
  if (const LimitSpec* spec = FindLimit(rule, name)) return spec;
  const std::vector<std::string_view> keys = KeysOf(rule);
  std::string list;
  for (std::string_view k : keys) list += (list.empty() ? "" : ", ") + std::string(k);
  r.Error(key_node, "unknown-limit",
          "unknown limit '" + name + "' of rule " + rule + " (did you mean '" +
              std::string(Nearest(name, keys)) + "'? " + rule + " takes: " + list + ")");
  return nullptr;
}

}  // namespace

void ReadLimitMap(YamlReader& r, const YAML::Node& limits, RuleLimits& out) {
  if (!r.ExpectMap(limits, "limits")) return;
  for (const auto& rule : limits) {
    const std::string id = rule.first.Scalar();
    if (!IsLimitRule(id)) {
      r.Error(rule.first, "unknown-rule",
              "unknown rule '" + id + "' in limits (did you mean '" +
                  std::string(Nearest(id, RuleIds())) +
                  "'? docs/report-format.md lists every rule's limits)");
      continue;
    }
    if (!r.ExpectMap(rule.second, "limits of " + id)) continue;
    for (const auto& kv : rule.second) {
      const LimitSpec* spec = KnownLimit(r, kv.first, id, kv.first.Scalar());
      if (spec == nullptr) continue;
      const std::optional<double> v = LimitValue(r, kv.second, *spec);
      if (!v) continue;
      if (!spec->may_be_negative && !r.Positive(kv.second, *v, id + "." + kv.first.Scalar(),
                                                /*allow_zero=*/true)) {
        continue;
      }
      out.Set(spec->key, *v);
    }
  }
}

}  // namespace stitchsim::scene::detail
