// Trace files: what is written is read back bit for bit (two routes: the sink's records and
// the file's), and a damaged file is an error with the file and byte offset, never a crash.
#include "stitchsim/trace/trace_file.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace stitchsim::trace {
namespace {

namespace fs = std::filesystem;

fs::path Scratch(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("stitchsim_trace_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir / name;
}

std::string ReadBytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

TraceFileHeader MakeHeader() {
  TraceFileHeader h;
  h.program_file = "prog.nc";
  h.scene_name = "plate";
  h.head = "rs535";
  h.stitch_length_mm = 5.0068;
  h.declared_stitches = 255;
  h.ik_wrist_singularity_rad = 0.0349;
  for (int j = 0; j < kNumJoints; ++j)
    h.cell.joint_names[static_cast<std::size_t>(j)] = "j" + std::to_string(j);
  h.cell.lower_limits.setConstant(-2.0);
  h.cell.upper_limits.setConstant(2.5);
  h.cell.max_velocities.setConstant(1.5);
  h.cell.collision_checked = true;
  h.cell.bodies = {"head:presser_foot", "rail", "constraint:a|b"};
  h.fingerprints = {{"scene", "scenes/plate.yaml", 0x1234567890abcdefull}};
  return h;
}

// Records everything it is sent.
struct Recorder : TraceSink {
  std::vector<LineRecord> lines;
  std::vector<TraceSample> samples;
  void OnLine(const LineRecord& l) override { lines.push_back(l); }
  void OnSample(const TraceSample& s) override { samples.push_back(s); }
};

Recorder MakeTrace() {
  Recorder r;
  LineRecord l;
  l.source_line = 7;
  l.rapid = true;
  l.stitching = true;
  l.from.translation() = Eigen::Vector3d(1, 2, 3);
  l.to = Eigen::Translation3d(4, 5, 6) * Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ());
  l.drive_to_mm = 10.1;
  l.path_to_mm = 10.2;
  l.duration_s = 0.7;
  l.feed_mm_per_min = 3000;
  l.samples_needed = 23;
  l.tows = 0x8000'0000'0000'8001ULL;  // tows 1, 16 and 64
  l.ply = 3;
  l.course = 41;
  r.lines.push_back(l);
  for (int i = 0; i < 6; ++i) {
    TraceSample s;
    s.time_s = 0.1 * i + 1e-17;
    s.source_line = 7;
    s.stitch = i / 2;
    s.line_fraction = i / 5.0;
    s.event = static_cast<SampleEvent>(i % 5);
    // Rotations repeat (the writer's same-rotation flag) and change.
    s.tool_part = Eigen::Translation3d(i, -i, 0.5 * i) *
                  Eigen::AngleAxisd(i < 3 ? 0.1 : 0.2 * i, Eigen::Vector3d(1, 2, 3).normalized());
    s.drive_mm = 1.7 * i;
    s.path_mm = 1.6 * i;
    s.phase = 0.15;
    s.drive_advancing = i % 2 == 0;
    s.needles_in = i % 3 == 0;
    s.has_joints = i != 1;
    s.ik_status = static_cast<IkStatus>(i % 6);
    s.joints = JointVector::LinSpaced(0.1 * i, 1.0);
    s.configuration = {Shoulder::kBack, i % 2 ? Elbow::kDown : Elbow::kUp, Wrist::kFlip};
    if (i >= 2) {
      s.collision.checked = true;
      s.collision.min_clearance_m = i == 2 ? 1e9 : 0.0123;
      if (i > 2) {
        s.collision.clearance_body_a = 0;
        s.collision.clearance_body_b = 2;
      }
      if (i == 4) {
        s.collision.contacts.push_back(
            {ContactClass::kRobotCell, 0, 1, 0.016, true, {3.1, 0.5, 0.2}});
        s.collision.contacts.push_back({ContactClass::kHeadPart, 2, 0, 0.0, false, {0, 0, 0}});
      }
      if (i == 5) s.collision.error = "FCL distance query failed for a|b";
    }
    r.samples.push_back(s);
  }
  return r;
}

fs::path WriteTrace(const std::string& name, const Recorder& t) {
  const fs::path p = Scratch(name);
  std::string error;
  auto w = TraceFileWriter::Open(p, MakeHeader(), error);
  EXPECT_NE(w, nullptr) << error;
  if (!w) return p;
  w->OnLine(t.lines[0]);
  for (const auto& s : t.samples) w->OnSample(s);
  EXPECT_EQ(w->Commit({261, 256, 51.25}), "");
  return p;
}

void ExpectSamePose(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  EXPECT_TRUE(a.matrix() == b.matrix()) << a.matrix() << "\nvs\n" << b.matrix();
}

TEST(TraceFile, WhatIsWrittenIsReadBackBitForBit) {
  const Recorder t = MakeTrace();
  const fs::path p = WriteTrace("round.trace", t);
  std::string error;
  auto r = TraceFileReader::Open(p, error);
  ASSERT_NE(r, nullptr) << error;
  const TraceFileHeader& h = r->Header();
  const TraceFileHeader want = MakeHeader();
  EXPECT_EQ(h.program_file, want.program_file);
  EXPECT_EQ(h.scene_name, want.scene_name);
  EXPECT_EQ(h.head, want.head);
  EXPECT_EQ(h.stitch_length_mm, want.stitch_length_mm);
  EXPECT_EQ(h.declared_stitches, want.declared_stitches);
  EXPECT_EQ(h.ik_wrist_singularity_rad, want.ik_wrist_singularity_rad);
  EXPECT_EQ(h.cell.joint_names, want.cell.joint_names);
  EXPECT_EQ(h.cell.lower_limits, want.cell.lower_limits);
  EXPECT_EQ(h.cell.upper_limits, want.cell.upper_limits);
  EXPECT_EQ(h.cell.max_velocities, want.cell.max_velocities);
  EXPECT_EQ(h.cell.collision_checked, true);
  EXPECT_EQ(h.cell.bodies, want.cell.bodies);
  ASSERT_EQ(h.fingerprints.size(), 1u);
  EXPECT_EQ(h.fingerprints[0].fnv1a, want.fingerprints[0].fnv1a);
  Recorder back;
  TraceFileSummary summary;
  ASSERT_TRUE(r->Replay(back, summary, error)) << error;
  EXPECT_EQ(summary.lines, 261);
  EXPECT_EQ(summary.moves, 256);
  EXPECT_EQ(summary.cycle_time_s, 51.25);
  ASSERT_EQ(back.lines.size(), 1u);
  const LineRecord &a = back.lines[0], &b = t.lines[0];
  EXPECT_EQ(a.source_line, b.source_line);
  EXPECT_EQ(a.rapid, b.rapid);
  EXPECT_EQ(a.stitching, b.stitching);
  EXPECT_EQ(a.head_retracted, b.head_retracted);
  ExpectSamePose(a.from, b.from);
  ExpectSamePose(a.to, b.to);
  EXPECT_EQ(a.drive_to_mm, b.drive_to_mm);
  EXPECT_EQ(a.duration_s, b.duration_s);
  EXPECT_EQ(a.samples_needed, b.samples_needed);
  EXPECT_EQ(a.tows, b.tows);
  EXPECT_EQ(a.ply, b.ply);
  EXPECT_EQ(a.course, b.course);
  ASSERT_EQ(back.samples.size(), t.samples.size());
  for (std::size_t i = 0; i < t.samples.size(); ++i) {
    const TraceSample &x = back.samples[i], &y = t.samples[i];
    EXPECT_EQ(x.time_s, y.time_s) << i;
    EXPECT_EQ(x.stitch, y.stitch) << i;
    EXPECT_EQ(x.event, y.event) << i;
    ExpectSamePose(x.tool_part, y.tool_part);
    EXPECT_EQ(x.drive_mm, y.drive_mm) << i;
    EXPECT_EQ(x.needles_in, y.needles_in) << i;
    EXPECT_EQ(x.drive_advancing, y.drive_advancing) << i;
    EXPECT_EQ(x.has_joints, y.has_joints) << i;
    if (y.has_joints) {
      EXPECT_EQ(x.ik_status, y.ik_status) << i;
      EXPECT_EQ(x.joints, y.joints) << i;
      EXPECT_EQ(x.configuration, y.configuration) << i;
    }
    EXPECT_EQ(x.collision.checked, y.collision.checked) << i;
    EXPECT_EQ(x.collision.min_clearance_m, y.collision.min_clearance_m) << i;
    EXPECT_EQ(x.collision.clearance_body_a, y.collision.clearance_body_a) << i;
    EXPECT_EQ(x.collision.clearance_body_b, y.collision.clearance_body_b) << i;
    EXPECT_EQ(x.collision.error, y.collision.error) << i;
    ASSERT_EQ(x.collision.contacts.size(), y.collision.contacts.size()) << i;
    for (std::size_t k = 0; k < y.collision.contacts.size(); ++k) {
      const Contact &c = x.collision.contacts[k], &d = y.collision.contacts[k];
      EXPECT_EQ(c.kind, d.kind);
      EXPECT_EQ(c.body_a, d.body_a);
      EXPECT_EQ(c.body_b, d.body_b);
      EXPECT_EQ(c.depth_m, d.depth_m);
      EXPECT_EQ(c.depth_measured, d.depth_measured);
      EXPECT_EQ(c.point_world_m, d.point_world_m);
    }
  }
}

TEST(TraceFile, NothingAppearsUnlessCommitted) {
  const fs::path p = Scratch("uncommitted.trace");
  std::string error;
  {
    auto w = TraceFileWriter::Open(p, MakeHeader(), error);
    ASSERT_NE(w, nullptr) << error;
    w->OnSample(TraceSample{});
  }
  EXPECT_FALSE(fs::exists(p));
}

// Every prefix and every single-byte change of a good file: an error naming the file and a
// byte offset, or (a change in a value) a file that reads; never a crash or a hang.
TEST(TraceFile, DamagedFilesAreErrorsWithFileAndOffset) {
  const std::string good = ReadBytes(WriteTrace("good.trace", MakeTrace()));
  const fs::path p = Scratch("damaged.trace");
  const auto read = [&](const std::string& bytes, std::string& error) {
    std::ofstream(p, std::ios::binary | std::ios::trunc) << bytes;
    auto r = TraceFileReader::Open(p, error);
    if (!r) return false;
    Recorder sink;
    TraceFileSummary summary;
    return r->Replay(sink, summary, error);
  };
  for (std::size_t cut = 0; cut < good.size(); ++cut) {
    std::string error;
    EXPECT_FALSE(read(good.substr(0, cut), error)) << cut;
    EXPECT_EQ(error.rfind(p.string() + ": byte ", 0), 0u) << cut << ": " << error;
  }
  for (std::size_t at = 0; at < good.size(); ++at) {
    std::string bytes = good;
    bytes[at] = static_cast<char>(bytes[at] ^ 0xa5);
    std::string error;
    if (!read(bytes, error)) {
      EXPECT_EQ(error.rfind(p.string() + ": byte ", 0), 0u) << error;
    }
  }
  std::string error;
  std::string bytes = good;
  bytes[0] = 'X';
  EXPECT_FALSE(read(bytes, error));
  EXPECT_NE(error.find("not a stitchsim trace"), std::string::npos) << error;
  bytes = good;
  bytes[8] = static_cast<char>(kTraceFormatVersion + 1);
  EXPECT_FALSE(read(bytes, error));
  EXPECT_NE(error.find("version " + std::to_string(kTraceFormatVersion + 1)), std::string::npos)
      << error;
  EXPECT_FALSE(read(good + "x", error));
  EXPECT_NE(error.find("after the summary"), std::string::npos) << error;
}

TEST(TraceFile, ADirectoryOrAMissingFileIsAnError) {
  std::string error;
  EXPECT_EQ(TraceFileReader::Open(fs::temp_directory_path(), error), nullptr);
  EXPECT_NE(error.find("directory"), std::string::npos) << error;
  EXPECT_EQ(TraceFileReader::Open(Scratch("none.trace"), error), nullptr);
  EXPECT_NE(error.find("none.trace"), std::string::npos) << error;
}

// The one IK-usable predicate.
TEST(TraceTypes, JointsAreUsableUnlessUnreachableOrBeyondALimit) {
  TraceSample s;
  EXPECT_FALSE(JointsUsable(s));  // no joints
  s.has_joints = true;
  for (IkStatus st : {IkStatus::kOk, IkStatus::kWristSingularity, IkStatus::kShoulderSingularity,
                      IkStatus::kConfigFlip}) {
    s.ik_status = st;
    EXPECT_TRUE(JointsUsable(s)) << ToString(st);
  }
  for (IkStatus st : {IkStatus::kUnreachable, IkStatus::kJointLimit}) {
    s.ik_status = st;
    EXPECT_FALSE(JointsUsable(s)) << ToString(st);
  }
}

TEST(TraceTypes, Fnv1aOfKnownBytes) {
  EXPECT_EQ(Fnv1a64(""), 0xcbf29ce484222325ull);
  EXPECT_EQ(Fnv1a64("a"), 0xaf63dc4c8601ec8cull);
}

}  // namespace
}  // namespace stitchsim::trace
