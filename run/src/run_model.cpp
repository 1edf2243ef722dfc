#include "stitchsim/run/run_model.h"

#include "stitchsim/run/status.h"

namespace stitchsim::run {
sim::TimingOptions TimingOptionsFor(const program::Dialect& dialect,
                                    const sim::ExecuteOptions& execute) {
  sim::TimingOptions t;
  t.law.ramp_time_s = dialect.trajectory.ramp_time_s;
  t.law.continuous = dialect.trajectory.continuous;
  t.law.look_ahead_lines = dialect.trajectory.look_ahead_lines;
  t.settle_time_s = execute.settle_time_s;
  return t;
}

namespace {

// The MuJoCo prototype; with dynamics, the cell must have a servo for every joint.
std::unique_ptr<sim::MujocoCell> MakeMujoco(const RunModel& m, DiagnosticSink& sink) {
  BoundedDiagnosticSink diagnostics(20);
  auto cell = sim::MujocoCell::Create(*m.loaded.scene, *m.loaded.robot, m.cell, diagnostics);
  if (Forward(diagnostics, sink) || !cell) return nullptr;
  if (m.dynamics && !cell->HasServos()) {
    ToolError(sink, "mujoco-model",
              "--dynamics: " + m.loaded.scene->cell_mjcf.string() +
                  " lacks a servo actuator (servo_<joint>) for every joint");
    return nullptr;
  }
  return cell;
}

}  // namespace

verify::RuleContext RunModel::Rules() const {
  verify::RuleContext ctx{loaded.scene.get(), &description, process.get()};
  ctx.declared_stitches = declared_stitches;
  ctx.ramp_time_s = dialect.trajectory.ramp_time_s;
  return ctx;
}

std::unique_ptr<RunModel> MakeRunModel(LoadedScene loaded, const program::Dialect& dialect,
                                       double stitch_length_mm,
                                       std::optional<long> declared_stitches,
                                       const RunOptions& options, DiagnosticSink& sink) {
  auto m = std::make_unique<RunModel>();
  m->loaded = std::move(loaded);
  m->dialect = dialect;
  m->stitch_length_mm = stitch_length_mm;
  m->declared_stitches = declared_stitches;
  m->dynamics = options.dynamics;
  const scene::Scene& scene = *m->loaded.scene;
  m->cell = sim::MakeCellSetup(*m->loaded.robot, scene);
  m->process =
      std::make_unique<process::ProcessModel>(process::MakeProcessModel(scene, stitch_length_mm));
  if (!options.no_collision) {
    BoundedDiagnosticSink world_diagnostics(20);
    m->collision = sim::CollisionWorld::Create(scene, *m->loaded.robot, world_diagnostics);
    if (Forward(world_diagnostics, sink) || !m->collision) return nullptr;
  }
  m->mujoco = MakeMujoco(*m, sink);
  if (!m->mujoco) return nullptr;
  m->description = sim::DescribeCell(*m->loaded.robot, m->collision.get());
  m->description.timed = true;
  m->description.dynamic = options.dynamics;
  m->execute = sim::ExecuteOptionsFor(scene);
  m->execute.allow_head_mismatch = options.allow_mismatch;
  m->execute.solve_every_sample = options.dynamics;
  m->timing = TimingOptionsFor(dialect, m->execute);
  return m;
}

RunData MakeRunData(const RunModel& model) {
  RunData d;
  d.kinematics = model.mujoco->Share();
  d.timing = model.mujoco->Share();
  if (model.dynamics) {
    d.physics = model.mujoco->Share();
    d.physics_poses = model.mujoco->Share();
  }
  if (model.collision) {
    d.collision = model.collision->Share();
    d.collision->UseKinematics(d.kinematics.get());
  }
  d.execute = model.execute;
  d.execute.collision = d.collision.get();
  d.execute.mujoco = d.kinematics.get();
  return d;
}

}  // namespace stitchsim::run
