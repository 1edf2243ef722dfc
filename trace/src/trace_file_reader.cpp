#include <cstring>
#include <fstream>
#include <system_error>

#include "stitchsim/trace/trace_file.h"
#include "trace_codec.h"

namespace stitchsim::trace {
namespace {

// Why a read stopped: carries the offset of the item that could not be read.
struct BadTrace {
  std::uint64_t offset;
  std::string why;
};

// Little-endian decoding from a buffered stream, with the offset of every byte read. Every
// read checks the bytes are there (a length is checked against what the file has left before
// anything is allocated).
class Decoder {
 public:
  Decoder(std::istream& in, std::uint64_t size) : in_(in), size_(size) {}

  std::uint64_t Offset() const { return offset_; }
  std::uint64_t Left() const { return size_ - offset_; }
  bool AtEnd() const { return offset_ == size_; }

  void Bytes(char* out, std::uint64_t n, const char* what) {
    if (n > Left()) {
      throw BadTrace{offset_, std::string("truncated: ") + what + " needs " + std::to_string(n) +
                                  " bytes, " + std::to_string(Left()) + " left"};
    }
    while (n > 0) {
      if (pos_ == end_) Fill();
      const std::uint64_t k = std::min<std::uint64_t>(n, end_ - pos_);
      std::memcpy(out, buf_ + pos_, k);
      pos_ += k;
      out += k;
      n -= k;
      offset_ += k;
    }
  }
  std::uint64_t Le(int n, const char* what) {
    unsigned char b[8];
    Bytes(reinterpret_cast<char*>(b), static_cast<std::uint64_t>(n), what);
    std::uint64_t v = 0;
    for (int i = n - 1; i >= 0; --i) v = (v << 8) | b[i];
    return v;
  }
  std::uint8_t U8(const char* what) { return static_cast<std::uint8_t>(Le(1, what)); }
  std::uint16_t U16(const char* what) { return static_cast<std::uint16_t>(Le(2, what)); }
  std::uint32_t U32(const char* what) { return static_cast<std::uint32_t>(Le(4, what)); }
  int I32(const char* what) { return static_cast<int>(static_cast<std::int32_t>(U32(what))); }
  long I64(const char* what) { return static_cast<long>(static_cast<std::int64_t>(Le(8, what))); }
  double F64(const char* what) {
    const std::uint64_t bits = Le(8, what);
    double v;
    std::memcpy(&v, &bits, sizeof v);
    return v;
  }
  bool Bool(const char* what) {
    const std::uint64_t at = offset_;
    const std::uint8_t b = U8(what);
    if (b > 1) throw BadTrace{at, std::string("corrupt: ") + what + " is " + std::to_string(b)};
    return b == 1;
  }
  std::string Str(const char* what) {
    const std::uint64_t at = offset_;
    const std::uint32_t n = U32(what);
    if (n > codec::kMaxStringBytes) {
      throw BadTrace{at, std::string("corrupt: ") + what + " of " + std::to_string(n) + " bytes"};
    }
    std::string s(n, '\0');
    Bytes(s.data(), n, what);
    return s;
  }
  void Vec(JointVector& v, const char* what) {
    for (int i = 0; i < kNumJoints; ++i) v[i] = F64(what);
  }
  void Translation(Eigen::Isometry3d& p, const char* what) {
    for (int i = 0; i < 3; ++i) p.translation()[i] = F64(what);
  }
  void Rotation(Eigen::Isometry3d& p, const char* what) {
    for (int c = 0; c < 3; ++c) {
      for (int r = 0; r < 3; ++r) p.linear()(r, c) = F64(what);
    }
  }
  Eigen::Isometry3d Pose(const char* what) {
    Eigen::Isometry3d p = Eigen::Isometry3d::Identity();
    Translation(p, what);
    Rotation(p, what);
    return p;
  }
  // A count of items of at least `min_item_bytes` each, no more than `max`.
  std::uint32_t Count(std::uint32_t max, std::uint64_t min_item_bytes, const char* what) {
    const std::uint64_t at = offset_;
    const std::uint32_t n = U32(what);
    if (n > max || n * min_item_bytes > Left()) {
      throw BadTrace{at, std::string("corrupt or truncated: ") + std::to_string(n) + " " + what};
    }
    return n;
  }

