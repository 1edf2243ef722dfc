#include "stitchsim/verify/value_series.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

namespace stitchsim::verify {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// NaN-aware min/max: NaN is "empty".
float Lower(float a, float b) { return std::isnan(a) ? b : (std::isnan(b) ? a : std::min(a, b)); }
float Upper(float a, float b) { return std::isnan(a) ? b : (std::isnan(b) ? a : std::max(a, b)); }

}  // namespace

void ValueSeries::Cover(long bucket) {
  if (min_.empty()) {
    first_ = bucket;
    min_.assign(1, kNaN);
    max_.assign(1, kNaN);
    return;
  }
  if (bucket < first_) {
    const auto grow = static_cast<std::size_t>(first_ - bucket);
    min_.insert(min_.begin(), grow, kNaN);
    max_.insert(max_.begin(), grow, kNaN);
    first_ = bucket;
  } else if (bucket >= first_ + static_cast<long>(min_.size())) {
    min_.resize(static_cast<std::size_t>(bucket - first_ + 1), kNaN);
    max_.resize(min_.size(), kNaN);
  }
}

void ValueSeries::Coarsen() {
  const long first = first_ >> 1;
  const long last = (first_ + static_cast<long>(min_.size()) - 1) >> 1;
  std::vector<float> lo(static_cast<std::size_t>(last - first + 1), kNaN), hi(lo);
  for (std::size_t i = 0; i < min_.size(); ++i) {
    const auto k = static_cast<std::size_t>(((first_ + static_cast<long>(i)) >> 1) - first);
    lo[k] = Lower(lo[k], min_[i]);
    hi[k] = Upper(hi[k], max_[i]);
  }
  min_ = std::move(lo);
  max_ = std::move(hi);
  first_ = first;
  ++shift_;
}

void ValueSeries::Add(int line, double value) {
  if (std::isnan(value)) return;
  const long bucket = static_cast<long>(std::max(line, 0)) >> shift_;
  const long size = static_cast<long>(min_.size());
  if (min_.empty() || bucket < first_ || bucket >= first_ + size) {
    Cover(bucket);
    while (static_cast<long>(min_.size()) > kMaxBuckets) Coarsen();
  }
  const auto k =
      static_cast<std::size_t>((static_cast<long>(std::max(line, 0)) >> shift_) - first_);
  const auto v = static_cast<float>(value);
  min_[k] = Lower(min_[k], v);
  max_[k] = Upper(max_[k], v);
}

void ValueSeries::Absorb(const ValueSeries& other) {
  if (other.min_.empty()) return;
  ValueSeries o = other;
  while (o.shift_ < shift_) o.Coarsen();
  if (min_.empty()) {
    *this = std::move(o);
    return;
  }
  while (shift_ < o.shift_) Coarsen();
  Cover(o.first_);
  Cover(o.first_ + static_cast<long>(o.min_.size()) - 1);
  for (std::size_t i = 0; i < o.min_.size(); ++i) {
    const auto k = static_cast<std::size_t>(o.first_ + static_cast<long>(i) - first_);
    min_[k] = Lower(min_[k], o.min_[i]);
    max_[k] = Upper(max_[k], o.max_[i]);
  }
  while (static_cast<long>(min_.size()) > kMaxBuckets) Coarsen();
}

nlohmann::json ValueSeries::ToJson() const {
  nlohmann::json lo = nlohmann::json::array(), hi = nlohmann::json::array();
  for (std::size_t i = 0; i < min_.size(); ++i) {
    lo.push_back(std::isnan(min_[i]) ? nlohmann::json(nullptr) : nlohmann::json(min_[i]));
    hi.push_back(std::isnan(max_[i]) ? nlohmann::json(nullptr) : nlohmann::json(max_[i]));
  }
  return {{"shift", shift_}, {"first", first_}, {"min", std::move(lo)}, {"max", std::move(hi)}};
}

bool ValueSeries::FromJson(const nlohmann::json& j) {
  ValueSeries s;
  try {
    s.shift_ = j.at("shift").get<int>();
    s.first_ = j.at("first").get<long>();
    const auto& lo = j.at("min");
    const auto& hi = j.at("max");
    if (s.shift_ < 0 || s.shift_ > 40 || s.first_ < 0 || !lo.is_array() || !hi.is_array() ||
        lo.size() != hi.size() || static_cast<long>(lo.size()) > kMaxBuckets)
      return false;
    for (std::size_t i = 0; i < lo.size(); ++i) {
      s.min_.push_back(lo[i].is_null() ? kNaN : lo[i].get<float>());
      s.max_.push_back(hi[i].is_null() ? kNaN : hi[i].get<float>());
    }
  } catch (const std::exception&) {
    return false;
  }
  *this = std::move(s);
  return true;
}

}  // namespace stitchsim::verify
