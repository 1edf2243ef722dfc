#include "stitchsim/planner/raster_planner.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numeric>
#include <ostream>
#include <sstream>

#include "detail/program_text.h"
#include "stitchsim/common/files.h"
#include "stitchsim/common/limits.h"
#include "stitchsim/geom/rotation.h"
#include "stitchsim/program/block.h"
#include "stitchsim/program/writer.h"
#include "stitchsim/scene/footprint.h"

namespace stitchsim::planner {
namespace {

// Traverse speed and retract / lower time for the time estimate (the head spec has none).
constexpr double kTraverseMmPerMin = 20000.0;
constexpr double kRetractLowerS = 0.5;

// A piece of one row to stitch: v, and the u-range of clear surface.
struct RowPiece {
  long row = 0;  ///< global row index (direction parity)
  double v = 0.0;
  double u_begin = 0.0;
  double u_end = 0.0;
};

// A region handed to one head: a row (jump) or a bay (serpentine).
struct Region {
  std::vector<RowPiece> pieces;
  long stitches = 0;
};

// Free u-intervals of the row at v inside [u0, u1].
std::vector<std::pair<double, double>> FreeIntervals(const std::vector<scene::Footprint>& fps,
                                                     double v, double u0, double u1) {
  std::vector<std::pair<double, double>> blocked;
  for (const scene::Footprint& f : fps) {
    double a = 0, b = 0;
    if (f.RowInterval(v, a, b) && b > u0 && a < u1) blocked.emplace_back(a, b);
  }
  std::sort(blocked.begin(), blocked.end());
  std::vector<std::pair<double, double>> free;
  double at = u0;
  for (const auto& [a, b] : blocked) {
    if (a > at) free.emplace_back(at, std::min(a, u1));
    at = std::max(at, b);
    if (at >= u1) break;
  }
  if (at < u1) free.emplace_back(at, u1);
  return free;
}

// Steps along a row at an exact 3D chord of `pitch`.
class RowStepper {
 public:
  RowStepper(const geom::Surface& s, double pitch) : s_(s), pitch_(pitch) {}
  /// u of the point one pitch (chord) from u in direction dir (+1/-1).
  double Next(double u, double v, double dir) const {
    const Eigen::Vector3d p = s_.Point({u, v});
    const double speed = s_.Jacobian({u, v}).col(0).norm();
    double du = pitch_ / std::max(speed, 1e-9);
    for (int it = 0; it < 3; ++it) {
      const double d = (s_.Point({u + dir * du, v}) - p).norm();
      if (d <= 0) break;
      du *= pitch_ / d;
    }
    return u + dir * du;
  }
  /// Stitches that fit in [a, b] starting at a (dir > 0) or at b (dir < 0).
  long Count(double a, double b, double v, double dir = 1.0) const {
    long n = 0;
    double u = dir > 0 ? a : b;
    while (true) {
      const double next = Next(u, v, dir);
      if (next > b + 1e-9 || next < a - 1e-9) break;
      u = next;
      ++n;
    }
    return n;
  }

 private:
  const geom::Surface& s_;
  double pitch_;
};

// Height of a point above a height-field surface: z minus the surface height at its (x, y),
// clamped into the domain.
double Above(const geom::Surface& s, const Eigen::Vector3d& p) {
  const geom::Domain2 dom = s.Domain();
  return p.z() - s.Point(p.head<2>().cwiseMax(dom.min).cwiseMin(dom.max)).z();
}

// Height of a constraint's top above the surface: the largest over its corners (box) or
// vertices (mesh).
double HeightAboveSurface(const scene::Constraint& c, const geom::Surface& s) {
  auto above = [&](const Eigen::Vector3d& p) { return Above(s, p); };
  double h = 0.0;
  if (c.shape == scene::Constraint::Shape::kMesh) {
    for (const auto& v : c.mesh.vertices) h = std::max(h, above(v));
    return h;
  }
  for (int k = 0; k < 8; ++k) {
    const Eigen::Vector3d corner(((k & 1) ? 0.5 : -0.5) * c.size_mm.x(),
                                 ((k & 2) ? 0.5 : -0.5) * c.size_mm.y(),
                                 ((k & 4) ? 0.5 : -0.5) * c.size_mm.z());
    h = std::max(h, above(c.pose_mm * corner));
  }
  return h;
}

// How far to lift along the normals na (at a) and nb (at b) so that the straight flight
// between the lifted points stays at least `clear` above the surface (sampled every 20 mm):
// `clear` itself unless the flight crosses a crown (a move between bays on a cambered skin).
double FlightLift(const geom::Surface& s, const Eigen::Vector3d& a, const Eigen::Vector3d& na,
                  const Eigen::Vector3d& b, const Eigen::Vector3d& nb, double clear) {
  double lift = clear;
  for (int it = 0; it < 8; ++it) {
    const Eigen::Vector3d from = a + lift * na, to = b + lift * nb;
    const int n = std::max(2, static_cast<int>((to - from).norm() / 20.0) + 1);
    double deficit = 0.0;
    for (int k = 0; k <= n; ++k) {
      deficit = std::max(deficit, clear - Above(s, from + (to - from) * (double(k) / n)));
    }
    if (deficit <= 1e-6) break;
    lift += deficit + 1.0;
  }
  return lift;
}

std::string Num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.6f", v);
  return buf;
}

}  // namespace

