#include "stitchsim/planner/code_library.h"

#include <climits>

#include "stitchsim/program/block.h"
#include "stitchsim/scene/yaml_reader.h"

namespace stitchsim::planner {
namespace {

// When a block fires, from its `at:` value into `event`; false (reported) if unknown.
bool ReadEvent(scene::YamlReader& r, const YAML::Node& at, UserCodeBlock::Event& event) {
  const std::optional<std::string> text = r.String(at, "'at'");
  if (!text) return false;
  if (*text == "every_stitches") {
    event = UserCodeBlock::Event::kEveryStitches;
  } else if (*text == "row_start") {
    event = UserCodeBlock::Event::kRowStart;
  } else if (*text == "before_jump") {
    event = UserCodeBlock::Event::kBeforeJump;
  } else {
    r.Error(at, "bad-event",
            "'at' must be every_stitches, row_start or before_jump, got '" + *text + "'");
    return false;
  }
  return true;
}

// The M codes of a block: 1 to 4, each in the dialect's user range.
void ReadMCodes(scene::YamlReader& r, const YAML::Node& m, const program::Dialect& dialect,
                UserCodeBlock& block) {
  if (!m.IsSequence() || m.size() == 0 || m.size() > program::kMaxMCodesPerBlock) {
    r.Error(m, "bad-m",
            block.name + ": 'm' must list 1 to " + std::to_string(program::kMaxMCodesPerBlock) +
                " M codes");
    return;
  }
  for (const YAML::Node& code : m) {
    const std::optional<long> v = r.Integer(code, "an M code", 0, INT_MAX);
    if (!v) continue;
    if (*v < dialect.m.user_macro_first || *v > dialect.m.user_macro_last) {
      r.Error(code, "m-not-user",
              block.name + ": M" + std::to_string(*v) + " is outside the user range M" +
                  std::to_string(dialect.m.user_macro_first) + "-M" +
                  std::to_string(dialect.m.user_macro_last));
      continue;
    }
    block.m_codes.push_back(static_cast<int>(*v));
  }
}

std::optional<UserCodeBlock> ReadBlock(scene::YamlReader& r, const YAML::Node& node,
                                       const program::Dialect& dialect) {
  if (!r.ExpectMap(node, "a code block")) return std::nullopt;
  r.CheckKeys(node, {"name", "at", "every", "m", "p"}, "a code block");
  UserCodeBlock block;
  block.name = "unnamed";
  if (const auto name = r.Child(node, "name", false)) {
    if (const auto text = r.String(*name, "'name'")) block.name = *text;
  }
  const auto at = r.Child(node, "at", true);
  const bool known_event = at && ReadEvent(r, *at, block.event);
  const bool counted = known_event && block.event == UserCodeBlock::Event::kEveryStitches;
  const auto every = r.Child(node, "every", counted);
  if (every && known_event && !counted) {
    r.Error(*every, "bad-every", block.name + ": 'every' belongs to at: every_stitches only");
  } else if (every) {
    block.every_stitches = r.Integer(*every, "'every' (stitches)", 1, LONG_MAX / 2).value_or(0);
  }
  if (const auto m = r.Child(node, "m", true)) ReadMCodes(r, *m, dialect, block);
  if (const auto p = r.Child(node, "p", false)) {
    if (const auto v = r.Integer(*p, "'p'", INT_MIN, INT_MAX)) block.param = static_cast<int>(*v);
  }
  return block;
}

std::optional<UserCodeLibrary> ReadLibrary(scene::YamlReader& r, const YAML::Node& root,
                                           const program::Dialect& dialect) {
  const std::size_t errors_before = r.Sink().ErrorCount();
  if (!r.ExpectMap(root, "the code library")) return std::nullopt;
  r.CheckKeys(root, {"blocks"}, "the code library");
  const auto blocks = r.Child(root, "blocks", true);
  if (!blocks) return std::nullopt;
  if (!blocks->IsSequence()) {
    r.Error(*blocks, "type", "'blocks' must be a list of code blocks");
    return std::nullopt;
  }
  UserCodeLibrary lib;
  for (const YAML::Node& node : *blocks) {
    if (auto block = ReadBlock(r, node, dialect)) lib.blocks.push_back(std::move(*block));
  }
  if (r.Sink().ErrorCount() > errors_before) return std::nullopt;
  return lib;
}

}  // namespace

std::optional<UserCodeLibrary> ParseUserCodeLibrary(std::string_view yaml,
                                                    const std::string& file_name,
                                                    const program::Dialect& dialect,
                                                    DiagnosticSink& sink) {
  scene::YamlReader r(file_name, sink, "library");
  const std::optional<YAML::Node> root = r.LoadText(std::string(yaml));
  if (!root) return std::nullopt;
  return ReadLibrary(r, *root, dialect);
}

std::optional<UserCodeLibrary> LoadUserCodeLibrary(const std::filesystem::path& file,
                                                   const program::Dialect& dialect,
                                                   DiagnosticSink& sink) {
  scene::YamlReader r(file, sink, "library");
  const std::optional<YAML::Node> root = r.LoadFile();
  if (!root) return std::nullopt;
  return ReadLibrary(r, *root, dialect);
}

}  // namespace stitchsim::planner
