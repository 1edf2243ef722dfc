#include "stitchsim/program/modal_state.h"

#include <istream>
#include <utility>

#include "codes.h"

namespace stitchsim::program {

ModalState::ModalState(const Dialect& dialect, std::string file_name, DiagnosticSink& sink)
    : dialect_(dialect), file_name_(std::move(file_name)), sink_(sink) {
  state_.units = dialect.default_units;
  previous_ = state_;
}

void ModalState::Error(const char* code, const Block& block, int column, std::string message) {
  sink_.Error(code, {file_name_, block.source_line, column}, std::move(message));
}

void ModalState::ApplyTow(const Block& block, std::size_t k) {
  if (!block.param) return;  // the reader has reported it
  const bool add = dialect_.MeaningOfM(block.m_codes[k]) == MMeaning::kTowAdd;
  const std::uint64_t bits =
      *block.param == 0 ? ~std::uint64_t{0} : std::uint64_t{1} << (*block.param - 1);
  state_.tows = add ? (state_.tows | bits) : (state_.tows & ~bits);
  step_.tows_changed = true;
}

// Applies the block's M codes in written order; true if one ends the programme.
bool ModalState::ApplyMCodes(const Block& block) {
  bool ends = false;
  for (std::size_t k = 0; k < block.m_codes.size(); ++k) {
    const int column = k < kMaxMCodesPerBlock ? block.columns.m_codes[k] : 0;
    switch (dialect_.MeaningOfM(block.m_codes[k])) {
      case MMeaning::kToolChange:
        if (!state_.selected_tool) {
          Error(codes::kMissingTool, block, column,
                "M" + std::to_string(dialect_.m.tool_change) + " before any " +
                    dialect_.tool_letter + " word selected a head");
        } else {
          state_.active_tool = state_.selected_tool;
          step_.tool_changed = true;
        }
        break;
      case MMeaning::kStitchOn:
        state_.stitching = true;
        break;
      case MMeaning::kStitchOff:
        state_.stitching = false;
        break;
      case MMeaning::kHeadRetract:
        state_.head_retracted = true;
        break;
      case MMeaning::kHeadLower:
        state_.head_retracted = false;
        break;
      case MMeaning::kHeadSection:
        if (block.param) {
          state_.head_section = block.param;
          step_.head_section = block.param;
        }
        break;
      case MMeaning::kTowAdd:
      case MMeaning::kTowCut:
        ApplyTow(block, k);
        break;
      case MMeaning::kPlyStart:
        if (state_.course != 0) {
          Error(codes::kAfpStructure, block, column,
                "M" + std::to_string(dialect_.m.ply_start) + " inside course " +
                    std::to_string(state_.course) + " (end it with M" +
                    std::to_string(dialect_.m.course_end) + " first)");
        } else if (block.param) {
          state_.ply = *block.param;
        }
        break;
      case MMeaning::kCourseStart:
        if (state_.course != 0) {
          Error(codes::kAfpStructure, block, column,
                "M" + std::to_string(dialect_.m.course_start) + " while course " +
                    std::to_string(state_.course) + " is still open");
        } else if (block.param) {
          state_.course = *block.param;
        }
        break;
      case MMeaning::kCourseEnd:
        if (state_.course == 0) {
          Error(codes::kAfpStructure, block, column,
                "M" + std::to_string(dialect_.m.course_end) + " outside a course");
        }
        state_.course = 0;
        break;
      case MMeaning::kUserMacro:
        step_.user_macros.push_back(block.m_codes[k]);
        break;
      case MMeaning::kProgramEnd:
        ends = true;
        break;
      case MMeaning::kUnknown:
        break;  // the reader has reported it
    }
  }
  return ends;
}

const Step& ModalState::Update(const Block& block) {
  step_.source_line = block.source_line;
  step_.is_move = false;
  step_.motion = Motion::kNone;
  step_.tool_changed = false;
  step_.program_end = false;
  step_.head_section.reset();
  step_.user_macros.clear();
  step_.tows_changed = false;
  previous_ = state_;
  if (!block.HasWords()) return step_;
  if (state_.program_ended) {
    Error(codes::kCodeAfterProgramEnd, block, block.columns.first_word,
          "words after M" + std::to_string(dialect_.m.program_end) + " (end of programme)");
    return step_;
  }

  if (block.units) state_.units = *block.units;
  const double mm_per_unit = MmPer(state_.units);
  if (block.feed) state_.feed_mm_per_min = *block.feed * mm_per_unit;
  if (block.motion != Motion::kNone) state_.motion = block.motion;
  if (block.tool) state_.selected_tool = block.tool;

  const bool ends = ApplyMCodes(block);

  if (block.HasAxisWords()) {
    int first_axis_column = 0;
    for (std::size_t a = 0; a < kAxisCount; ++a) {
      if (!block.axes[a]) continue;
      if (first_axis_column == 0) first_axis_column = block.columns.axes[a];
      const double scale = IsAngular(static_cast<Axis>(a)) ? 1.0 : mm_per_unit;
      state_.axes[a] = *block.axes[a] * scale;
    }
    if (state_.motion == Motion::kNone) {
      Error(codes::kNoMotionMode, block, first_axis_column,
            "axis words before any G" + std::to_string(dialect_.g.rapid) + "/G" +
                std::to_string(dialect_.g.feed) + " motion code");
    } else {
      step_.is_move = true;
      step_.motion = state_.motion;
      if (state_.motion == Motion::kFeed && !state_.feed_mm_per_min) {
        Error(codes::kMissingFeed, block, first_axis_column,
              "feed move (G" + std::to_string(dialect_.g.feed) + ") before any " +
                  dialect_.feed_letter + " word set the feed");
      }
    }
  }

  if (ends) {
    state_.program_ended = true;
    step_.program_end = true;
  }
  return step_;
}

std::optional<std::array<double, 3>> ModalState::AnglesRad() const {
  const auto& a = state_[Axis::kA];
  const auto& b = state_[Axis::kB];
  const auto& c = state_[Axis::kC];
  if (!a || !b || !c) return std::nullopt;
  return std::array<double, 3>{DegToRad(*a), DegToRad(*b), DegToRad(*c)};
}

CheckSummary CheckProgram(std::istream& in, const Dialect& dialect, std::string file_name,
                          DiagnosticSink& sink) {
  const std::size_t errors_before = sink.ErrorCount();
  CheckSummary summary;
  ProgramReader reader(in, dialect, file_name, sink);
  ModalState modal(dialect, std::move(file_name), sink);
  Block block;
  while (reader.Next(block)) {
    ++summary.blocks;
    if (modal.Update(block).is_move) ++summary.moves;
  }
  summary.lines = reader.LineCount();
  summary.header = reader.Header();
  summary.ok = sink.ErrorCount() == errors_before;
  return summary;
}

}  // namespace stitchsim::program
