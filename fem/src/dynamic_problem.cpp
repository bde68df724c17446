#include "ddafrac/fem/dynamic_problem.hpp"

#include <deal.II/base/timer.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "ddafrac/common/whole_file.hpp"

#include "model.hpp"

namespace ddafrac::fem {

namespace {

// Output times are matched to steps to within this fraction of a step.
constexpr double step_rounding = 1e-9;
constexpr double pi = 3.14159265358979323846;

std::string pvd_document(const std::vector<SnapshotRecord>& snapshots) {
  std::string s =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      "  <Collection>\n";
  char line[256];
  for (const auto& snap : snapshots) {
    std::snprintf(line, sizeof line, "    <DataSet timestep=\"%.17g\" part=\"0\" file=\"%s\"/>\n",
                  snap.t, snap.file.c_str());
    s += line;
  }
  return s + "  </Collection>\n</VTKFile>\n";
}

double energy_of(const detail::Matrix& matrix, const detail::Vec& x, detail::Vec& scratch) {
  matrix.vmult(scratch, x);
  return 0.5 * (x * scratch);
}

}  // namespace

double TractionPulse::pressure(double t) const {
  if (t < 0.0 || t > duration) return 0.0;
  return peak * std::sin(pi * t / duration);
}

DynamicResult run_dynamic(const DynamicProblem& problem) {
  if (!(problem.dt > 0.0) || !(problem.end_time > 0.0))
    throw FemError("dynamic FEM needs dt > 0 and end_time > 0");
  const double beta = problem.newmark.beta, gamma = problem.newmark.gamma;
  if (!(beta > 0.0) || gamma < 0.5) throw FemError("Newmark needs beta > 0 and gamma >= 1/2");
  dealii::Timer timer;
  DynamicResult result;
  const detail::Model model(problem.mesh, problem.material, problem.discretisation);

  if (problem.pulse && !(problem.pulse->duration > 0.0))
    throw FemError("a traction pulse needs a duration > 0");
  const auto patch = model.require_boundary(problem.held_group);
  detail::Constraints constraints;
  if (!problem.pulse)
    for (const auto i : model.boundary_dofs(patch, -1)) constraints.add_line(i);
  constraints.close();
  // Nodal load of a unit pressure on the patch (the pulse scales it).
  dealii::Vector<double> unit_load(model.n_dofs());
  if (problem.pulse)
    model.add_pressure(
        1.0, [patch](const detail::Point&, dealii::types::boundary_id b) { return b == patch ? 1.0 : 0.0; },
        unit_load);
  const detail::Vec patch_load = detail::to_trilinos(unit_load, model);

  detail::Matrix stiffness, mass, effective;
  model.make_sparse_matrix(stiffness, constraints);
  model.make_sparse_matrix(mass, constraints);
  model.assemble(constraints, stiffness, &mass);
  const double dt = problem.dt;
  const double c_u = 1.0 / (beta * dt * dt), c_v = 1.0 / (beta * dt), c_a = 0.5 / beta - 1.0;
  effective.copy_from(stiffness);
  effective.add(c_u, mass);
  const detail::ElasticSolver solver(effective, model, problem.solver);

  // Initial state: rigid motion at v0 towards -y, the held patch at rest, no stress.
  dealii::Vector<double> v_initial(model.n_dofs());
  for (dealii::types::global_dof_index i = 0; i < model.n_dofs(); ++i)
    if (model.dof_component(i) == 1 && !constraints.is_constrained(i)) v_initial[i] = -problem.v0;
  detail::Vec u = model.make_vector(), a = model.make_vector(), w = model.make_vector();
  detail::Vec rhs = model.make_vector(), u_new = model.make_vector(), scratch = model.make_vector();
  detail::Vec v = detail::to_trilinos(v_initial, model);
  result.stats.setup_seconds = timer.wall_time();
  timer.restart();

  auto record = [&](double t) {
    const auto displacement = detail::to_serial(u);
    for (std::size_t g = 0; g < problem.gauges.size(); ++g) {
      const auto& gauge = problem.gauges[g];
      const auto s = model.stress_at(displacement, detail::Point(gauge.x, gauge.y));
      if (!s) throw FemError("gauge " + gauge.name + " is outside the FEM body");
      result.gauges.push_back({t, g, make_sample(gauge.x, gauge.y, *s)});
    }
    result.energy.push_back({t, energy_of(mass, v, scratch), energy_of(stiffness, u, scratch)});
  };

  const bool snapshots = !problem.snapshot_directory.empty() && problem.snapshot_interval > 0.0;
  if (snapshots && detail::is_root())
    std::filesystem::create_directories(problem.snapshot_directory / "vtk");
  auto snapshot = [&](double t) {
    char name[64];
    std::snprintf(name, sizeof name, "vtk/snapshot_%06zu.vtu", result.snapshots.size());
    result.snapshots.push_back({t, name});
    const auto displacement = detail::to_serial(u), velocity = detail::to_serial(v);
    model.write_vtu(displacement, problem.snapshot_directory / name, &velocity);
    if (detail::is_root())
      common::write_whole_text(problem.snapshot_directory / "run.pvd",
                               pvd_document(result.snapshots));
  };

  const auto steps = static_cast<int>(std::ceil(problem.end_time / dt - step_rounding));
  const auto every = std::max(1, static_cast<int>(std::lround(problem.output_interval / dt)));
  const auto every_snapshot =
      std::max(1, static_cast<int>(std::lround(problem.snapshot_interval / dt)));
  record(0.0);
  if (snapshots) snapshot(0.0);
  for (int n = 1; n <= steps; ++n) {
    // M (c_u u + c_v v + c_a a) = (K + c_u M) u_new
    w.equ(c_u, u);
    w.add(c_v, v);
    w.add(c_a, a);
    mass.vmult(rhs, w);
    if (problem.pulse) rhs.add(problem.pulse->pressure(n * dt), patch_load);
    u_new = u;
    result.stats.iterations += solver.solve(u_new, rhs);
    // a_new = c_u (u_new - u) - c_v v - c_a a;  v += dt ((1 - gamma) a + gamma a_new)
    w.equ(c_u, u_new);
    w.add(-c_u, u);
    w.add(-c_v, v);
    w.add(-c_a, a);
    v.add(dt * (1.0 - gamma), a);
    v.add(dt * gamma, w);
    a = w;
    u = u_new;
    if (n % every == 0 || n == steps) record(n * dt);
    if (snapshots && (n % every_snapshot == 0 || n == steps)) snapshot(n * dt);
  }
  result.steps = steps;
  result.stats.solve_seconds = timer.wall_time();
  result.stats.cells = model.n_cells();
  result.stats.dofs = model.n_dofs();
  return result;
}

}  // namespace ddafrac::fem
