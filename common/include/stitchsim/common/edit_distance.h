#pragma once
// Edit distance between names, for "did you mean" suggestions in diagnostics.

#include <cstddef>
#include <string_view>

namespace stitchsim {

/// Levenshtein distance: the fewest single-character insertions, deletions and
/// substitutions that turn `a` into `b`.
std::size_t EditDistance(std::string_view a, std::string_view b);

}  // namespace stitchsim
