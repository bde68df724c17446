#include "ddafrac/fem/dynamic_problem.hpp"

#include <deal.II/base/timer.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "ddafrac/common/pvd.hpp"
#include "ddafrac/common/whole_file.hpp"

#include "ddafrac/common/angles.hpp"
#include "model.hpp"
#include "step_solver.hpp"

namespace ddafrac::fem {

namespace {

// Output times are matched to steps to within this fraction of a step.
constexpr double step_rounding = 1e-9;
constexpr double pi = common::kPi;

/// Adds the wall time of its scope to a phase total (s).
class PhaseTimer {
 public:
  explicit PhaseTimer(double& total) : total_(total), start_(Clock::now()) {}
  ~PhaseTimer() { total_ += std::chrono::duration<double>(Clock::now() - start_).count(); }
  PhaseTimer(const PhaseTimer&) = delete;
  PhaseTimer& operator=(const PhaseTimer&) = delete;

 private:
  using Clock = std::chrono::steady_clock;
  double& total_;
  Clock::time_point start_;
};

std::string pvd_document(const std::vector<SnapshotRecord>& snapshots) {
  std::vector<common::PvdEntry> entries;
  for (const SnapshotRecord& snap : snapshots) entries.push_back({snap.t, snap.file});
  return common::pvd_document(entries);
}

double energy_of(const detail::Matrix& matrix, const detail::Vec& x, detail::Vec& scratch) {
  matrix.vmult(scratch, x);
  return 0.5 * (x * scratch);
}

const DynamicProblem& checked(const DynamicProblem& problem) {
  if (!(problem.dt > 0.0) || !(problem.end_time > 0.0)) throw FemError("dynamic FEM needs dt > 0 and end_time > 0");
  const double beta = problem.newmark.beta, gamma = problem.newmark.gamma;
  if (!(beta > 0.0) || gamma < 0.5) throw FemError("Newmark needs beta > 0 and gamma >= 1/2");
  if (problem.pulse && !(problem.pulse->duration > 0.0)) throw FemError("a traction pulse needs a duration > 0");
  return problem;
}

/// The Newmark time loop of one DynamicProblem, in the order of the method: constraints and
/// initial state, then K, M and the effective matrix K + c_u M with its solver (built once: the
/// matrix does not change at a fixed dt), then per step the right-hand side, the solve and the
/// update of a, v and u, with gauges, energies and snapshots recorded at their intervals.
/// The effective matrix is factorised (sparse Cholesky on one rank, MUMPS on more) so that a
/// step costs one product with M and two triangular solves.
class NewmarkRun {
 public:
  explicit NewmarkRun(const DynamicProblem& problem);
  DynamicResult run();

 private:
  void setup_system();
  void assemble_system();
  void build_solver();
  void assemble_rhs(double t);
  void solve();
  void update();
  void record(double t);
  void snapshot(double t);

