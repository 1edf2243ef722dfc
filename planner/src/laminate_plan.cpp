// PlanLaminate: the stack's plies planned on the tool surface on several threads, same-angle
// references staggered, then each ply lifted onto the thickness the plies below it lay.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <ostream>
#include <sstream>
#include <thread>

#include "stitchsim/common/units.h"
#include "stitchsim/geom/surface_walk.h"
#include "stitchsim/planner/laminate_planner.h"

namespace stitchsim::planner {
namespace {

/// What one stack entry is planned from: its ply with the stagger shift applied.
struct LaminateJob {
  scene::PlySpec ply;
  LaminatePly out;
  std::optional<PlyPlan> plan;
  DiagnosticSink sink;
};

bool SameFibreAngle(double a_rad, double b_rad) {
  return std::abs(std::remainder(a_rad - b_rad, kPi)) < 1e-6;
}

/// `ply` with its reference moved `shift_mm` to the left of its fibre direction, in the
/// tangent plane at the origin's foot point. A geodesic or constant-angle reference starts at
/// the foot of the origin, so the foot itself moves; a projected one is the fibre axis through the
/// origin, so the origin moves (the axis keeps its height over the surface).
scene::PlySpec Shifted(const geom::Surface& surface, scene::PlySpec ply, double shift_mm) {
  if (shift_mm == 0.0) return ply;
  const geom::SurfaceProjection foot = surface.Project(ply.origin_mm);
  const Eigen::Vector3d n = foot.normal;
  const Eigen::Vector3d d =
      Eigen::AngleAxisd(ply.angle_rad, n) * geom::Tangential(ply.direction, n);
  const Eigen::Vector3d left = n.cross(d).normalized();
  const Eigen::Vector3d from =
      ply.reference_path == scene::ReferencePath::kProjected ? ply.origin_mm : foot.point;
  ply.origin_mm = from + shift_mm * left;
  return ply;
}

/// The jobs of the stack with their same-angle index and stagger shift; false (a diagnostic)
/// when the stagger rule cannot be kept.
bool StackJobs(const scene::Scene& scene, const scene::LaminateSpec& lam,
               std::vector<LaminateJob>& jobs, DiagnosticSink& sink) {
  const process::TowLayout layout = process::TowLayoutOf(scene.head);
  const int w = std::max(1, lam.stagger_plies_before_repeat);
  jobs = std::vector<LaminateJob>(lam.stack.size());
  for (std::size_t i = 0; i < lam.stack.size(); ++i) {
    const scene::PlySpec& ply = scene.plies[lam.stack[i].ply];
    LaminatePly& o = jobs[i].out;
    o.stack_index = i;
    o.scene_ply = lam.stack[i].ply;
    o.thickness_mm = ply.thickness_mm;
    o.course_width_mm = process::PlyTowBand(layout, ply.tows).count * layout.width_mm;
    for (std::size_t j = 0; j < i; ++j) {
      if (SameFibreAngle(scene.plies[lam.stack[j].ply].angle_rad, ply.angle_rad))
        ++o.same_angle_index;
    }
    const double step = o.course_width_mm / (w + 1);
    if (o.same_angle_index > 0 && step < lam.stagger_offset_mm) {
      char text[320];
      std::snprintf(text, sizeof(text),
                    "laminate '%s': ply '%s' repeats a fibre angle, and its course of %.4g mm "
                    "holds %d seam positions only %.4g mm apart, less than the stagger offset "
                    "%.4g mm (lower the offset or plies_before_repeat)",
                    lam.name.c_str(), ply.name.c_str(), o.course_width_mm, w + 1, step,
                    lam.stagger_offset_mm);
      sink.Error("plan-laminate-stagger", lam.where, text);
      return false;
    }
    o.stagger_shift_mm = (o.same_angle_index % (w + 1)) * step;
    jobs[i].ply = Shifted(*scene.surface, ply, o.stagger_shift_mm);
  }
  return true;
}

/// PlanPly over the jobs on `threads` threads; each job keeps its own diagnostics.
void PlanJobs(const scene::Scene& scene, std::vector<LaminateJob>& jobs,
              const LaminatePlanOptions& options, int threads) {
  std::atomic<std::size_t> next{0};
  std::mutex progress_mutex;
  double done = 0.0;
  auto work = [&] {
    PlyPlanOptions ply_options = options.ply;
    ply_options.progress = nullptr;
    for (std::size_t i = next++; i < jobs.size(); i = next++) {
      // Each ply on a thread of its own: an OpenCASCADE surface's projection starts from the
      // last answer on its thread (geom/src/occt_surface.cpp), so a ply planned after another
      // on one thread came out different in the sixth decimal, and the programme depended on
      // which worker took which ply. A fresh thread starts every ply from the same state.
      std::thread([&, i] {
        jobs[i].plan = PlanPly(scene, jobs[i].ply, ply_options, jobs[i].sink);
      }).join();
      if (options.progress) {
        const std::lock_guard<std::mutex> lock(progress_mutex);
        options.progress(++done, static_cast<double>(jobs.size()));
      }
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();
}

/// The (u, v) box of every tow edge of the plans (the field's extent), inside the domain.
geom::Domain2 LaidBox(const geom::Surface& surface, const std::vector<PlyPlan*>& plans) {
  geom::Domain2 box{Eigen::Vector2d::Constant(INFINITY), Eigen::Vector2d::Constant(-INFINITY)};
  for (const PlyPlan* plan : plans)
    for (const PlyCourse& c : plan->courses)
      for (const PlyPoint& p : c.points)
        for (const Eigen::Vector2d& b : p.boundary_uv) {
          box.min = box.min.cwiseMin(b);
          box.max = box.max.cwiseMax(b);
        }
  const geom::Domain2 domain = surface.Domain();
  box.min = box.min.cwiseMax(domain.min);
  box.max = box.max.cwiseMin(domain.max);
  return box;
}

/// Every pose and tow edge of `plan` moved along the surface normal at its foot by the
/// thickness below it: the roller's contact on the raised surface (an inclined head, whose tool
/// z leans from the normal, is not raised along its axis).
void LiftOnto(const geom::Surface& surface, const ThicknessField& below, PlyPlan& plan) {
  for (PlyCourse& c : plan.courses) {
    for (PlyPoint& p : c.points) {
      const Eigen::Vector3d z = p.tool.linear().col(2);
      auto up = [&](const Eigen::Vector2d& uv) {  // the normal on the head's side
        const Eigen::Vector3d n = surface.Normal(uv);
        return n.dot(z) < 0.0 ? Eigen::Vector3d(-n) : n;
      };
      p.tool.translation() += below.At(p.uv) * up(p.uv);
      for (std::size_t k = 0; k < p.boundary.size(); ++k)
        p.boundary[k] += below.At(p.boundary_uv[k]) * up(p.boundary_uv[k]);
    }
  }
}

}  // namespace

std::optional<LaminatePlan> PlanLaminate(const scene::Scene& scene,
                                         const scene::LaminateSpec& laminate,
                                         const LaminatePlanOptions& options, DiagnosticSink& sink) {
  if (scene.head.kind != scene::HeadKind::kAfp || scene.surface == nullptr) {
    sink.Error("plan-not-afp-head", laminate.where,
               "scene '" + scene.name + "' mounts head '" + scene.head.name + "', not an AFP head");
    return std::nullopt;
  }
  std::vector<LaminateJob> jobs;
  if (!StackJobs(scene, laminate, jobs, sink)) return std::nullopt;
  const int hardware = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const int threads = std::clamp(options.jobs > 0 ? options.jobs : hardware, 1,
                                 static_cast<int>(std::max<std::size_t>(1, jobs.size())));
  PlanJobs(scene, jobs, options, threads);
  bool ok = true;
  for (LaminateJob& j : jobs) {  // stack order, whatever thread planned it
    for (const Diagnostic& d : j.sink.Diagnostics()) sink.Report(d);
    ok = ok && j.plan.has_value();
  }
  if (!ok) return std::nullopt;

  LaminatePlan out;
  out.laminate = laminate.name;
  std::vector<PlyPlan*> plans;
  std::vector<double> thickness;
  for (LaminateJob& j : jobs) {
    plans.push_back(&*j.plan);
    thickness.push_back(j.out.thickness_mm);
  }
  const auto below = StackPlies(*scene.surface, plans, thickness, options.thickness_cell_mm,
                                &out.max_thickness_mm, &out.thickness_cell_mm);
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    LaminateJob& j = jobs[i];
    std::tie(j.out.below_min_mm, j.out.below_max_mm) = below[i];
    j.out.plan = std::move(*j.plan);
    const PlyPlan& p = j.out.plan;
    out.courses += static_cast<int>(p.courses.size());
    out.tow_segments += p.tow_segments;
    out.events += p.events;
    out.laid_length_mm += p.laid_length_mm;
    out.plies.push_back(std::move(j.out));
  }
  return out;
}

std::vector<std::pair<double, double>> StackPlies(const geom::Surface& surface,
                                                  const std::vector<PlyPlan*>& plans,
                                                  const std::vector<double>& thickness_mm,
                                                  double cell_mm, double* max_mm, double* cell) {
  ThicknessField field(LaidBox(surface, plans), cell_mm);
  std::vector<std::pair<double, double>> below;
  for (std::size_t i = 0; i < plans.size(); ++i) {
    LiftOnto(surface, field, *plans[i]);
    below.push_back(field.AddPly(*plans[i], thickness_mm[i]));
  }
  if (max_mm != nullptr) *max_mm = field.MaxMm();
  if (cell != nullptr) *cell = field.CellMm();
  return below;
}

void WriteLaminateProgram(const LaminatePlan& plan, const scene::Scene& scene,
                          const program::Dialect& dialect, std::ostream& out) {
  std::vector<const PlyPlan*> plies;
  for (const LaminatePly& p : plan.plies) plies.push_back(&p.plan);
  WritePlyProgram(plies, scene, dialect, out, plan.laminate);
}

void WriteLaminateTowsCsv(const LaminatePlan& plan, std::ostream& out) {
  std::string text;
  for (const LaminatePly& p : plan.plies) {
    std::ostringstream one;
    WritePlyTowsCsv(p.plan, one);
    std::istringstream rows(one.str());
    std::string row;
    std::getline(rows, row);  // the header, once
    if (text.empty()) text = "stack," + row + "\n";
    const std::string lead = std::to_string(p.stack_index + 1) + ",";
    while (std::getline(rows, row)) text += lead + row + "\n";
  }
  out << text;
}

}  // namespace stitchsim::planner
