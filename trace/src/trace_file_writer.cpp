#include <cmath>
#include <cstring>
#include <ostream>

#include "stitchsim/common/files.h"
#include "stitchsim/trace/trace_file.h"
#include "trace_codec.h"

namespace stitchsim::trace {
namespace {

// Little-endian encoding into a reused buffer, flushed to the stream per record.
class Encoder {
 public:
  void U8(std::uint8_t v) { bytes_.push_back(static_cast<char>(v)); }
  void U16(std::uint16_t v) { Le(v, 2); }
  void U32(std::uint32_t v) { Le(v, 4); }
  void I32(int v) { Le(static_cast<std::uint32_t>(v), 4); }
  void I64(long v) { Le(static_cast<std::uint64_t>(v), 8); }
  void U64(std::uint64_t v) { Le(v, 8); }
  void F64(double v) {
    std::uint64_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    Le(bits, 8);
  }
  void Str(const std::string& s) {
    U32(static_cast<std::uint32_t>(s.size()));
    bytes_.append(s);
  }
  void Vec(const JointVector& v) {
    for (int i = 0; i < kNumJoints; ++i) F64(v[i]);
  }
  void Translation(const Eigen::Isometry3d& p) {
    for (int i = 0; i < 3; ++i) F64(p.translation()[i]);
  }
  void Rotation(const Eigen::Isometry3d& p) {
    for (int c = 0; c < 3; ++c) {
      for (int r = 0; r < 3; ++r) F64(p.linear()(r, c));
    }
  }
  void Pose(const Eigen::Isometry3d& p) {
    Translation(p);
    Rotation(p);
  }
  void FlushTo(std::ostream& out) {
    out.write(bytes_.data(), static_cast<std::streamsize>(bytes_.size()));
    bytes_.clear();
  }