RasterOptions RasterOptionsFor(const scene::Scene& scene) {
  RasterOptions o;
  o.pitch_mm = scene.raster.pitch_mm.value_or(o.pitch_mm);
  o.row_spacing_mm = scene.raster.row_spacing_mm.value_or(o.row_spacing_mm);
  o.margin_mm = scene.raster.margin_mm.value_or(o.margin_mm);
  return o;
}

std::optional<RasterStrategy> ParseRasterStrategy(std::string_view text) {
  if (text == "jump") return RasterStrategy::kJump;
  if (text == "serpentine") return RasterStrategy::kSerpentine;
  return std::nullopt;
}

std::string_view ToString(RasterStrategy strategy) {
  return strategy == RasterStrategy::kJump ? "jump" : "serpentine";
}

// ---- user code library ----------------------------------------------------------------------

std::optional<UserCodeLibrary> ParseUserCodeLibrary(std::string_view yaml,
                                                    const std::string& file_name,
                                                    const program::Dialect& dialect,
                                                    DiagnosticSink& sink) {
  auto at = [&](const YAML::Node& n) {
    return SourceLocation{file_name, n.Mark().line + 1, n.Mark().column + 1};
  };
  UserCodeLibrary lib;
  const std::size_t errors_before = sink.ErrorCount();
  try {
    const YAML::Node root = YAML::Load(std::string(yaml));
    const YAML::Node blocks = root["blocks"];
    if (!blocks || !blocks.IsSequence()) {
      sink.Error("library-no-blocks", {file_name, 1, 1}, "expected a 'blocks:' list");
      return std::nullopt;
    }
    for (const YAML::Node& b : blocks) {
      UserCodeBlock blk;
      blk.name = b["name"] ? b["name"].as<std::string>() : "unnamed";
      const std::string event = b["at"] ? b["at"].as<std::string>() : "";
      if (event == "every_stitches") {
        blk.event = UserCodeBlock::Event::kEveryStitches;
        blk.every_stitches = b["every"] ? b["every"].as<long>() : 0;
        if (blk.every_stitches <= 0) {
          sink.Error("library-bad-every", at(b), blk.name + ": 'every' must be a positive count");
        }
      } else if (event == "row_start") {
        blk.event = UserCodeBlock::Event::kRowStart;
      } else if (event == "before_jump") {
        blk.event = UserCodeBlock::Event::kBeforeJump;
      } else {
        sink.Error("library-bad-event", at(b),
                   blk.name + ": 'at' must be every_stitches, row_start or before_jump");
      }
      if (b["m"]) {
        for (const YAML::Node& m : b["m"]) blk.m_codes.push_back(m.as<int>());
      }
      if (blk.m_codes.empty() || blk.m_codes.size() > program::kMaxMCodesPerBlock) {
        sink.Error("library-bad-m", at(b), blk.name + ": 'm' must list 1 to 4 M codes");
      }
      for (int m : blk.m_codes) {
        if (m < dialect.m.user_macro_first || m > dialect.m.user_macro_last) {
          sink.Error("library-m-not-user", at(b),
                     blk.name + ": M" + std::to_string(m) + " is outside the user range M" +
                         std::to_string(dialect.m.user_macro_first) + "-M" +
                         std::to_string(dialect.m.user_macro_last));
        }
      }
      if (b["p"]) blk.param = b["p"].as<int>();
      lib.blocks.push_back(std::move(blk));
    }
  } catch (const YAML::Exception& e) {
    sink.Error("library-yaml", {file_name, e.mark.line + 1, e.mark.column + 1}, e.msg);
    return std::nullopt;
  }
  if (sink.ErrorCount() > errors_before) return std::nullopt;
  return lib;
}

