#pragma once
// Command-line conventions shared by every subcommand: length options with unit suffixes, and
// the top-level dispatch (bare `stitchsim`, unknown subcommands with a suggestion).

#include <CLI/CLI.hpp>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "stitchsim/common/units.h"

namespace stitchsim::app {

/// What a length option accepts beyond being finite.
enum class LengthRange { kAny, kPositive, kNonNegative };

/// Adds `name` as a length: a number with an optional unit suffix (`2.5mm`, `0.1in`, `1m`); a
/// bare number is in `default_unit`, named in the help with `default_text` (the default
/// value, or what happens when the option is not given). `store` receives millimetres.
CLI::Option* AddLengthOption(CLI::App* app, const std::string& name,
                             std::function<void(double)> store, LengthUnit default_unit,
                             LengthRange range, const std::string& description,
                             const std::string& default_text);

/// As AddLengthOption for `count` comma-separated lengths (each with its own suffix, if any).
CLI::Option* AddLengthListOption(CLI::App* app, const std::string& name, std::size_t count,
                                 std::vector<double>& store_mm, LengthUnit default_unit,
                                 const std::string& description);

/// The closest of `candidates` to `word` by edit distance, if it is close enough to be a
/// plausible typo (at most 2 edits, or a prefix); nullopt otherwise.
std::optional<std::string> NearestName(const std::string& word,
                                       const std::vector<std::string>& candidates);

/// Before CLI11 parses: a bare command (no subcommand at a level that needs one) prints that
/// level's help and gives 0; an unknown subcommand name is reported with the nearest one and
/// gives 2. nullopt: parse normally.
std::optional<int> PreDispatch(const CLI::App& app, const std::vector<std::string>& args);

}  // namespace stitchsim::app
