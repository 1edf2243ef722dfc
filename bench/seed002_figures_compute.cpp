// Seed 002's figures (see seed002_figures.h). The wing: the paper starts from a curve on the
// leading edge and places 790 points in the section nearest the root, 300.6 cm of offsets,
// more than one side of the root section (about 230 cm): here the offsets go both ways from
// the leading edge, 395 over the upper skin and 394 over the lower, and the 790 points are
// the root ends of the curves (lower skin, leading edge, upper skin).
#include <cmath>
#include <ctime>
#include <memory>

#include "seed002_figures.h"
#include "stitchsim/common/diagnostics.h"
#include "stitchsim/common/units.h"
#include "stitchsim/planner/laminate_family.h"
#include "stitchsim/planner/offset_curves.h"
#include "stitchsim/scene/scene.h"

namespace stitchsim::bench {
namespace {

using planner::FiberAxis;
using planner::OffsetFamily;
using planner::OffsetMethod;

// The axis from `a` to `b`, projected along `v`, sampled to `tol_mm`; offset `count` times.
struct Run {
  OffsetFamily family;
  planner::ReferenceCurve reference;
  double seconds = 0.0;
};
Run Offsets(const geom::Surface& s, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
            const Eigen::Vector3d& v, double tol_mm, double d, int count, OffsetMethod m) {
  FiberAxis axis;
  axis.start_mm = a;
  axis.end_mm = b;
  axis.projection = v;
  Run r;
  r.reference = planner::ProjectFiberAxis(s, axis, tol_mm);
  if (!r.reference.ok) return r;
  planner::OffsetOptions o;
  o.distance_mm = d;
  o.count = count;
  o.method = m;
  const std::clock_t t0 = std::clock();  // CPU time: this machine's wall clock is shared
  r.family = planner::OffsetCurves(s, r.reference.points, o);
  r.seconds = static_cast<double>(std::clock() - t0) / CLOCKS_PER_SEC;
  return r;
}

bool Failed(Seed002Figures& f, const Run& r, const std::string& what) {
  if (r.reference.ok && r.family.ok) return false;
  f.message = what + ": " + (r.reference.ok ? r.family.message : r.reference.message);
  return true;
}

DriftFigures Drift(const geom::Surface& s, const Run& r, double d, std::size_t index) {
  const planner::OffsetDrift drift = planner::MeasureDrift(s, r.family, d, index);
  return {drift.surface_length_mm, drift.drift_mm, drift.eq2_total_mm, r.seconds};
}

bool Circle(Seed002Figures& f) {
  constexpr double d = 6.35;
  const auto cylinder = geom::MakeCylinder(2 * d, true, 100, 4 * kPi * d - 1);
  const Run r =
      Offsets(*cylinder, {-20, 0, 50}, {20, 0, 50}, {0, 0, -1}, 0.01, d, 6, OffsetMethod::kPaper);
  if (Failed(f, r, "circle of radius 2d")) return false;
  const std::size_t j = r.family.curves[0].size() / 2;
  f.circle_measured_per_step_d = (d - r.family.steps[0].surface_distance_mm[j]) / d;
  f.circle_eq2_per_step_d = r.family.steps[0].eq2_error_mm[j] / d;
  return true;
}

bool WingFamily(Seed002Figures& f, const geom::Surface& wing, OffsetMethod m, DriftFigures& out) {
  // The leading edge (x = 0, z = 0 with no sweep, dihedral or twist) from 100 mm to 3100 mm
  // out from the root: inboard, where the chord still holds 395 offsets each way.
  const double d = f.wing_d_mm;
  const Eigen::Vector3d root(-200, f.wing_station_y_mm, 0), outboard(-200, 3100, 0);
  const Eigen::Vector3d aft(1, 0, 0);
  // Root to tip: N x T = (-x) x (+y) = -z, the lower skin; tip to root: the upper.
  const Run lower = Offsets(wing, root, outboard, aft, 0.01, d, f.wing_offsets_lower, m);
  const Run upper = Offsets(wing, outboard, root, aft, 0.01, d, f.wing_offsets_upper, m);
  if (Failed(f, lower, "wing, lower skin") || Failed(f, upper, "wing, upper skin")) return false;
  f.wing_points_per_curve = static_cast<int>(lower.reference.points.size());
  const DriftFigures a = Drift(wing, lower, d, 0);
  const DriftFigures b = Drift(wing, upper, d, upper.reference.points.size() - 1);
  out.surface_length_mm = a.surface_length_mm + b.surface_length_mm;
  out.drift_mm = a.drift_mm + b.drift_mm;
  out.eq2_total_mm = a.eq2_total_mm + b.eq2_total_mm;
  out.seconds = a.seconds + b.seconds;
  return true;
}

bool WingFigures(Seed002Figures& f, const std::filesystem::path& scene_file) {
  DiagnosticSink sink;
  const std::unique_ptr<scene::Scene> scene = scene::LoadScene(scene_file, sink);
  if (!scene) {
    f.message = scene_file.string() + " does not load";
    for (const auto& diag : sink.Diagnostics()) f.message += "\n" + FormatDiagnostic(diag);
    return false;
  }
  f.wing_offsets_upper = 395;
  f.wing_offsets_lower = 394;
  f.wing_station_y_mm = 100;
  f.wing_nominal_mm = f.wing_d_mm * (f.wing_offsets_upper + f.wing_offsets_lower);
  return WingFamily(f, *scene->surface, OffsetMethod::kPaper, f.wing_paper) &&
         WingFamily(f, *scene->surface, OffsetMethod::kCorrected, f.wing_corrected);
}

// A clockwise arc of radius r about the origin, +30 to -30 deg, a point every ~1 mm: its
// N x T points outwards, so its offsets are the circles r + k d.
planner::SurfaceCurve ClockwiseArc(double r) {
  planner::SurfaceCurve c;
  const int n = static_cast<int>(r * 60 * kDeg);
  for (int k = 0; k <= n; ++k) {
    const double phi = (30.0 - 60.0 * k / n) * kDeg;
    planner::CurvePoint p;
    p.position = Eigen::Vector3d(r * std::cos(phi), r * std::sin(phi), 0);
    p.uv = p.position.head<2>();
    p.tangent = Eigen::Vector3d(std::sin(phi), -std::cos(phi), 0);
    c.push_back(p);
  }
  return c;
}

bool Laminate(Seed002Figures& f) {
  constexpr double r = 635, d = 6.35, theta = 30 * kDeg;
  const auto plane = geom::MakePlane(3000, 3000);
  planner::OffsetOptions o;
  o.distance_mm = d;
  o.count = 12;
  const OffsetFamily family = planner::OffsetCurves(*plane, ClockwiseArc(r), o);
  if (!family.ok) {
    f.message = "laminate offsets: " + family.message;
    return false;
  }
  f.eq4_deg = planner::LaminateAngleError(r, d, theta) / kDeg;
  for (const bool corrected : {false, true}) {
    planner::LaminateOptions lo;
    lo.theta_rad = theta;
    lo.corrected = corrected;
    const planner::LaminateCurve l = planner::LaminateFamilyCurve(*plane, family.curves, 60, lo);
    if (!l.ok || l.crossings.size() < 2) {
      f.message = "laminate curve: " + l.message;
      return false;
    }
    double worst = 0.0;
    for (const auto& c : l.crossings) worst = std::max(worst, std::abs(c.crossing_rad - theta));
    if (corrected) {
      f.laminate_corrected_worst_deg = worst / kDeg;
    } else {
      f.laminate_paper_deg = (theta - l.crossings[1].arrive_rad) / kDeg;
      f.laminate_paper_worst_deg = worst / kDeg;
    }
  }
  return true;
}

bool Inflected(Seed002Figures& f) {
  Eigen::Matrix4d c = Eigen::Matrix4d::Zero();
  c(0, 3) = 0.05;  // z = y^3 / 20
  geom::Domain2 dom;
  dom.min = Eigen::Vector2d(-5, -12);
  dom.max = Eigen::Vector2d(5, 12);
  const auto surface = geom::MakePolynomialHeightField(c, dom);
  constexpr double d = 0.150;
  for (const OffsetMethod m : {OffsetMethod::kPaper, OffsetMethod::kCorrected}) {
    const Run r = Offsets(*surface, {-2, -3.5, 50}, {2, -3.5, 50}, {0, 0, -1}, 0.001, d, 124, m);
    if (Failed(f, r, "inflected surface")) return false;
    (m == OffsetMethod::kPaper ? f.inflected_paper : f.inflected_corrected) =
        Drift(*surface, r, d, 0);
  }
  return true;
}

}  // namespace

Seed002Figures ComputeSeed002Figures(const std::filesystem::path& naca_wing_scene) {
  Seed002Figures f;
  f.ok = Circle(f) && WingFigures(f, naca_wing_scene) && Laminate(f) && Inflected(f);
  return f;
}

}  // namespace stitchsim::bench