 private:
  void Le(std::uint64_t v, int n) {
    for (int i = 0; i < n; ++i) bytes_.push_back(static_cast<char>((v >> (8 * i)) & 0xff));
  }
  std::string bytes_;
};

void EncodeHeader(const TraceFileHeader& h, Encoder& e) {
  for (char c : codec::kMagic) e.U8(static_cast<std::uint8_t>(c));
  e.U32(kTraceFormatVersion);
  e.Str(h.program_file);
  e.Str(h.scene_name);
  e.Str(h.head);
  e.F64(h.stitch_length_mm);
  e.U8(h.declared_stitches ? 1 : 0);
  e.I64(h.declared_stitches.value_or(0));
  e.F64(h.ik_wrist_singularity_rad);
  for (const std::string& name : h.cell.joint_names) e.Str(name);
  e.Vec(h.cell.lower_limits);
  e.Vec(h.cell.upper_limits);
  e.Vec(h.cell.max_velocities);
  e.Vec(h.cell.max_accelerations);
  e.Vec(h.cell.max_efforts);
  for (double v : {h.cell.payload_rated_kg, h.cell.payload_rated_lz_m, h.cell.payload_rated_lxy_m,
                   h.cell.wrist_to_flange_m}) {
    e.F64(v);
  }
  e.U8(h.cell.timed ? 1 : 0);
  e.U8(h.cell.dynamic ? 1 : 0);
  e.U8(h.cell.collision_checked ? 1 : 0);
  e.U32(static_cast<std::uint32_t>(h.cell.bodies.size()));
  for (const std::string& body : h.cell.bodies) e.Str(body);
  e.U32(static_cast<std::uint32_t>(h.fingerprints.size()));
  for (const FileFingerprint& f : h.fingerprints) {
    e.Str(f.role);
    e.Str(f.path);
    e.U64(f.fnv1a);
  }
}

std::uint8_t ConfigurationBits(const ArmConfiguration& c) {
  return static_cast<std::uint8_t>((c.shoulder == Shoulder::kBack ? 1 : 0) |
                                   (c.elbow == Elbow::kDown ? 2 : 0) |
                                   (c.wrist == Wrist::kFlip ? 4 : 0));
}

void EncodeCollision(const SampleCollision& c, Encoder& e) {
  e.F64(c.min_clearance_m);
  if (c.clearance_body_a >= 0) {
    e.I32(c.clearance_body_a);
    e.I32(c.clearance_body_b);
  }
  if (!c.contacts.empty()) {
    e.U32(static_cast<std::uint32_t>(c.contacts.size()));
    for (const Contact& k : c.contacts) {
      e.U8(k.kind == ContactClass::kRobotCell ? 1 : 0);
      e.I32(k.body_a);
      e.I32(k.body_b);
      e.F64(k.depth_m);
      e.U8(k.depth_measured ? 1 : 0);
      for (int i = 0; i < 3; ++i) e.F64(k.point_world_m[i]);
    }
  }
  if (!c.error.empty()) e.Str(c.error);
}

}  // namespace

std::uint64_t Fnv1a64(std::string_view bytes) {
  std::uint64_t h = 14695981039346656037ull;  // the FNV-1a 64-bit offset basis
  for (unsigned char c : bytes) h = (h ^ c) * 1099511628211ull;
  return h;
}

struct TraceFileWriter::Impl {
  std::unique_ptr<OutputFile> file;
  Encoder encoder;
  Eigen::Matrix3d last_rotation = Eigen::Matrix3d::Constant(std::nan(""));
};

TraceFileWriter::TraceFileWriter() : impl_(std::make_unique<Impl>()) {}
TraceFileWriter::~TraceFileWriter() = default;

std::unique_ptr<TraceFileWriter> TraceFileWriter::Open(const std::filesystem::path& path,
                                                       const TraceFileHeader& header,
                                                       std::string& error) {
  std::unique_ptr<TraceFileWriter> w(new TraceFileWriter());
  w->impl_->file = OutputFile::Open(path, error);
  if (!w->impl_->file) return nullptr;
  EncodeHeader(header, w->impl_->encoder);
  w->impl_->encoder.FlushTo(w->impl_->file->Stream());
  return w;
}

void TraceFileWriter::OnLine(const LineRecord& l) {
  Encoder& e = impl_->encoder;
  e.U8(codec::kLineTag);
  e.I32(l.source_line);
  e.U8(static_cast<std::uint8_t>((l.rapid ? codec::kRapid : 0) |
                                 (l.stitching ? codec::kStitching : 0) |
                                 (l.head_retracted ? codec::kHeadRetracted : 0) |
                                 (l.over_sample_limit ? codec::kOverSampleLimit : 0)));
  e.Pose(l.from);
  e.Pose(l.to);
  for (double v : {l.drive_from_mm, l.drive_to_mm, l.path_from_mm, l.path_to_mm, l.duration_s,
                   l.feed_mm_per_min, l.samples_needed, l.timed_duration_s}) {
    e.F64(v);
  }
  e.U64(l.tows);
  e.I32(l.ply);
  e.I32(l.course);
  e.FlushTo(impl_->file->Stream());
}

void TraceFileWriter::OnSample(const TraceSample& s) {
  Encoder& e = impl_->encoder;
  const SampleCollision& c = s.collision;
  // Bit-equal rotations only (NaN never equals: the first sample always writes its own).
  const bool same_rotation = s.tool_part.linear() == impl_->last_rotation;
  std::uint16_t flags = static_cast<std::uint16_t>(s.event);
  if (s.drive_advancing) flags |= codec::kDriveAdvancing;
  if (s.needles_in) flags |= codec::kNeedlesIn;
  if (s.has_joints) flags |= codec::kHasJoints;
  if (c.checked) flags |= codec::kCollisionChecked;
  if (c.checked && !c.contacts.empty()) flags |= codec::kHasContacts;
  if (c.checked && !c.error.empty()) flags |= codec::kHasError;
  if (same_rotation) flags |= codec::kSameRotation;
  if (c.checked && c.clearance_body_a >= 0) flags |= codec::kHasClearancePair;
  if (s.has_timing) flags |= codec::kHasTiming;
  if (s.tracked) flags |= codec::kTracked;
  if (s.collision_probe) flags |= codec::kCollisionProbe;
  e.U8(codec::kSampleTag);
  e.U16(flags);
  e.F64(s.time_s);
  e.I32(s.source_line);
  e.I64(s.stitch);
  e.F64(s.line_fraction);
  e.Translation(s.tool_part);
  if (!same_rotation) e.Rotation(s.tool_part);
  e.F64(s.drive_mm);
  e.F64(s.path_mm);
  e.F64(s.phase);
  if (s.has_joints) {
    e.U8(static_cast<std::uint8_t>(s.ik_status));
    e.U8(ConfigurationBits(s.configuration));
    e.Vec(s.joints);
  }
  if (s.has_timing) {
    e.F64(s.timed_s);
    if (s.has_joints) {
      e.Vec(s.joint_velocities);
      e.Vec(s.joint_accelerations);
      e.Vec(s.joint_torques);
    }
  }
  if (s.tracked) {
    e.F64(s.tracking_error_mm);
    e.F64(s.tracking_error_deg);
  }
  if (c.checked) EncodeCollision(c, e);
  impl_->last_rotation = s.tool_part.linear();
  e.FlushTo(impl_->file->Stream());
}

std::string TraceFileWriter::Commit(const TraceFileSummary& summary) {
  Encoder& e = impl_->encoder;
  e.U8(codec::kEndTag);
  e.I64(summary.lines);
  e.I64(summary.moves);
  e.F64(summary.cycle_time_s);
  e.F64(summary.cycle_time_timed_s);
  e.FlushTo(impl_->file->Stream());
  return impl_->file->Commit();
}

}  // namespace stitchsim::trace
