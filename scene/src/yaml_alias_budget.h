#pragma once
// Anchors and aliases let a small YAML file stand for a huge tree (ten levels of ten aliases:
// ten billion nodes), and anything that walks the loaded tree walks every copy. The text is
// first read as parser events, no nodes built, and the tree's size counted with every alias
// expanded, so a file past the limit is refused at the alias before anything walks it.

#include <yaml-cpp/mark.h>

#include <cstdint>
#include <optional>
#include <string>

namespace stitchsim::scene::detail {

/// An alias that makes the document too large, or that names a node it lies inside.
struct AliasProblem {
  YAML::Mark mark;  ///< the alias (`*name`)
  std::string message;
};

/// The first alias of `text`'s first document that takes its node count, with aliases
/// expanded, past `max_nodes`, or that refers to a node enclosing it; nullopt when none.
/// Throws YAML::Exception on a syntax error, as YAML::Load does.
std::optional<AliasProblem> FindAliasProblem(const std::string& text, std::uint64_t max_nodes);

}  // namespace stitchsim::scene::detail
