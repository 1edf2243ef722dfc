#include "stitchsim/program/block.h"

#include <algorithm>

namespace stitchsim::program {

bool Block::HasAxisWords() const {
  return std::any_of(axes.begin(), axes.end(), [](const auto& v) { return v.has_value(); });
}

bool Block::HasWords() const {
  return block_number || motion != Motion::kNone || units || absolute || feed || tool || param ||
         !m_codes.empty() || HasAxisWords();
}

void Block::Clear() {
  source_line = 0;
  block_number.reset();
  motion = Motion::kNone;
  units.reset();
  absolute = false;
  axes.fill(std::nullopt);
  feed.reset();
  tool.reset();
  param.reset();
  m_codes.clear();
  comment.clear();
  columns = WordColumns{};
}

bool operator==(const Block& a, const Block& b) {
  return a.block_number == b.block_number && a.motion == b.motion && a.units == b.units &&
         a.absolute == b.absolute && a.axes == b.axes && a.feed == b.feed && a.tool == b.tool &&
         a.param == b.param && a.m_codes == b.m_codes && a.comment == b.comment;
}

}  // namespace stitchsim::program