std::optional<UserCodeLibrary> LoadUserCodeLibrary(const std::filesystem::path& file,
                                                   const program::Dialect& dialect,
                                                   DiagnosticSink& sink) {
  const FileText text = ReadRegularFile(file, limits::kMaxYamlFileBytes);
  if (!text.ok()) {
    sink.Error("library-unreadable", {file.string(), 0, 0},
               "cannot read the code library: " + text.error);
    return std::nullopt;
  }
  return ParseUserCodeLibrary(text.text, file.string(), dialect, sink);
}

// ---- planning -------------------------------------------------------------------------------

namespace {

struct Plan {
  std::vector<Region> regions;
  std::vector<std::vector<std::size_t>> per_head;  // region indices per head (0-based)
};

std::vector<Region> JumpRegions(const std::vector<scene::Footprint>& fps,
                                const Eigen::AlignedBox2d& box, double spacing) {
  std::vector<Region> out;
  const long rows = static_cast<long>(std::floor(box.sizes().y() / spacing + 1e-9)) + 1;
  for (long r = 0; r < rows; ++r) {
    const double v = box.min().y() + r * spacing;
    Region reg;
    for (const auto& [a, b] : FreeIntervals(fps, v, box.min().x(), box.max().x())) {
      reg.pieces.push_back({r, v, a, b});
    }
    if (!reg.pieces.empty()) out.push_back(std::move(reg));
  }
  return out;
}

// Bays: the grid cut at every footprint's u and v edges; cells ordered band by band (v),
// snaking along u.
std::vector<Region> BayRegions(const std::vector<scene::Footprint>& fps,
                               const Eigen::AlignedBox2d& box, double spacing) {
  std::vector<double> us = {box.min().x(), box.max().x()};
  std::vector<double> vs = {box.min().y(), box.max().y() + 1e-6};
  for (const scene::Footprint& f : fps) {
    const Eigen::Vector2d ext =
        f.axis_x.cwiseAbs() * f.half_mm.x() + f.axis_y.cwiseAbs() * f.half_mm.y();
    for (double s : {-1.0, 1.0}) {
      const double u = f.centre.x() + s * ext.x();
      const double v = f.centre.y() + s * ext.y();
      if (u > box.min().x() && u < box.max().x()) us.push_back(u);
      if (v > box.min().y() && v < box.max().y()) vs.push_back(v);
    }
  }
  std::sort(us.begin(), us.end());
  us.erase(std::unique(us.begin(), us.end()), us.end());
  std::sort(vs.begin(), vs.end());
  vs.erase(std::unique(vs.begin(), vs.end()), vs.end());
  std::vector<Region> out;
  for (std::size_t j = 0; j + 1 < vs.size(); ++j) {
    const long r0 = static_cast<long>(std::ceil((vs[j] - box.min().y()) / spacing - 1e-9));
    const long r1 = static_cast<long>(std::ceil((vs[j + 1] - box.min().y()) / spacing - 1e-9));
    for (std::size_t ii = 0; ii + 1 < us.size(); ++ii) {
      const std::size_t i = j % 2 == 0 ? ii : us.size() - 2 - ii;
      Region reg;
      for (long r = r0; r < r1; ++r) {
        const double v = box.min().y() + r * spacing;
        if (v > box.max().y() + 1e-9) break;
        for (const auto& [a, b] : FreeIntervals(fps, v, us[i], us[i + 1])) {
          reg.pieces.push_back({r, v, a, b});
        }
      }
      if (!reg.pieces.empty()) out.push_back(std::move(reg));
    }
  }
  return out;
}

}  // namespace

