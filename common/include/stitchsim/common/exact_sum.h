#pragma once
// A sum of doubles that does not depend on the order of its terms: each term is taken on a
// fixed grid of 2^-64 (a 128-bit integer count of it), so the parts of a programme summed on
// different threads or machines add up to exactly the serial sum. Terms are >= 0 and < 2^62;
// a term's bits below 2^-64 are dropped (the same way in every order).

#include <cmath>
#include <cstdint>
#include <string>

namespace stitchsim {

class ExactSum {
 public:
  void Add(double x) { units_ += static_cast<Units>(std::ldexp(x, 64)); }
  void Add(const ExactSum& other) { units_ += other.units_; }
  double Value() const { return std::ldexp(static_cast<double>(units_), -64); }
  /// 32 hex digits (two's complement), for partial result files; FromHex reads it back.
  std::string Hex() const {
    static constexpr char kDigits[] = "0123456789abcdef";
    std::string out(32, '0');
    auto u = static_cast<UnsignedUnits>(units_);
    for (int i = 31; i >= 0; --i, u >>= 4) out[static_cast<std::size_t>(i)] = kDigits[u & 0xF];
    return out;
  }
  static bool FromHex(const std::string& text, ExactSum& out) {
    if (text.size() != 32) return false;
    UnsignedUnits u = 0;
    for (char c : text) {
      int d = c >= '0' && c <= '9' ? c - '0' : (c >= 'a' && c <= 'f' ? c - 'a' + 10 : -1);
      if (d < 0) return false;
      u = (u << 4) | static_cast<UnsignedUnits>(d);
    }
    out.units_ = static_cast<Units>(u);
    return true;
  }
  bool operator==(const ExactSum&) const = default;

 private:
  __extension__ typedef __int128 Units;
  __extension__ typedef unsigned __int128 UnsignedUnits;
  Units units_ = 0;
};

}  // namespace stitchsim
