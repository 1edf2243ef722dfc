#pragma once
// A rule's values along the programme, for plots (the HTML report): per bucket of programme
// lines the smallest and the largest value checked there. Buckets are aligned to multiples of
// their width (a power of two lines); when the lines seen would need more than kMaxBuckets,
// the width doubles and neighbouring buckets merge. So the size is bounded, and the series of a
// programme verified in parts and merged (Absorb) equals the serial one, bucket for bucket.

#include <cstdint>
#include <nlohmann/json_fwd.hpp>
#include <vector>

namespace stitchsim::verify {

class ValueSeries {
 public:
  static constexpr long kMaxBuckets = 2048;

  /// Adds one checked value at a programme line (>= 0). NaN is ignored.
  void Add(int line, double value);
  /// Folds another series (any order of parts; the result is the union's).
  void Absorb(const ValueSeries& other);
  void Clear() { *this = ValueSeries(); }

  bool Empty() const { return min_.empty(); }
  /// Lines per bucket (a power of two).
  long BucketLines() const { return 1L << shift_; }
  /// The first line of bucket 0.
  long FirstLine() const { return first_ << shift_; }
  /// Per bucket: smallest and largest value; NaN where nothing was checked.
  const std::vector<float>& Min() const { return min_; }
  const std::vector<float>& Max() const { return max_; }

  /// As JSON ({"shift","first","min","max"}, NaN as null) and back; false when malformed.
  nlohmann::json ToJson() const;
  bool FromJson(const nlohmann::json& j);

 private:
  void Coarsen();           // doubles the bucket width
  void Cover(long bucket);  // grows the buckets to include `bucket` (at this width)

  int shift_ = 0;   ///< bucket width = 2^shift lines
  long first_ = 0;  ///< bucket index (line >> shift) of min_[0]
  std::vector<float> min_, max_;
};

}  // namespace stitchsim::verify