 private:
  void Fill() {
    in_.read(buf_, sizeof buf_);
    end_ = static_cast<std::uint64_t>(in_.gcount());
    pos_ = 0;
    if (end_ == 0) throw BadTrace{offset_, "read error (the file shrank while being read?)"};
  }
  std::istream& in_;
  std::uint64_t size_;
  std::uint64_t offset_ = 0;
  char buf_[1 << 16];
  std::uint64_t pos_ = 0, end_ = 0;
};

void DecodeHeader(Decoder& d, TraceFileHeader& h) {
  char magic[sizeof codec::kMagic];
  if (d.Left() < sizeof magic) {
    throw BadTrace{0, d.Left() == 0 ? "empty file, not a stitchsim trace"
                                    : "not a stitchsim trace file (too short)"};
  }
  d.Bytes(magic, sizeof magic, "magic");
  if (std::memcmp(magic, codec::kMagic, sizeof magic) != 0) {
    throw BadTrace{0, "not a stitchsim trace file (no trace magic)"};
  }
  const std::uint32_t version = d.U32("format version");
  if (version != kTraceFormatVersion) {
    throw BadTrace{sizeof magic, "trace format version " + std::to_string(version) +
                                     "; this stitchsim reads version " +
                                     std::to_string(kTraceFormatVersion) + " (save it again)"};
  }
  h.program_file = d.Str("programme file name");
  h.scene_name = d.Str("scene name");
  h.head = d.Str("head name");
  h.stitch_length_mm = d.F64("stitch length");
  const bool declared = d.Bool("declared-stitches flag");
  const long stitches = d.I64("declared stitches");
  if (declared) h.declared_stitches = stitches;
  h.ik_wrist_singularity_rad = d.F64("IK wrist-singularity band");
  for (std::string& name : h.cell.joint_names) name = d.Str("joint name");
  d.Vec(h.cell.lower_limits, "lower joint limits");
  d.Vec(h.cell.upper_limits, "upper joint limits");
  d.Vec(h.cell.max_velocities, "joint speeds");
  d.Vec(h.cell.max_accelerations, "joint accelerations");
  d.Vec(h.cell.max_efforts, "joint torque limits");
  for (double* v : {&h.cell.payload_rated_kg, &h.cell.payload_rated_lz_m,
                    &h.cell.payload_rated_lxy_m, &h.cell.wrist_to_flange_m}) {
    *v = d.F64("payload rating");
  }
  h.cell.timed = d.Bool("timed flag");
  h.cell.dynamic = d.Bool("dynamic flag");
  h.cell.collision_checked = d.Bool("collision-checked flag");
  const std::uint32_t bodies = d.Count(codec::kMaxBodies, 4, "bodies");
  h.cell.bodies.reserve(bodies);
  for (std::uint32_t i = 0; i < bodies; ++i) h.cell.bodies.push_back(d.Str("body name"));
  const std::uint32_t files = d.Count(codec::kMaxFingerprints, 16, "fingerprints");
  for (std::uint32_t i = 0; i < files; ++i) {
    FileFingerprint f;
    f.role = d.Str("fingerprint role");
    f.path = d.Str("fingerprinted file");
    f.fnv1a = d.Le(8, "fingerprint");
    h.fingerprints.push_back(std::move(f));
  }
}

void DecodeLine(Decoder& d, LineRecord& l) {
  l.source_line = d.I32("line number");
  const std::uint64_t at = d.Offset();
  const std::uint8_t flags = d.U8("line flags");
  if ((flags & ~codec::kKnownLineFlags) != 0) throw BadTrace{at, "corrupt line flags"};
  l.rapid = (flags & codec::kRapid) != 0;
  l.stitching = (flags & codec::kStitching) != 0;
  l.head_retracted = (flags & codec::kHeadRetracted) != 0;
  l.over_sample_limit = (flags & codec::kOverSampleLimit) != 0;
  l.from = d.Pose("line start pose");
  l.to = d.Pose("line end pose");
  for (double* v : {&l.drive_from_mm, &l.drive_to_mm, &l.path_from_mm, &l.path_to_mm, &l.duration_s,
                    &l.feed_mm_per_min, &l.samples_needed, &l.timed_duration_s}) {
    *v = d.F64("line record");
  }
  l.tows = d.Le(8, "tow mask");
  l.ply = d.I32("ply");
  l.course = d.I32("course");
}

// A body index of the header's table (-1 allowed only where `none_ok`).
int BodyIndex(Decoder& d, const CellDescription& cell, bool none_ok) {
  const std::uint64_t at = d.Offset();
  const int i = d.I32("body index");
  if ((i == -1 && none_ok) || (i >= 0 && static_cast<std::size_t>(i) < cell.bodies.size())) {
    return i;
  }
  throw BadTrace{at, "corrupt: body index " + std::to_string(i) + " (the table has " +
                         std::to_string(cell.bodies.size()) + ")"};
}

void DecodeCollision(Decoder& d, std::uint16_t flags, const CellDescription& cell,
                     SampleCollision& c) {
  c.checked = true;
  c.min_clearance_m = d.F64("clearance");
  if ((flags & codec::kHasClearancePair) != 0) {
    c.clearance_body_a = BodyIndex(d, cell, false);
    c.clearance_body_b = BodyIndex(d, cell, false);
  }
  if ((flags & codec::kHasContacts) != 0) {
    const std::uint32_t n = d.Count(codec::kMaxContacts, 42, "contacts");
    c.contacts.resize(n);
    for (Contact& k : c.contacts) {
      const std::uint64_t at = d.Offset();
      const std::uint8_t kind = d.U8("contact kind");
      if (kind > 1) throw BadTrace{at, "corrupt contact kind"};
      k.kind = kind == 1 ? ContactClass::kRobotCell : ContactClass::kHeadPart;
      k.body_a = BodyIndex(d, cell, false);
      k.body_b = BodyIndex(d, cell, false);
      k.depth_m = d.F64("contact depth");
      k.depth_measured = d.Bool("depth-measured flag");
      for (int i = 0; i < 3; ++i) k.point_world_m[i] = d.F64("contact point");
    }
  }
  if ((flags & codec::kHasError) != 0) c.error = d.Str("collision query error");
}

// `s` holds the previous sample (its rotation is reused when the flags say so).
void DecodeSample(Decoder& d, const CellDescription& cell, bool have_previous, TraceSample& s) {
  const std::uint64_t at = d.Offset();
  const std::uint16_t flags = d.U16("sample flags");
  const std::uint16_t event = flags & codec::kEventMask;
  const bool collision_flags_without_check =
      (flags & codec::kCollisionChecked) == 0 &&
      (flags & (codec::kHasContacts | codec::kHasError | codec::kHasClearancePair)) != 0;
  if ((flags & ~codec::kKnownSampleFlags) != 0 ||
      event > static_cast<std::uint16_t>(SampleEvent::kNeedleExit) ||
      collision_flags_without_check || ((flags & codec::kSameRotation) != 0 && !have_previous) ||
      ((flags & codec::kCollisionChecked) != 0 && !cell.collision_checked)) {
    throw BadTrace{at, "corrupt sample flags"};
  }
  const Eigen::Matrix3d previous_rotation = s.tool_part.linear();
  s = TraceSample{};
  s.event = static_cast<SampleEvent>(event);
  s.drive_advancing = (flags & codec::kDriveAdvancing) != 0;
  s.needles_in = (flags & codec::kNeedlesIn) != 0;
  s.has_joints = (flags & codec::kHasJoints) != 0;
  s.collision_probe = (flags & codec::kCollisionProbe) != 0;
  s.time_s = d.F64("sample time");
  s.source_line = d.I32("sample line");
  s.stitch = d.I64("sample stitch");
  s.line_fraction = d.F64("line fraction");
  d.Translation(s.tool_part, "tool position");
  if ((flags & codec::kSameRotation) != 0) {
    s.tool_part.linear() = previous_rotation;
  } else {
    d.Rotation(s.tool_part, "tool rotation");
  }
  s.drive_mm = d.F64("drive");
  s.path_mm = d.F64("path length");
  s.phase = d.F64("phase");
  if (s.has_joints) {
    const std::uint64_t status_at = d.Offset();
    const std::uint8_t status = d.U8("IK status");
    const std::uint8_t config = d.U8("arm configuration");
    if (status > static_cast<std::uint8_t>(IkStatus::kConfigFlip) ||
        (config & ~codec::kKnownConfigurationBits) != 0) {
      throw BadTrace{status_at, "corrupt IK status or arm configuration"};
    }
    s.ik_status = static_cast<IkStatus>(status);
    s.configuration.shoulder = (config & 1) != 0 ? Shoulder::kBack : Shoulder::kFront;
    s.configuration.elbow = (config & 2) != 0 ? Elbow::kDown : Elbow::kUp;
    s.configuration.wrist = (config & 4) != 0 ? Wrist::kFlip : Wrist::kNoFlip;
    d.Vec(s.joints, "joints");
  }
  if ((flags & codec::kHasTiming) != 0) {
    s.has_timing = true;
    s.timed_s = d.F64("timed time");
    if (s.has_joints) {
      d.Vec(s.joint_velocities, "joint velocities");
      d.Vec(s.joint_accelerations, "joint accelerations");
      d.Vec(s.joint_torques, "joint torques");
    }
  }
  if ((flags & codec::kTracked) != 0) {
    s.tracked = true;
    s.tracking_error_mm = d.F64("tracking error");
    s.tracking_error_deg = d.F64("tracking error (angle)");
  }
  if ((flags & codec::kCollisionChecked) != 0) DecodeCollision(d, flags, cell, s.collision);
}

std::string Where(const std::filesystem::path& path, std::uint64_t offset) {
  return path.string() + ": byte " + std::to_string(offset) + ": ";
}

}  // namespace

struct TraceFileReader::Impl {
  std::filesystem::path path;
  std::ifstream in;
  std::unique_ptr<Decoder> decoder;
  TraceFileHeader header;
};

TraceFileReader::TraceFileReader() : impl_(std::make_unique<Impl>()) {}
TraceFileReader::~TraceFileReader() = default;

std::unique_ptr<TraceFileReader> TraceFileReader::Open(const std::filesystem::path& path,
                                                       std::string& error) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status)) {
    error = path.string() + ": no such trace file";
    return nullptr;
  }
  if (!std::filesystem::is_regular_file(status)) {
    error = path.string() + (std::filesystem::is_directory(status)
                                 ? ": is a directory, not a trace file"
                                 : ": not a regular file, not a trace file");
    return nullptr;
  }
  const std::uint64_t size = std::filesystem::file_size(path, ec);
  std::unique_ptr<TraceFileReader> r(new TraceFileReader());
  r->impl_->path = path;
  r->impl_->in.open(path, std::ios::binary);
  if (ec || !r->impl_->in) {
    error = path.string() + ": cannot be read";
    return nullptr;
  }
  r->impl_->decoder = std::make_unique<Decoder>(r->impl_->in, size);
  try {
    DecodeHeader(*r->impl_->decoder, r->impl_->header);
  } catch (const BadTrace& bad) {
    error = Where(path, bad.offset) + bad.why;
    return nullptr;
  }
  return r;
}

