// An AFP programme read back into plies, courses and lay-up stations (afp_program.h).
#include "stitchsim/program/afp_program.h"

#include <cmath>
#include <istream>
#include <iterator>
#include <set>
#include <sstream>

#include "stitchsim/program/modal_state.h"
#include "stitchsim/program/tool_pose.h"

namespace stitchsim::program {
namespace {

constexpr char kNoCourses[] = "sequence-no-courses";
constexpr char kEmptyCourse[] = "sequence-empty-course";
constexpr char kOpenTows[] = "sequence-open-tows";
constexpr char kMarksOrder[] = "sequence-marks-order";
constexpr char kIncompletePose[] = "sequence-incomplete-pose";

bool HasMeaning(const Dialect& d, const Block& b, MMeaning m) {
  for (const int code : b.m_codes)
    if (d.MeaningOfM(code) == m) return true;
  return false;
}

// The open course while it is read.
struct OpenCourse {
  AfpCourse course;
  bool in_layup = false;         // a tow has been added
  bool laid = false;             // a tow laid on a feed move with the head lowered
  int end_line = 0;              // the block where the mask last returned to 0
  std::size_t end_stations = 0;  // stations up to and including that block
};

class Reader {
 public:
  Reader(const Dialect& dialect, std::string file, DiagnosticSink& sink)
      : dialect_(dialect), order_(EulerOrderOf(dialect)), file_(std::move(file)), sink_(sink) {}

  void Block(const program::Block& b, const ModalState& modal, AfpProgram& out);
  bool Finish(AfpProgram& out, int last_line, bool errors);

 private:
  void Error(const char* code, int line, std::string message) {
    sink_.Error(code, SourceLocation{file_, line, 1}, std::move(message));
  }
  void StartPly(const program::Block& b, const MachineState& s, AfpProgram& out);
  void StartCourse(const program::Block& b, const MachineState& s);
  void EndCourse(const program::Block& b, const MachineState& s, AfpProgram& out);
  void Layup(const program::Block& b, const ModalState& modal);
  static void SetLeaving(LayupStation& st, const MachineState& s) {
    st.tows = s.tows;
    st.head_retracted = s.head_retracted;
    st.motion = s.motion == Motion::kNone ? Motion::kFeed : s.motion;
    st.feed_mm_per_min = s.feed_mm_per_min.value_or(0.0);
  }