  dealii::Timer timer_;
  const DynamicProblem& problem_;
  const detail::Model model_;
  const double dt_;  // s
  // a_new = c_u (u_new - u) - c_v v - c_a a, the Newmark relations solved for a_new.
  const double c_u_, c_v_, c_a_;
  detail::Constraints constraints_;
  detail::Matrix stiffness_, mass_, effective_;
  std::unique_ptr<detail::StepSolver> solver_;
  detail::Vec patch_load_;                    // N/m per Pa: nodal load of a unit pressure on the patch
  std::vector<detail::Model::Probe> gauges_;  // one per problem gauge, located once
  detail::Vec u_, v_, a_;                     // state carried between steps: m, m/s, m/s^2
  detail::Vec ghosted_u_, ghosted_v_;         // u and v with ghost entries, for sampling
  detail::Vec w_, rhs_, u_new_, scratch_;     // per-step scratch
  DynamicResult result_;
};

NewmarkRun::NewmarkRun(const DynamicProblem& problem)
    : problem_(checked(problem)),
      model_(problem.mesh, problem.material, problem.discretisation),
      dt_(problem.dt),
      c_u_(1.0 / (problem.newmark.beta * dt_ * dt_)),
      c_v_(1.0 / (problem.newmark.beta * dt_)),
      c_a_(0.5 / problem.newmark.beta - 1.0) {}

DynamicResult NewmarkRun::run() {
  result_.setup.model = timer_.wall_time();  // the model was built by the constructor
  {
    const PhaseTimer timing(result_.setup.assembly);
    setup_system();
    assemble_system();
  }
  build_solver();
  result_.stats.setup_seconds = timer_.wall_time();
  timer_.restart();

  const auto steps = static_cast<int>(std::ceil(problem_.end_time / dt_ - step_rounding));
  const auto every = std::max(1, static_cast<int>(std::lround(problem_.output_interval / dt_)));
  const bool snapshots = !problem_.snapshot_directory.empty() && problem_.snapshot_interval > 0.0;
  const auto every_snapshot = std::max(1, static_cast<int>(std::lround(problem_.snapshot_interval / dt_)));
  if (snapshots && detail::is_root()) std::filesystem::create_directories(problem_.snapshot_directory / "vtk");
  if (snapshots) MPI_Barrier(MPI_COMM_WORLD);  // every rank writes its piece there
  record(0.0);
  if (snapshots) snapshot(0.0);
  for (int n = 1; n <= steps; ++n) {
    assemble_rhs(n * dt_);
    solve();
    update();
    if (n % every == 0 || n == steps) record(n * dt_);
    if (snapshots && (n % every_snapshot == 0 || n == steps)) snapshot(n * dt_);
  }
  result_.steps = steps;
  result_.stats.solve_seconds = timer_.wall_time();
  result_.stats.cells = model_.n_cells();
  result_.stats.dofs = model_.n_dofs();
  return std::move(result_);
}

/// The held patch (u = 0 from t = 0) unless a pulse loads it; the initial rigid motion at v0
/// towards -y with the held patch at rest and no stress; the gauges located in the mesh.
void NewmarkRun::setup_system() {
  const auto patch = model_.require_boundary(problem_.held_group);
  constraints_.reinit(model_.relevant());
  if (!problem_.pulse)
    for (const auto i : model_.boundary_dofs(patch, -1)) constraints_.add_line(i);
  constraints_.close();

  patch_load_ = model_.make_vector();
  if (problem_.pulse)
    model_.add_pressure(
        1.0, [patch](const detail::Point&, dealii::types::boundary_id b) { return b == patch ? 1.0 : 0.0; },
        patch_load_);

  v_ = model_.make_vector();
  for (const auto i : model_.owned())
    if (model_.dof_component(i) == 1 && !constraints_.is_constrained(i)) v_[i] = -problem_.v0;
  v_.compress(dealii::VectorOperation::insert);
  std::vector<detail::Point> points;
  for (const auto& gauge : problem_.gauges) points.emplace_back(gauge.x, gauge.y);
  auto probes = model_.probes(points);
  for (std::size_t g = 0; g < probes.size(); ++g) {
    if (!probes[g]) throw FemError("gauge " + problem_.gauges[g].name + " is outside the FEM body");
    gauges_.push_back(std::move(*probes[g]));
  }
  for (auto* x : {&u_, &a_, &w_, &rhs_, &u_new_, &scratch_}) *x = model_.make_vector();
  for (auto* x : {&ghosted_u_, &ghosted_v_}) *x = model_.make_ghosted();
}

/// K and the consistent M with the constraints condensed, and the effective matrix of the
/// step, K + c_u M.
void NewmarkRun::assemble_system() {
  model_.make_sparse_matrix(stiffness_, constraints_);
  model_.make_sparse_matrix(mass_, constraints_);
  model_.assemble(constraints_, stiffness_, &mass_);
  effective_.copy_from(stiffness_);
  effective_.add(c_u_, mass_);
}

/// The solver of the effective matrix: factorised, or its AMG set up, once.
void NewmarkRun::build_solver() {
  const PhaseTimer timing(result_.setup.solver);
  solver_ = detail::make_step_solver(problem_.step_solver, effective_, model_, problem_.cg);
  result_.stats.solver = solver_->name();
}

/// (K + c_u M) u_new = M (c_u u + c_v v + c_a a) + f(t).
void NewmarkRun::assemble_rhs(double t) {
  const PhaseTimer timing(result_.times.rhs);
  const double *u = u_.begin(), *v = v_.begin(), *a = a_.begin();
  double* w = w_.begin();
  const std::ptrdiff_t owned = w_.end() - w_.begin();
  for (std::ptrdiff_t i = 0; i < owned; ++i) w[i] = c_u_ * u[i] + c_v_ * v[i] + c_a_ * a[i];
  mass_.vmult(rhs_, w_);
  if (problem_.pulse) rhs_.add(problem_.pulse->pressure(t), patch_load_);
}

void NewmarkRun::solve() {
  const PhaseTimer timing(result_.times.solve);
  result_.stats.iterations += solver_->solve(u_new_, rhs_);
}

/// a_new = c_u (u_new - u) - c_v v - c_a a;  v += dt ((1 - gamma) a + gamma a_new).
void NewmarkRun::update() {
  const PhaseTimer timing(result_.times.update);
  const double gamma = problem_.newmark.gamma;
  const double v_from_a = dt_ * (1.0 - gamma), v_from_a_new = dt_ * gamma;  // s
  const double* u_new = u_new_.begin();
  double *u = u_.begin(), *v = v_.begin(), *a = a_.begin();
  const std::ptrdiff_t owned = u_.end() - u_.begin();  // entry-wise: no communication
  for (std::ptrdiff_t i = 0; i < owned; ++i) {
    const double a_new = c_u_ * u_new[i] - c_u_ * u[i] - c_v_ * v[i] - c_a_ * a[i];
    v[i] = v[i] + v_from_a * a[i] + v_from_a_new * a_new;
    a[i] = a_new;
    u[i] = u_new[i];
  }
}

void NewmarkRun::record(double t) {
  {
    const PhaseTimer timing(result_.times.gauges);
    ghosted_u_ = u_;
    const auto stresses = model_.stresses(ghosted_u_, gauges_);
    for (std::size_t g = 0; g < gauges_.size(); ++g) {
      const auto& gauge = problem_.gauges[g];
      result_.gauges.push_back({t, g, make_sample(gauge.x, gauge.y, stresses[g])});
    }
  }
  const PhaseTimer timing(result_.times.energy);
  result_.energy.push_back({t, energy_of(mass_, v_, scratch_), energy_of(stiffness_, u_, scratch_)});
}

void NewmarkRun::snapshot(double t) {
  const PhaseTimer timing(result_.times.output);
  char stem[64];
  std::snprintf(stem, sizeof stem, "snapshot_%06zu", result_.snapshots.size());
  ghosted_u_ = u_;
  ghosted_v_ = v_;
  const auto record = model_.write_vtu(ghosted_u_, problem_.snapshot_directory / "vtk", stem, &ghosted_v_);
  result_.snapshots.push_back({t, "vtk/" + record});
  if (detail::is_root())
    common::write_whole_text(problem_.snapshot_directory / "run.pvd", pvd_document(result_.snapshots));
}

}  // namespace

double TractionPulse::pressure(double t) const {
  if (t < 0.0 || t > duration) return 0.0;
  return peak * std::sin(pi * t / duration);
}

DynamicResult run_dynamic(const DynamicProblem& problem) { return NewmarkRun(problem).run(); }

}  // namespace ddafrac::fem
