#include "stitchsim/program/identity.h"

#include <charconv>
#include <cmath>

#include "codes.h"

namespace stitchsim::program {
namespace {

template <typename T>
std::optional<T> Parse(std::string_view text) {
  T value{};
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

}  // namespace

std::optional<ProgramIdentity> ReadIdentity(const ProgramHeader& header,
                                            const std::string& file_name, DiagnosticSink& sink) {
  ProgramIdentity id;
  bool ok = true;
  auto bad = [&](std::string_view key, const std::string& why) {
    sink.Error(codes::kBadHeader, {file_name, header.LineOf(key), 1},
               "header " + std::string(key) + "=" + std::string(*header.Find(key)) + ": " + why);
    ok = false;
  };
  if (const auto v = header.Find("scene")) id.scene = std::string(*v);
  if (const auto v = header.Find("head")) id.head = std::string(*v);
  if (const auto v = header.Find("stitch_length_mm")) {
    const auto x = Parse<double>(*v);
    if (!x || !std::isfinite(*x) || *x <= 0) {
      bad("stitch_length_mm", "the stitch length must be a positive number of millimetres");
    } else {
      id.stitch_length_mm = *x;
    }
  }
  if (const auto v = header.Find("stitches")) {
    const auto n = Parse<long>(*v);
    if (!n || *n < 0) {
      bad("stitches", "the stitch count must be a whole number >= 0");
    } else {
      id.stitches = *n;
    }
  }
  if (!ok) return std::nullopt;
  return id;
}

}  // namespace stitchsim::program