  const Dialect& dialect_;
  geom::EulerOrder order_;
  std::string file_;
  DiagnosticSink& sink_;
  std::optional<OpenCourse> open_;
  std::set<std::pair<int, int>> seen_;  // (ply, course)
  int current_ply_index_ = -1;
  double moved_mm_ = 0.0;  // every move's tool-point length
  std::optional<Eigen::Vector3d> last_point_;
};

void Reader::StartPly(const program::Block& b, const MachineState& s, AfpProgram& out) {
  current_ply_index_ = -1;
  for (std::size_t i = 0; i < out.plies.size(); ++i)
    if (out.plies[i].number == s.ply) current_ply_index_ = static_cast<int>(i);
  if (current_ply_index_ < 0) {
    AfpPly p;
    p.number = s.ply;
    p.line = b.source_line;
    p.comment = b.comment;
    out.plies.push_back(p);
    current_ply_index_ = static_cast<int>(out.plies.size()) - 1;
  }
  if (out.prologue_last_line == 0) out.prologue_last_line = b.source_line - 1;
}

void Reader::StartCourse(const program::Block& b, const MachineState& s) {
  if (s.ply == 0 || current_ply_index_ < 0) {
    Error(kMarksOrder, b.source_line,
          "course " + std::to_string(s.course) + " starts before any ply (M" +
              std::to_string(dialect_.m.ply_start) + " P<n> first)");
  } else if (!seen_.insert({s.ply, s.course}).second) {
    Error(kMarksOrder, b.source_line,
          "course " + std::to_string(s.course) + " of ply " + std::to_string(s.ply) +
              " appears twice (course numbers are unique within a ply)");
  }
  open_.emplace();
  open_->course.ply = s.ply;
  open_->course.number = s.course;
  open_->course.begin_line = b.source_line;
}

void Reader::EndCourse(const program::Block& b, const MachineState& s, AfpProgram& out) {
  OpenCourse& oc = *open_;
  AfpCourse& c = oc.course;
  c.end_line = b.source_line;
  if (s.tows != 0) {
    Error(kOpenTows, b.source_line,
          "course " + std::to_string(c.number) + " ends with tows still laying (cut them with M" +
              std::to_string(dialect_.m.tow_cut) + " P0 before M" +
              std::to_string(dialect_.m.course_end) + ")");
  } else if (!oc.laid) {
    Error(kEmptyCourse, c.begin_line,
          "course " + std::to_string(c.number) + " of ply " + std::to_string(c.ply) +
              " lays no tow (no feed move with the head lowered and a tow added)");
  } else if (current_ply_index_ >= 0) {
    c.stations.resize(oc.end_stations);
    c.layup_last_line = oc.end_line;
    c.layup_length_mm = 0.0;
    for (std::size_t i = 1; i < c.stations.size(); ++i)
      c.layup_length_mm +=
          (c.stations[i].pose.translation() - c.stations[i - 1].pose.translation()).norm();
    out.plies[static_cast<std::size_t>(current_ply_index_)].courses.push_back(
        static_cast<int>(out.courses.size()));
    out.courses.push_back(std::move(c));
  }
  open_.reset();
}

void Reader::Layup(const program::Block& b, const ModalState& modal) {
  OpenCourse& oc = *open_;
  const MachineState& before = modal.Previous();
  const MachineState& after = modal.State();
  const bool adds = (after.tows & ~before.tows) != 0;
  const bool moves = b.HasAxisWords();
  if (!oc.in_layup && adds) {
    const auto pose = ToolPoseOf(before, order_);
    if (!pose) {
      Error(kIncompletePose, b.source_line,
            "a tow is added before the head's whole pose (X Y Z A B C) is known");
      return;
    }
    oc.in_layup = true;
    AfpCourse& c = oc.course;
    c.layup_first_line = b.source_line;
    c.entry.units = before.units;
    c.entry.motion = before.motion;
    c.entry.feed_mm_per_min = before.feed_mm_per_min;
    c.entry.head_retracted = before.head_retracted;
    c.entry.rail_mm = before[Axis::kRail];
    c.entry.rotator_deg = before[Axis::kRotator];
    LayupStation st;
    st.source_line = b.source_line;
    st.pose = *pose;
    c.stations.push_back(st);
  }
  if (!oc.in_layup) return;
  auto& stations = oc.course.stations;
  SetLeaving(stations.back(), after);
  if (moves) {
    const auto pose = ToolPoseOf(after, order_);
    if (!pose) {
      Error(kIncompletePose, b.source_line, "a lay-up move with the head's pose not all known");
      return;
    }
    if (after.motion == Motion::kFeed && !after.head_retracted && after.tows != 0) oc.laid = true;
    LayupStation st;
    st.source_line = b.source_line;
    st.pose = *pose;
    SetLeaving(st, after);
    stations.push_back(st);
  }
  if (before.tows != 0 && after.tows == 0) {
    oc.end_line = b.source_line;
    oc.end_stations = stations.size();
  }
}

void Reader::Block(const program::Block& b, const ModalState& modal, AfpProgram& out) {
  const MachineState& s = modal.State();
  if (b.HasAxisWords()) {
    if (!out.first_pose) out.first_pose = ToolPoseOf(s, order_);
    if (s[Axis::kX] && s[Axis::kY] && s[Axis::kZ]) {
      const Eigen::Vector3d p(*s[Axis::kX], *s[Axis::kY], *s[Axis::kZ]);
      if (last_point_) moved_mm_ += (p - *last_point_).norm();
      last_point_ = p;
      out.tool_path.push_back({b.source_line, p});
    }
  }
  if (HasMeaning(dialect_, b, MMeaning::kPlyStart) && s.ply != 0) StartPly(b, s, out);
  if (HasMeaning(dialect_, b, MMeaning::kCourseStart) && s.course != 0 && !open_) StartCourse(b, s);
  if (open_ && !HasMeaning(dialect_, b, MMeaning::kCourseStart)) Layup(b, modal);
  if (open_ && HasMeaning(dialect_, b, MMeaning::kCourseEnd)) EndCourse(b, s, out);
}

bool Reader::Finish(AfpProgram& out, int last_line, bool errors) {
  if (out.courses.empty() && !errors) {
    Error(kNoCourses, std::max(1, last_line),
          "no course marks (M" + std::to_string(dialect_.m.course_start) + " P<n> ... M" +
              std::to_string(dialect_.m.course_end) +
              "): this is not a fibre-placement programme the sequencer can read "
              "(docs/program-format.md, \"Fibre placement\")");
  }
  double layup = 0.0;
  for (const auto& c : out.courses) layup += c.layup_length_mm;
  out.offpart_length_mm = std::max(0.0, moved_mm_ - layup);
  return true;
}

}  // namespace

std::string_view AfpProgram::Line(int line) const {
  if (line < 1 || line > static_cast<int>(line_start.size())) return {};
  const std::size_t from = line_start[static_cast<std::size_t>(line - 1)];
  std::size_t to = line < static_cast<int>(line_start.size())
                       ? line_start[static_cast<std::size_t>(line)] - 1
                       : text.size();
  if (to > from && text[to - 1] == '\r') --to;
  if (to < from) to = from;
  return std::string_view(text).substr(from, to - from);
}

std::optional<AfpProgram> ReadAfpProgram(std::istream& in, const Dialect& dialect,
                                         std::string file_name, DiagnosticSink& sink) {
  AfpProgram out;
  out.file_name = file_name;
  out.text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  out.line_start.push_back(0);
  for (std::size_t i = 0; i < out.text.size(); ++i)
    if (out.text[i] == '\n' && i + 1 < out.text.size()) out.line_start.push_back(i + 1);
  std::istringstream stream(out.text);
  const std::size_t errors_before = sink.ErrorCount();
  ProgramReader reader(stream, dialect, file_name, sink);
  ModalState modal(dialect, file_name, sink);
  Reader r(dialect, file_name, sink);
  program::Block block;
  while (reader.Next(block)) {
    modal.Update(block);
    if (sink.ErrorCount() > errors_before) continue;
    r.Block(block, modal, out);
  }
  out.header = reader.Header();
  if (out.prologue_last_line == 0) out.prologue_last_line = reader.LineCount();
  r.Finish(out, reader.LineCount(), sink.ErrorCount() > errors_before);
  if (sink.ErrorCount() > errors_before) return std::nullopt;
  return out;
}

}  // namespace stitchsim::program