std::optional<RasterSummary> WriteRasterProgram(const scene::Scene& scene, const RasterOptions& o,
                                                const program::Dialect& dialect, std::ostream& out,
                                                DiagnosticSink& sink) {
  using program::Axis;
  const SourceLocation where{scene.file.string(), 0, 0};
  const geom::Surface& surface = *scene.surface;
  if (!surface.IsHeightField() || !surface.CoversDomain()) {
    sink.Error("plan-raster-surface", where,
               "raster planning needs a height-field surface (plane or polynomial), not '" +
                   surface.Kind() + "'");
    return std::nullopt;
  }
  if (!(o.pitch_mm > 0) || !(o.row_spacing_mm > 0) || !(o.margin_mm >= 0) || o.heads < 1) {
    sink.Error("plan-raster-options", where,
               "pitch and row spacing must be positive, margin >= 0, heads >= 1");
    return std::nullopt;
  }
  std::vector<int> working;
  for (int h = 1; h <= o.heads; ++h) {
    if (std::find(o.out_of_service.begin(), o.out_of_service.end(), h) == o.out_of_service.end())
      working.push_back(h);
  }
  if (working.empty()) {
    sink.Error("plan-raster-no-head", where, "every head is out of service");
    return std::nullopt;
  }
  const geom::Domain2 dom = surface.Domain();
  Eigen::AlignedBox2d box(dom.min, dom.max);
  if (o.region) box = box.intersection(*o.region);
  box.min().array() += o.edge_margin_mm;
  box.max().array() -= o.edge_margin_mm;
  if (box.isEmpty() || box.sizes().minCoeff() <= 0) {
    sink.Error("plan-raster-empty-region", where, "the stitch region is empty");
    return std::nullopt;
  }
  // Stitches on the flat region (the surface adds slope, at most a few per cent here): a tiny
  // pitch must not write a programme that fills the disk.
  const double flat_stitches =
      (box.sizes().x() / o.pitch_mm + 1.0) * (box.sizes().y() / o.row_spacing_mm + 1.0);
  if (flat_stitches > static_cast<double>(limits::kMaxRasterStitches)) {
    sink.Error("plan-raster-too-many-stitches", where,
               "pitch " + Num(o.pitch_mm) + " mm and row spacing " + Num(o.row_spacing_mm) +
                   " mm over this region make about " + Num(flat_stitches) +
                   " stitches, more than the limit of " +
                   std::to_string(limits::kMaxRasterStitches) + " (docs/limits.md)");
    return std::nullopt;
  }

  // The needles pierce beside the tool point: grow the footprints by their spread on the
  // surface (through point plus the slant over the preform thickness).
  double spread_mm = 0.0;
  for (const scene::NeedleSpec& n : scene.head.needles) {
    const double slant = std::abs(n.direction.z()) > 1e-9
                             ? n.direction.head<2>().norm() / std::abs(n.direction.z())
                             : 0.0;
    spread_mm =
        std::max(spread_mm, n.through_mm.head<2>().norm() + slant * scene.preform_thickness_mm);
  }
  // The head beside the needles (presser foot, needle housing: the head spec's envelope)
  // must stay clear of the constraints too, also while it turns in place at a row end.
  const double keep_out_mm =
      std::max(spread_mm, scene.head.envelope ? scene.head.envelope->radius_mm : 0.0);
  const std::vector<scene::Footprint> fps =
      scene::ConstraintFootprints(scene, o.margin_mm + keep_out_mm);
  // Constraint heights above the surface: what a retracted head must clear.
  double tallest_mm = 0.0;
  for (const scene::Constraint& c : scene.constraints) {
    const double h = HeightAboveSurface(c, surface);
    if (scene.head.envelope && h >= scene.head.envelope->height_mm) {
      sink.Error("plan-raster-constraint-too-tall", c.where,
                 "constraint '" + c.name + "' rises " + Num(h) +
                     " mm above the surface, not below the head's envelope height (" +
                     Num(scene.head.envelope->height_mm) +
                     " mm): the stitching unit above it would hit it beside the stitches");
      return std::nullopt;
    }
    tallest_mm = std::max(tallest_mm, h);
  }
  // A jump or a move between bays is flown at least this high above the surface: the
  // tallest constraint plus RasterOptions::lift_clearance_mm.
  const double lift_clear_mm = tallest_mm + o.lift_clearance_mm;
  const RowStepper stepper(surface, o.pitch_mm);
  std::vector<Region> regions = o.strategy == RasterStrategy::kJump
                                    ? JumpRegions(fps, box, o.row_spacing_mm)
                                    : BayRegions(fps, box, o.row_spacing_mm);
  // Stitches per region: the header declares the total (verify's program.stitch_count), and
  // regions go to heads in contiguous runs of nearly equal stitch count.
  long total = 0;
  for (Region& r : regions) {
    for (const RowPiece& p : r.pieces) r.stitches += stepper.Count(p.u_begin, p.u_end, p.v);
    total += r.stitches;
  }
  std::vector<std::vector<std::size_t>> per_head(working.size());
  {
    long acc = 0;
    std::size_t h = 0;
    for (std::size_t i = 0; i < regions.size(); ++i) {
      // Move on when this region's middle is past the head's share.
      while (h + 1 < working.size() &&
             static_cast<double>(acc) + 0.5 * static_cast<double>(regions[i].stitches) >
                 static_cast<double>(total) * static_cast<double>(h + 1) /
                     static_cast<double>(working.size())) {
        ++h;
      }
      per_head[h].push_back(i);
      acc += regions[i].stitches;
    }
  }

  const auto& st = scene.head.stitch;
  const double feed_mm_min = st.stitch_rate_per_min * o.pitch_mm;
  const double stitch_time_s = 60.0 / st.stitch_rate_per_min;

  RasterSummary sum;
  sum.head_stitches.assign(static_cast<std::size_t>(o.heads), 0);
  program::ProgramWriter w(out, dialect);
  program::ProgramHeader header;
  header.entries = {{"scene", scene.name},
                    {"head", scene.head.name},
                    {"raster", std::string(ToString(o.strategy))},
                    {"stitch_length_mm", Num(o.pitch_mm)},
                    {"row_spacing_mm", Num(o.row_spacing_mm)},
                    {"heads", std::to_string(o.heads)},
                    {"stitches", std::to_string(total)}};
  program::Block b;
  detail::WriteOpening(w, b, dialect, header, scene.head.tool_number);
  detail::PoseWords pose_words(dialect);
  auto frame = [&](double u, double v, double dir) {
    const Eigen::Vector2d uv(u, v);
    const Eigen::Vector3d t = dir * surface.Jacobian(uv).col(0);
    return geom::FrameFromNormalAndDirection(surface.Normal(uv), t)
        .value_or(Eigen::Matrix3d::Identity());
  };
  auto emit_user = [&](UserCodeBlock::Event ev) {
    for (const UserCodeBlock& u : o.library.blocks) {
      if (u.event != ev) continue;
      b.Clear();
      b.m_codes = u.m_codes;
      b.param = u.param;
      w.Write(b);
      ++sum.user_blocks;
    }
  };
  auto m_line = [&](std::initializer_list<int> codes) {
    b.Clear();
    b.m_codes = codes;
    w.Write(b);
  };

  double drive = 0.0;    // U = V: stitched length so far
  double row_dir = 1.0;  // direction of the next row stitched (+u / -u)
  bool have_pos = false, stitching = false;
  Eigen::Vector3d pos = Eigen::Vector3d::Zero();
  bool feed_written = false;
  // Move to the start of a piece: needles out; retract if the straight path crosses a
  // footprint or `force_retract`.
  auto transit = [&](const Eigen::Vector3d& to, const Eigen::Matrix3d& r, bool force_retract,
                     double turn_sign) {
    bool crosses = force_retract;
    if (have_pos && !crosses) {
      for (const scene::Footprint& f : fps) {
        if (f.Crosses(pos.head<2>(), to.head<2>())) {
          crosses = true;
          break;
        }
      }
    }
    const bool retract = have_pos && crosses;
    if (stitching) {
      m_line({dialect.m.stitch_off});
      stitching = false;
    }
    auto rapid = [&](const Eigen::Vector3d& p, const Eigen::Matrix3d& rot) {
      b.Clear();
      b.motion = program::Motion::kRapid;
      pose_words.Set(b, p, rot);
      b[Axis::kDrive] = drive;
      b[Axis::kPathLength] = drive;
      w.Write(b);
      ++sum.motion_lines;
    };
    // A half turn (the row direction reverses) in two quarter turns about the tool z axis,
    // alternating sense, so the wrist unwinds instead of winding up and the interpolation
    // between the end orientations is never ambiguous.
    auto quarter_turn_at = [&](const Eigen::Vector3d& p) {
      if (have_pos && geom::AngleBetween(pose_words.Rotation(), r) > 0.5 * 3.14159265358979323846) {
        rapid(p, pose_words.Rotation() * Eigen::AngleAxisd(0.5 * turn_sign * 3.14159265358979323846,
                                                           Eigen::Vector3d::UnitZ())
                                             .toRotationMatrix());
      }
    };
    if (retract) {
      emit_user(UserCodeBlock::Event::kBeforeJump);
      m_line({dialect.m.head_retract});
      ++sum.jumps;
      sum.traverse_s += kRetractLowerS;
      // Up along the normals, across, down.
      const Eigen::Vector3d na = pose_words.Rotation().col(2), nb = r.col(2);
      const double lift = FlightLift(surface, pos, na, to, nb, lift_clear_mm);
      const Eigen::Vector3d up = pos + lift * na, over = to + lift * nb;
      rapid(up, pose_words.Rotation());
      quarter_turn_at(up);
      rapid(over, r);
      rapid(to, r);
      sum.traverse_s += (2 * lift + (over - up).norm()) / kTraverseMmPerMin * 60.0;
      m_line({dialect.m.head_lower});
    } else {
      if (have_pos) ++sum.turns;
      quarter_turn_at(pos);
      rapid(to, r);
      if (have_pos) sum.traverse_s += (to - pos).norm() / kTraverseMmPerMin * 60.0;
    }
    pos = to;
    have_pos = true;
  };

  for (std::size_t hi = 0; hi < working.size(); ++hi) {
    const int head = working[hi];
    if (per_head[hi].empty()) continue;
    if (working.size() > 1 || o.heads > 1) {
      if (stitching) {
        m_line({dialect.m.stitch_off});
        stitching = false;
      }
      b.Clear();
      b.m_codes = {dialect.m.head_section};
      b.param = head;
      b.comment = "head " + std::to_string(head);
      w.Write(b);
    }
    bool first_in_head = true;
    for (std::size_t ri : per_head[hi]) {
      const Region& reg = regions[ri];
      ++sum.bays;
      bool first_in_region = true;
      long prev_row = -1;
      // Rows alternate direction in the order they are stitched; the pieces of a row are
      // taken in its direction (a reversed row runs its pieces last to first).
      for (std::size_t g = 0; g < reg.pieces.size();) {
        std::size_t g_end = g;
        while (g_end < reg.pieces.size() && reg.pieces[g_end].row == reg.pieces[g].row) ++g_end;
        long stitchable = 0;
        for (std::size_t k = g; k < g_end && stitchable == 0; ++k) {
          stitchable =
              stepper.Count(reg.pieces[k].u_begin, reg.pieces[k].u_end, reg.pieces[k].v, row_dir);
        }
        if (stitchable == 0) {
          g = g_end;
          continue;
        }
        const double dir = row_dir;
        row_dir = -row_dir;
        for (std::size_t k = 0; k < g_end - g; ++k) {
          const RowPiece& piece = reg.pieces[dir > 0 ? g + k : g_end - 1 - k];
          // Whole stitches from the piece's start end (the start end depends on direction).
          const long n = stepper.Count(piece.u_begin, piece.u_end, piece.v, dir);
          if (n == 0) continue;
          double u = dir > 0 ? piece.u_begin : piece.u_end;
          const Eigen::Matrix3d r = frame(u, piece.v, dir);
          // Jump: pieces of one row are separated by a constraint; serpentine: new bay.
          const bool force_retract =
              (o.strategy == RasterStrategy::kSerpentine && first_in_region && !first_in_head) ||
              (prev_row == piece.row);
          transit(surface.Point({u, piece.v}), r, force_retract, -dir);
          first_in_head = false;
          first_in_region = false;
          if (prev_row != piece.row) {
            ++sum.rows;
            emit_user(UserCodeBlock::Event::kRowStart);
          }
          prev_row = piece.row;
          m_line({dialect.m.stitch_on});
          stitching = true;
          for (long k = 0; k < n; ++k) {
            const double next = stepper.Next(u, piece.v, dir);
            drive += o.pitch_mm;
            const Eigen::Vector3d p = surface.Point({next, piece.v});
            b.Clear();
            b.motion = program::Motion::kFeed;
            pose_words.Set(b, p, frame(next, piece.v, dir));
            b[Axis::kDrive] = drive;
            b[Axis::kPathLength] = drive;
            if (!feed_written) b.feed = feed_mm_min;
            feed_written = true;
            w.Write(b);
            ++sum.motion_lines;
            ++sum.stitches;
            ++sum.head_stitches[static_cast<std::size_t>(head - 1)];
            sum.stitching_s += stitch_time_s;
            pos = p;
            u = next;
            for (const UserCodeBlock& ub : o.library.blocks) {
              if (ub.event == UserCodeBlock::Event::kEveryStitches &&
                  sum.stitches % ub.every_stitches == 0) {
                b.Clear();
                b.m_codes = ub.m_codes;
                b.param = ub.param;
                w.Write(b);
                ++sum.user_blocks;
              }
            }
          }
        }
        g = g_end;
      }
    }
  }
  if (stitching) m_line({dialect.m.stitch_off});
  detail::WriteEnding(w, b, dialect);
  return sum;
}

}  // namespace stitchsim::planner
