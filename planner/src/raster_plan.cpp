// The raster plan (docs/raster.md): rows cut at the constraint footprints into regions (jump:
// one per row; serpentine: one per bay), regions split among the working heads, and the
// passes over them with the transits between.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "detail/raster_rows.h"
#include "stitchsim/common/limits.h"
#include "stitchsim/common/units.h"
#include "stitchsim/planner/raster_planner.h"

namespace stitchsim::planner {
namespace {

using detail::Num;

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

// Height of a point above the surface: on a height field z minus the surface height at its
// (x, y), clamped into the domain; otherwise its signed distance from its closest point.
double Above(const geom::Surface& s, const Eigen::Vector3d& p) {
  if (!s.IsHeightField()) return s.Project(p).signed_distance_mm;
  const geom::Domain2 dom = s.Domain();
  return p.z() - s.Point(p.head<2>().cwiseMax(dom.min).cwiseMin(dom.max)).z();
}

// Height of a constraint's top above the surface: the largest over its corners (box) or
// vertices (mesh).
double ConstraintHeightAboveSurface(const scene::Constraint& c, const geom::Surface& s) {
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

// The rows' v. A height field: v0 + k * spacing (the spacing in y). Otherwise the rows are
// `spacing` apart on the surface: each the exact 3D chord of one spacing from the one before,
// along the iso-u line through the middle of the stitch region.
class RowGrid {
 public:
  RowGrid(const geom::Surface& s, const Eigen::AlignedBox2d& box, double spacing)
      : v0_(box.min().y()), spacing_(spacing) {
    if (s.IsHeightField()) {
      rows_ = static_cast<long>(std::floor(box.sizes().y() / spacing + 1e-9)) + 1;
      return;
    }
    const double u = box.center().x();
    for (double v = v0_; v <= box.max().y() + 1e-9;) {
      vs_.push_back(v);
      const double next = NextV(s, u, v);
      // A degenerate iso-line (no progress) or more rows than a programme may have: stop.
      if (!(next > v) || vs_.size() > static_cast<std::size_t>(limits::kMaxRasterStitches)) break;
      v = next;
    }
    rows_ = static_cast<long>(vs_.size());
  }
  long Rows() const { return rows_; }
  /// v of row r; +infinity past the last row of a surface-spaced grid.
  double V(long r) const {
    if (vs_.empty()) return v0_ + r * spacing_;
    return r < rows_ ? vs_[static_cast<std::size_t>(r)] : std::numeric_limits<double>::infinity();
  }
  /// The first row at or above v.
  long FirstAtOrAbove(double v) const {
    if (vs_.empty()) return static_cast<long>(std::ceil((v - v0_) / spacing_ - 1e-9));
    return static_cast<long>(std::lower_bound(vs_.begin(), vs_.end(), v - 1e-9 * spacing_) -
                             vs_.begin());
  }

 private:
  // v of the point one spacing (3D chord) beyond (u, v) along +v.
  double NextV(const geom::Surface& s, double u, double v) const {
    const Eigen::Vector3d p = s.Point({u, v});
    double dv = spacing_ / std::max(s.Jacobian({u, v}).col(1).norm(), 1e-9);
    for (int it = 0; it < 4; ++it) {
      const double d = (s.Point({u, v + dv}) - p).norm();
      if (d <= 0) break;
      dv *= spacing_ / d;
    }
    return v + dv;
  }

  double v0_ = 0.0;
  double spacing_ = 1.0;
  long rows_ = 0;
  std::vector<double> vs_;  // empty on a height field
};

std::vector<RasterRegion> JumpRegions(const std::vector<scene::Footprint>& fps,
                                      const Eigen::AlignedBox2d& box, const RowGrid& grid) {
  std::vector<RasterRegion> out;
  for (long r = 0; r < grid.Rows(); ++r) {
    const double v = grid.V(r);
    RasterRegion reg;
    for (const auto& [a, b] : FreeIntervals(fps, v, box.min().x(), box.max().x())) {
      reg.pieces.push_back({r, v, a, b});
    }
    if (!reg.pieces.empty()) out.push_back(std::move(reg));
  }
  return out;
}

// Bays: the grid cut at every footprint's u and v edges; cells ordered band by band (v),
// snaking along u.
std::vector<RasterRegion> BayRegions(const std::vector<scene::Footprint>& fps,
                                     const Eigen::AlignedBox2d& box, const RowGrid& grid) {
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
  std::vector<RasterRegion> out;
  for (std::size_t j = 0; j + 1 < vs.size(); ++j) {
    const long r0 = grid.FirstAtOrAbove(vs[j]);
    const long r1 = grid.FirstAtOrAbove(vs[j + 1]);
    for (std::size_t ii = 0; ii + 1 < us.size(); ++ii) {
      const std::size_t i = j % 2 == 0 ? ii : us.size() - 2 - ii;
      RasterRegion reg;
      for (long r = r0; r < r1; ++r) {
        const double v = grid.V(r);
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

// The (u, v) box to stitch, the working heads, and the options checked; nullopt (reported)
// when raster planning cannot start.
struct Setup {
  Eigen::AlignedBox2d box;
  std::vector<int> working;  // 1-based head numbers in service
};

std::optional<Setup> CheckSetup(const scene::Scene& scene, const RasterOptions& o,
                                DiagnosticSink& sink) {
  const SourceLocation where{scene.file.string(), 0, 0};
  const geom::Surface& surface = *scene.surface;
  if (!surface.CoversDomain()) {
    sink.Error("plan-raster-surface", where,
               "raster planning needs a surface that covers its (u, v) domain, not '" +
                   surface.Kind() + "'");
    return std::nullopt;
  }
  if (!(o.pitch_mm > 0) || !(o.row_spacing_mm > 0) || !(o.margin_mm >= 0) || o.heads < 1) {
    sink.Error("plan-raster-options", where,
               "pitch and row spacing must be positive, margin >= 0, heads >= 1");
    return std::nullopt;
  }
  Setup s;
  for (int h = 1; h <= o.heads; ++h) {
    if (std::find(o.out_of_service.begin(), o.out_of_service.end(), h) == o.out_of_service.end())
      s.working.push_back(h);
  }
  if (s.working.empty()) {
    sink.Error("plan-raster-no-head", where, "every head is out of service");
    return std::nullopt;
  }
  const geom::Domain2 dom = surface.Domain();
  s.box = Eigen::AlignedBox2d(dom.min, dom.max);
  if (o.region) s.box = s.box.intersection(*o.region);
  s.box.min().array() += o.edge_margin_mm;
  s.box.max().array() -= o.edge_margin_mm;
  if (s.box.isEmpty() || s.box.sizes().minCoeff() <= 0) {
    sink.Error("plan-raster-empty-region", where, "the stitch region is empty");
    return std::nullopt;
  }
  // Stitches on the flat region (the surface adds slope, at most a few per cent here): a tiny
  // pitch must not write a programme that fills the disk.
  const double flat_stitches =
      (s.box.sizes().x() / o.pitch_mm + 1.0) * (s.box.sizes().y() / o.row_spacing_mm + 1.0);
  if (flat_stitches > static_cast<double>(limits::kMaxRasterStitches)) {
    sink.Error("plan-raster-too-many-stitches", where,
               "pitch " + Num(o.pitch_mm) + " mm and row spacing " + Num(o.row_spacing_mm) +
                   " mm over this region make about " + Num(flat_stitches) +
                   " stitches, more than the limit of " +
                   std::to_string(limits::kMaxRasterStitches) + " (docs/limits.md)");
    return std::nullopt;
  }
  return s;
}

// How far from the tool point the head must keep off a constraint: the larger of the needles'
// spread on the surface (through point plus the slant over the preform thickness) and the
// head spec's envelope radius (presser foot, needle housing; also while it turns in place).
double KeepOutMm(const scene::Scene& scene) {
  double spread_mm = 0.0;
  for (const scene::NeedleSpec& n : scene.head.needles) {
    const double slant = std::abs(n.direction.z()) > 1e-9
                             ? n.direction.head<2>().norm() / std::abs(n.direction.z())
                             : 0.0;
    spread_mm =
        std::max(spread_mm, n.through_mm.head<2>().norm() + slant * scene.preform_thickness_mm);
  }
  return std::max(spread_mm, scene.head.envelope ? scene.head.envelope->radius_mm : 0.0);
}

// The constraints' footprints in the surface's (u, v), grown by `grow_mm`; nullopt (reported
// at the constraint) when one does not project onto the surface.
std::optional<std::vector<scene::Footprint>> Footprints(const scene::Scene& scene, double grow_mm,
                                                        DiagnosticSink& sink) {
  std::vector<scene::Footprint> out;
  for (const scene::Constraint& c : scene.constraints) {
    std::string error;
    std::optional<scene::Footprint> f =
        scene::ConstraintFootprintOn(c, *scene.surface, grow_mm, error);
    if (!f) {
      sink.Error("plan-raster-footprint", c.where,
                 "constraint '" + c.name + "' does not project onto the surface: " + error);
      return std::nullopt;
    }
    out.push_back(std::move(*f));
  }
  return out;
}

// The tallest constraint's height above the surface (what a retracted head must clear);
// nullopt (reported) when one reaches the head's envelope height.
std::optional<double> TallestConstraintMm(const scene::Scene& scene, DiagnosticSink& sink) {
  double tallest_mm = 0.0;
  for (const scene::Constraint& c : scene.constraints) {
    const double h = ConstraintHeightAboveSurface(c, *scene.surface);
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
  return tallest_mm;
}

// Regions go to the working heads in contiguous runs of nearly equal stitch count: a head
// moves on when a region's middle is past its share. Region indices per working head.
std::vector<std::vector<std::size_t>> SplitAmongHeads(const std::vector<RasterRegion>& regions,
                                                      long total, std::size_t heads) {
  std::vector<std::vector<std::size_t>> per_head(heads);
  long acc = 0;
  std::size_t h = 0;
  for (std::size_t i = 0; i < regions.size(); ++i) {
    while (h + 1 < heads &&
           static_cast<double>(acc) + 0.5 * static_cast<double>(regions[i].stitches) >
               static_cast<double>(total) * static_cast<double>(h + 1) /
                   static_cast<double>(heads)) {
      ++h;
    }
    per_head[h].push_back(i);
    acc += regions[i].stitches;
  }
  return per_head;
}

// Walks the passes in programme order, deciding each transit from where the head is.
class PassBuilder {
 public:
  PassBuilder(const geom::Surface& surface, const RasterPlan& plan)
      : surface_(surface), plan_(plan), stepper_(surface, plan.pitch_mm) {}

  // The passes over one region, appended to `out`. Rows alternate direction in the order
  // they are stitched; the pieces of a row are taken in its direction (a reversed row runs
  // its pieces last to first).
  void Region(const RasterRegion& reg, bool first_in_head, std::vector<RasterPass>& out) {
    bool first_in_region = true;
    long prev_row = -1;
    for (std::size_t g = 0; g < reg.pieces.size();) {
      std::size_t g_end = g;
      while (g_end < reg.pieces.size() && reg.pieces[g_end].row == reg.pieces[g].row) ++g_end;
      long stitchable = 0;
      for (std::size_t k = g; k < g_end && stitchable == 0; ++k) {
        const RasterRowPiece& p = reg.pieces[k];
        stitchable = stepper_.Count(p.u_begin_mm, p.u_end_mm, p.v_mm, row_dir_);
      }
      if (stitchable == 0) {
        g = g_end;
        continue;
      }
      const double dir = row_dir_;
      row_dir_ = -row_dir_;
      for (std::size_t k = 0; k < g_end - g; ++k) {
        const RasterRowPiece& piece = reg.pieces[dir > 0 ? g + k : g_end - 1 - k];
        RasterPass pass;
        pass.piece = piece;
        pass.direction = dir;
        double u_last = 0.0;
        pass.stitches = stepper_.Count(piece.u_begin_mm, piece.u_end_mm, piece.v_mm, dir, &u_last);
        if (pass.stitches == 0) continue;
        // Jump: pieces of one row are separated by a constraint; serpentine: a new bay.
        const bool force_retract =
            (plan_.strategy == RasterStrategy::kSerpentine && first_in_region && !first_in_head) ||
            prev_row == piece.row;
        pass.transit = TransitTo(pass, force_retract);
        first_in_head = false;
        first_in_region = false;
        pass.row_start = prev_row != piece.row;
        prev_row = piece.row;
        // Where the head is after the pass: its last stitch.
        pos_uv_ = {u_last, piece.v_mm};
        pos_ = surface_.Point(pos_uv_);
        rotation_ = detail::StitchFrame(surface_, u_last, piece.v_mm, dir);
        have_pos_ = true;
        out.push_back(pass);
      }
      g = g_end;
    }
  }

 private:
  // Retract when the straight path crosses a footprint or `force_retract`.
  std::optional<RasterTransit> TransitTo(const RasterPass& pass, bool force_retract) const {
    if (!have_pos_) return std::nullopt;
    const double u = pass.direction > 0 ? pass.piece.u_begin_mm : pass.piece.u_end_mm;
    const Eigen::Vector3d to = surface_.Point({u, pass.piece.v_mm});
    const Eigen::Matrix3d r = detail::StitchFrame(surface_, u, pass.piece.v_mm, pass.direction);
    RasterTransit t;
    t.jump = force_retract;
    for (std::size_t i = 0; i < plan_.footprints.size() && !t.jump; ++i) {
      t.jump = Crosses(plan_.footprints[i], pos_uv_, {u, pass.piece.v_mm});
    }
    if (t.jump) {
      t.lift_mm =
          FlightLift(surface_, pos_, rotation_.col(2), to, r.col(2), plan_.flight_clearance_mm);
    }
    t.quarter_turn = geom::AngleBetween(rotation_, r) > 0.5 * kPi;
    t.turn_sign = -pass.direction;
    return t;
  }

  // Off a height field a move that only grazes a footprint's edge (a row end at a bay edge to
  // the next row's start there) does not cross it: the (u, v) footprints are not axis-exact, and
  // the exact slab test would retract on rounding. A height field keeps the exact test.
  bool Crosses(const scene::Footprint& f, const Eigen::Vector2d& a,
               const Eigen::Vector2d& b) const {
    if (surface_.IsHeightField()) return f.Crosses(a, b);
    return f.SegmentDepth(a, b) > kGrazeMm;
  }
  static constexpr double kGrazeMm = 1e-6;

  const geom::Surface& surface_;
  const RasterPlan& plan_;
  const detail::RowStepper stepper_;
  double row_dir_ = 1.0;  // direction of the next row stitched (+u / -u)
  bool have_pos_ = false;
  Eigen::Vector3d pos_ = Eigen::Vector3d::Zero();           // last stitch
  Eigen::Vector2d pos_uv_ = Eigen::Vector2d::Zero();        // its (u, v)
  Eigen::Matrix3d rotation_ = Eigen::Matrix3d::Identity();  // its tool frame
};

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

std::optional<RasterPlan> PlanRaster(const scene::Scene& scene, const RasterOptions& o,
                                     DiagnosticSink& sink) {
  const std::optional<Setup> setup = CheckSetup(scene, o, sink);
  if (!setup) return std::nullopt;
  RasterPlan plan;
  plan.strategy = o.strategy;
  plan.pitch_mm = o.pitch_mm;
  plan.row_spacing_mm = o.row_spacing_mm;
  plan.heads = o.heads;
  plan.head_sections = setup->working.size() > 1 || o.heads > 1;
  plan.library = o.library;
  std::optional<std::vector<scene::Footprint>> footprints =
      Footprints(scene, o.margin_mm + KeepOutMm(scene), sink);
  if (!footprints) return std::nullopt;
  plan.footprints = std::move(*footprints);
  const std::optional<double> tallest_mm = TallestConstraintMm(scene, sink);
  if (!tallest_mm) return std::nullopt;
  plan.flight_clearance_mm = *tallest_mm + o.lift_clearance_mm;
  const RowGrid grid(*scene.surface, setup->box, o.row_spacing_mm);
  plan.regions = o.strategy == RasterStrategy::kJump
                     ? JumpRegions(plan.footprints, setup->box, grid)
                     : BayRegions(plan.footprints, setup->box, grid);
  for (const RasterRegion& r : plan.regions) plan.row_pieces += std::ssize(r.pieces);
  double rows_done = 0.0;
  const auto report = [&](const RasterRegion& r, double share) {
    if (!o.progress) return;
    rows_done += share * static_cast<double>(r.pieces.size());
    o.progress(rows_done, static_cast<double>(plan.row_pieces));
  };
  // Stitches per region: the header declares the total (verify's program.stitch_count).
  const detail::RowStepper stepper(*scene.surface, o.pitch_mm);
  for (RasterRegion& r : plan.regions) {
    for (const RasterRowPiece& p : r.pieces)
      r.stitches += stepper.Count(p.u_begin_mm, p.u_end_mm, p.v_mm);
    plan.stitches += r.stitches;
    report(r, detail::kProgressCountShare);
  }
  const auto per_head = SplitAmongHeads(plan.regions, plan.stitches, setup->working.size());
  PassBuilder passes(*scene.surface, plan);
  for (std::size_t hi = 0; hi < setup->working.size(); ++hi) {
    if (per_head[hi].empty()) continue;
    RasterSection section;
    section.head = setup->working[hi];
    section.regions = per_head[hi].size();
    for (std::size_t ri : per_head[hi]) {
      passes.Region(plan.regions[ri], section.passes.empty(), section.passes);
      report(plan.regions[ri], detail::kProgressPassShare);
    }
    plan.sections.push_back(std::move(section));
  }
  return plan;
}

}  // namespace stitchsim::planner
