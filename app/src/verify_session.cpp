#include "verify_session.h"

namespace stitchsim::app {
namespace {

std::optional<MujocoCells> MakeMujocoCells(const LoadedScene& ls, const sim::CellSetup& cell,
                                           bool dynamics) {
  BoundedDiagnosticSink diagnostics(20);
  MujocoCells cells;
  cells.kinematics = sim::MujocoCell::Create(*ls.scene, *ls.robot, cell, diagnostics);
  if (PrintDiagnostics(diagnostics) || !cells.kinematics) return std::nullopt;
  cells.timing = cells.kinematics->Share();
  if (dynamics) {
    if (!cells.kinematics->HasServos()) {
      PrintError("mujoco-model", "--dynamics: " + ls.scene->cell_mjcf.string() +
                                     " lacks a servo actuator (servo_<joint>) for every joint");
      return std::nullopt;
    }
    cells.physics = cells.kinematics->Share();
    cells.physics_poses = cells.kinematics->Share();
  }
  return cells;
}

sim::TimingOptions TimingOptionsFor(const program::Dialect& dialect,
                                    const sim::ExecuteOptions& execute) {
  sim::TimingOptions t;
  t.law.ramp_time_s = dialect.trajectory.ramp_time_s;
  t.law.continuous = dialect.trajectory.continuous;
  t.law.look_ahead_lines = dialect.trajectory.look_ahead_lines;
  t.settle_time_s = execute.settle_time_s;
  return t;
}

}  // namespace

verify::RuleContext VerifySession::Rules() const {
  verify::RuleContext ctx{ls.scene.get(), &description, model.get()};
  ctx.declared_stitches = declared_stitches;
  return ctx;
}

std::unique_ptr<VerifySession> MakeSession(LoadedScene ls, const program::Dialect& dialect,
                                           double stitch_length_mm,
                                           std::optional<long> declared_stitches,
                                           const SessionOptions& options) {
  auto s = std::make_unique<VerifySession>();
  s->ls = std::move(ls);
  s->dialect = dialect;
  s->stitch_length_mm = stitch_length_mm;
  s->declared_stitches = declared_stitches;
  const scene::Scene& scene = *s->ls.scene;
  s->cell = sim::MakeCellSetup(*s->ls.robot, scene);
  s->model =
      std::make_unique<process::ProcessModel>(process::MakeProcessModel(scene, stitch_length_mm));
  if (!options.no_collision) {
    BoundedDiagnosticSink world_diagnostics(20);
    s->collision = sim::CollisionWorld::Create(scene, *s->ls.robot, world_diagnostics);
    if (PrintDiagnostics(world_diagnostics) || !s->collision) return nullptr;
  }
  std::optional<MujocoCells> mj = MakeMujocoCells(s->ls, s->cell, options.dynamics);
  if (!mj) return nullptr;
  s->mj = std::move(*mj);
  if (s->collision) s->collision->UseKinematics(s->mj.kinematics.get());
  s->description = sim::DescribeCell(*s->ls.robot, s->collision.get());
  s->description.timed = true;
  s->description.dynamic = options.dynamics;
  s->execute = sim::ExecuteOptionsFor(scene);
  s->execute.collision = s->collision.get();
  s->execute.allow_head_mismatch = options.allow_mismatch;
  s->execute.mujoco = s->mj.kinematics.get();
  s->execute.solve_every_sample = options.dynamics;
  s->timing = TimingOptionsFor(dialect, s->execute);
  return s;
}

}  // namespace stitchsim::app
