#pragma once
// Typed, validated reads from yaml-cpp nodes that report file:line:col diagnostics with a
// caller's code prefix instead of throwing: unknown and duplicate keys, numbers, lengths with
// units, referenced files. The scene, head-spec and limits loaders and the raster planner's
// code library read their YAML through it.

#include <yaml-cpp/yaml.h>

#include <Eigen/Core>
#include <filesystem>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "stitchsim/common/diagnostics.h"
#include "stitchsim/common/units.h"

namespace stitchsim::scene::detail {

/// Where files named inside a YAML file may lie: in one of `roots` (symlinks resolved),
/// anywhere when `allow_outside`.
struct FileRefPolicy {
  std::vector<std::filesystem::path> roots;
  bool allow_outside = false;
};

class YamlReader {
 public:
  YamlReader(std::filesystem::path file, DiagnosticSink& sink, std::string prefix)
      : file_(std::move(file)), sink_(sink), prefix_(std::move(prefix)) {}

  /// Parses the whole file (a regular file within limits::kMaxYamlFileBytes); reports a
  /// missing or unreadable file, syntax errors and keys given twice in one mapping.
  std::optional<YAML::Node> LoadFile();
  /// As LoadFile, from `text` already read (diagnostics still name File()).
  std::optional<YAML::Node> LoadText(const std::string& text);

  /// The file `name` given at `node` (relative to this file's folder), when it exists, is a
  /// regular file and lies where `policy` allows; else reported ("-path-outside",
  /// "-missing-file", "-not-a-file") and nullopt.
  std::optional<std::filesystem::path> ReferencedFile(const YAML::Node& node,
                                                      const std::string& name,
                                                      const FileRefPolicy& policy,
                                                      std::string_view what);

  SourceLocation At(const YAML::Node& node) const;
  void Error(const YAML::Node& node, std::string_view code, std::string message);

  /// Reports every key of `map` not in `allowed` ("<prefix>-unknown-key").
  bool CheckKeys(const YAML::Node& map, std::initializer_list<std::string_view> allowed,
                 std::string_view context);
  bool ExpectMap(const YAML::Node& node, std::string_view what);
  /// Child `key` of `map`; reports "<prefix>-missing-key" when required and absent.
  std::optional<YAML::Node> Child(const YAML::Node& map, std::string_view key, bool required);

  std::optional<double> Number(const YAML::Node& node, std::string_view what);
  /// `text` (part of the scalar `node`) as a strict finite number; problems reported at
  /// `node` as Number reports them.
  std::optional<double> NumberText(const YAML::Node& node, std::string_view text,
                                   std::string_view what);
  /// A whole number in [min, max]; "<prefix>-bad-number" or "<prefix>-out-of-range" else.
  std::optional<long> Integer(const YAML::Node& node, std::string_view what, long min, long max);
  std::optional<std::string> String(const YAML::Node& node, std::string_view what);
  std::optional<bool> Bool(const YAML::Node& node, std::string_view what);
  /// A length: a number in `unit`, or a string "<number> mm|in|m". Result in millimetres.
  std::optional<double> Length(const YAML::Node& node, LengthUnit unit, std::string_view what);
  /// A sequence of exactly `n` numbers (or lengths when `unit` is given; result in mm).
  std::optional<Eigen::VectorXd> Vector(const YAML::Node& node, int n, std::string_view what,
                                        std::optional<LengthUnit> unit = std::nullopt);

  /// Checks value > 0 (or >= 0 when allow_zero); reports "<prefix>-out-of-range".
  bool Positive(const YAML::Node& node, double value, std::string_view what,
                bool allow_zero = false);

  const std::filesystem::path& File() const { return file_; }
  DiagnosticSink& Sink() { return sink_; }
  const std::string& Prefix() const { return prefix_; }

 private:
  bool CheckDuplicateKeys(const YAML::Node& root);

  std::filesystem::path file_;
  DiagnosticSink& sink_;
  std::string prefix_;
};

}  // namespace stitchsim::scene::detail

namespace stitchsim::scene {
using detail::FileRefPolicy;
using detail::YamlReader;
}  // namespace stitchsim::scene
