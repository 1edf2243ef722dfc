#include "yaml_alias_budget.h"

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/parser.h>

#include <sstream>
#include <vector>

namespace stitchsim::scene::detail {
namespace {

// Counts nodes as the parser reports them: a scalar or null is one node, a container one
// plus its children, an alias the count of the node it names.
class ExpandedNodeCounter : public YAML::EventHandler {
 public:
  explicit ExpandedNodeCounter(std::uint64_t max_nodes) : max_nodes_(max_nodes) {}

  const std::optional<AliasProblem>& Problem() const { return problem_; }

  void OnDocumentStart(const YAML::Mark&) override {}
  void OnDocumentEnd() override {}
  void OnAnchor(const YAML::Mark&, const std::string& name) override { pending_name_ = name; }
  void OnNull(const YAML::Mark&, YAML::anchor_t anchor) override { Leaf(anchor); }
  void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t anchor,
                const std::string&) override {
    Leaf(anchor);
  }
  void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t anchor,
                       YAML::EmitterStyle::value) override {
    Open(anchor);
  }
  void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t anchor,
                  YAML::EmitterStyle::value) override {
    Open(anchor);
  }
  void OnSequenceEnd() override { Close(); }
  void OnMapEnd() override { Close(); }

  void OnAlias(const YAML::Mark& mark, YAML::anchor_t anchor) override {
    if (problem_) return;
    const std::string name = anchor < names_.size() ? names_[anchor] : std::string();
    const std::uint64_t nodes = anchor < anchor_nodes_.size() ? anchor_nodes_[anchor] : 0;
    if (nodes == 0) {
      problem_ = AliasProblem{
          mark, "alias '*" + name + "' refers to a node that contains it (an endless tree)"};
      return;
    }
    if (total_ + nodes > max_nodes_) {
      problem_ = AliasProblem{
          mark, "alias '*" + name + "' stands for " + std::to_string(nodes) +
                    " nodes and takes the document past " + std::to_string(max_nodes_) +
                    " nodes with its aliases expanded, the limit (docs/limits.md)"};
      return;
    }
    Add(nodes);
  }

 private:
  struct OpenNode {
    YAML::anchor_t anchor = YAML::NullAnchor;
    std::uint64_t nodes = 1;
  };

  void Add(std::uint64_t nodes) {
    total_ += nodes;
    if (!open_.empty()) open_.back().nodes += nodes;
  }
  // Anchor ids count up from 1 in the order the anchors appear; 0 marks one still open.
  void Name(YAML::anchor_t anchor) {
    if (anchor == YAML::NullAnchor) return;
    if (anchor >= anchor_nodes_.size()) {
      anchor_nodes_.resize(anchor + 1, 0);
      names_.resize(anchor + 1);
    }
    anchor_nodes_[anchor] = 0;
    names_[anchor] = pending_name_;
  }
  void Leaf(YAML::anchor_t anchor) {
    Name(anchor);
    if (anchor != YAML::NullAnchor) anchor_nodes_[anchor] = 1;
    Add(1);
  }
  void Open(YAML::anchor_t anchor) {
    Name(anchor);
    ++total_;  // its parent counts it when it closes
    open_.push_back({anchor, 1});
  }
  void Close() {
    const OpenNode done = open_.back();
    open_.pop_back();
    if (done.anchor != YAML::NullAnchor) anchor_nodes_[done.anchor] = done.nodes;
    if (!open_.empty()) open_.back().nodes += done.nodes;  // already in total_
  }

  std::uint64_t max_nodes_;
  std::uint64_t total_ = 0;
  std::vector<OpenNode> open_;
  std::vector<std::uint64_t> anchor_nodes_;  // by anchor id: expanded size, 0 while open
  std::vector<std::string> names_;           // by anchor id
  std::string pending_name_;
  std::optional<AliasProblem> problem_;
};

}  // namespace

std::optional<AliasProblem> FindAliasProblem(const std::string& text, std::uint64_t max_nodes) {
  std::istringstream in(text);
  YAML::Parser parser(in);
  ExpandedNodeCounter counter(max_nodes);
  parser.HandleNextDocument(counter);
  return counter.Problem();
}

}  // namespace stitchsim::scene::detail