const TraceFileHeader& TraceFileReader::Header() const { return impl_->header; }

bool TraceFileReader::Replay(TraceSink& sink, TraceFileSummary& summary, std::string& error) {
  Decoder& d = *impl_->decoder;
  const CellDescription& cell = impl_->header.cell;
  LineRecord line;
  TraceSample sample;
  bool have_sample = false;
  try {
    for (;;) {
      const std::uint64_t at = d.Offset();
      if (d.AtEnd()) throw BadTrace{at, "truncated: the trace ends without its summary"};
      const std::uint8_t tag = d.U8("record tag");
      if (tag == codec::kLineTag) {
        DecodeLine(d, line);
        sink.OnLine(line);
      } else if (tag == codec::kSampleTag) {
        DecodeSample(d, cell, have_sample, sample);
        have_sample = true;
        sink.OnSample(sample);
      } else if (tag == codec::kEndTag) {
        summary.lines = d.I64("line count");
        summary.moves = d.I64("move count");
        summary.cycle_time_s = d.F64("cycle time");
        summary.cycle_time_timed_s = d.F64("timed cycle time");
        if (!d.AtEnd()) throw BadTrace{d.Offset(), "corrupt: bytes after the summary"};
        return true;
      } else {
        throw BadTrace{at, "corrupt: unknown record tag " + std::to_string(tag)};
      }
    }
  } catch (const BadTrace& bad) {
    error = Where(impl_->path, bad.offset) + bad.why;
    return false;
  }
}

}  // namespace stitchsim::trace
