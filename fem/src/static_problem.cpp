#include "ddafrac/fem/static_problem.hpp"

#include <deal.II/base/timer.h>
#include <deal.II/lac/full_matrix.h>

#include <cmath>
#include <map>
#include <optional>

#include "model.hpp"

namespace ddafrac::fem {

using dealii::types::boundary_id;
using dealii::types::global_dof_index;
using detail::Model;

struct StaticSolution::Impl {
  std::unique_ptr<Model> model;
  dealii::Vector<double> u;
  dealii::Vector<double> load;  // applied nodal forces
  std::map<std::string, std::array<double, 2>> applied;
  RunStats stats;
};

namespace {

constexpr double half_pi = 1.5707963267948966;

/// Makes the load orthogonal to the rigid-body modes (removes the discrete imbalance of a
/// self-equilibrated load, so that pinning the rigid modes costs no reaction).
void remove_rigid_components(const Model& model, dealii::Vector<double>& f) {
  const auto modes = model.rigid_modes();
  dealii::FullMatrix<double> gram(3, 3), inverse(3, 3);
  dealii::Vector<double> projection(3), coefficients(3);
  for (unsigned int a = 0; a < 3; ++a) {
    projection[a] = modes[a] * f;
    for (unsigned int b = 0; b < 3; ++b) gram(a, b) = modes[a] * modes[b];
  }
  inverse.invert(gram);
  inverse.vmult(coefficients, projection);
  for (unsigned int a = 0; a < 3; ++a) f.add(-coefficients[a], modes[a]);
}

/// Pins the three rigid-body modes: both components of the node nearest the centre, and the
/// y component of the node farthest from it in x.
void pin_rigid_modes(const Model& model, detail::Constraints& constraints) {
  // Ties are broken by position, not by DoF number, so that every partition pins the same nodes.
  const auto& points = model.dof_points();
  auto before = [&](global_dof_index a, global_dof_index b, double ka, double kb) {
    if (ka != kb) return ka < kb;
    return points[a][0] != points[b][0] ? points[a][0] < points[b][0] : points[a][1] < points[b][1];
  };
  std::optional<global_dof_index> centre, far;
  for (global_dof_index i = 0; i < points.size(); ++i) {
    if (model.dof_component(i) != 1) continue;
    if (!centre || before(i, *centre, points[i].norm(), points[*centre].norm())) centre = i;
  }
  const double xc = points[*centre][0];
  for (global_dof_index i = 0; i < points.size(); ++i) {
    if (model.dof_component(i) != 1) continue;
    if (!far || before(i, *far, -std::abs(points[i][0] - xc), -std::abs(points[*far][0] - xc))) far = i;
  }
  for (const global_dof_index i : {model.sibling(*centre), *centre, *far}) constraints.add_line(i);
}

std::array<double, 2> resultant(const Model& model, const dealii::Vector<double>& f) {
  std::array<double, 2> sum{0.0, 0.0};
  for (global_dof_index i = 0; i < f.size(); ++i) sum[model.dof_component(i)] += f[i];
  return sum;
}

}  // namespace

StaticSolution solve_static(const StaticProblem& problem) {
  dealii::Timer timer;
  auto impl = std::make_unique<StaticSolution::Impl>();
  impl->model = std::make_unique<Model>(problem.mesh, problem.material, problem.discretisation);
  const Model& model = *impl->model;
  detail::Constraints constraints;
  dealii::Vector<double> load(model.n_dofs());

  // Applies a pressure on the faces of the groups, remembering each group's resultant.
  auto apply = [&](double pressure, const std::vector<std::string>& groups, const Model::FaceSelector& extra) {
    for (const auto& group : groups) {
      const boundary_id id = model.require_boundary(group);
      dealii::Vector<double> part(model.n_dofs());
      model.add_pressure(
          pressure, [&](const detail::Point& q, boundary_id b) { return b == id ? extra(q, b) : 0.0; }, part);
      impl->applied[group] = resultant(model, part);
      load += part;
    }
  };
  const auto everywhere = [](const detail::Point&, boundary_id) { return 1.0; };

  if (const auto* arc = std::get_if<ArcPressure>(&problem.load)) {
    if (model.boundary_id("load_top") && model.boundary_id("load_bottom")) {
      apply(arc->pressure, {"load_top", "load_bottom"}, everywhere);
    } else {
      const double half_angle = arc->half_angle;
      apply(arc->pressure, {"rim"}, [half_angle](const detail::Point& q, boundary_id) {
        const bool on_arc = std::abs(half_pi - std::abs(std::atan2(q[1], q[0]))) < half_angle;
        return on_arc ? 1.0 : 0.0;
      });
    }
    remove_rigid_components(model, load);
    pin_rigid_modes(model, constraints);
  } else {
    const auto& flat = std::get<FlatLoad>(problem.load);
    const auto bottom = model.boundary_dofs(model.require_boundary("flat_bottom"), 1);
    const auto& points = model.dof_points();
    global_dof_index pin = model.sibling(bottom.front());  // x dof of the bottom node nearest x = 0
    for (const auto i : bottom) {
      constraints.add_line(i);
      const double xi = std::abs(points[i][0]), xp = std::abs(points[pin][0]);
      if (xi < xp || (xi == xp && points[i][0] < points[pin][0])) pin = model.sibling(i);
    }
    constraints.add_line(pin);
    if (flat.displacement > 0.0) {
      for (const auto i : model.boundary_dofs(model.require_boundary("flat_top"), 1)) {
        constraints.add_line(i);
        constraints.set_inhomogeneity(i, -flat.displacement);
      }
    } else {
      apply(flat.pressure, {"flat_top"}, everywhere);
    }
  }
  constraints.close();

  detail::Matrix stiffness;
  model.make_sparse_matrix(stiffness, constraints);
  dealii::Vector<double> rhs(model.n_dofs());
  model.assemble(constraints, stiffness, nullptr, &rhs);
  for (global_dof_index i = 0; i < rhs.size(); ++i)
    if (!constraints.is_constrained(i)) rhs[i] += load[i];
  const detail::ElasticSolver solver(stiffness, model, problem.solver);
  impl->stats.setup_seconds = timer.wall_time();
  impl->stats.solver = detail::ElasticSolver::name;

  timer.restart();
  detail::Vec x = model.make_vector();
  impl->stats.iterations = solver.solve(x, detail::to_trilinos(rhs, model));
  impl->u = detail::to_serial(x);
  constraints.distribute(impl->u);
  impl->stats.solve_seconds = timer.wall_time();
  impl->stats.cells = model.n_cells();
  impl->stats.dofs = model.n_dofs();
  impl->load = std::move(load);
  return StaticSolution(std::move(impl));
}

StaticSolution::StaticSolution(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
StaticSolution::StaticSolution(StaticSolution&&) noexcept = default;
StaticSolution& StaticSolution::operator=(StaticSolution&&) noexcept = default;
StaticSolution::~StaticSolution() = default;

StressSample StaticSolution::stress_at(double x, double y) const {
  const auto s = impl_->model->stress_at(impl_->u, detail::Point(x, y));
  if (!s) throw FemError("point (" + std::to_string(x) + ", " + std::to_string(y) + ") is outside the FEM body");
  return make_sample(x, y, *s);
}

std::vector<StressSample> StaticSolution::profile(double x0, double y0, double x1, double y1, int n) const {
  if (n < 2) throw FemError("a profile needs at least two points");
  std::vector<StressSample> out;
  for (int i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) / (n - 1);
    const double x = x0 + t * (x1 - x0), y = y0 + t * (y1 - y0);
    if (const auto s = impl_->model->stress_at(impl_->u, detail::Point(x, y))) out.push_back(make_sample(x, y, *s));
  }
  return out;
}

std::array<double, 2> StaticSolution::boundary_force(const std::string& group) const {
  const Model& model = *impl_->model;
  const auto internal = model.internal_force(impl_->u);
  std::array<double, 2> sum{0.0, 0.0};
  for (const auto i : model.boundary_dofs(model.require_boundary(group), -1))
    sum[model.dof_component(i)] += internal[i] - impl_->load[i];
  return sum;
}

std::array<double, 2> StaticSolution::applied_force(const std::string& group) const {
  const auto it = impl_->applied.find(group);
  return it == impl_->applied.end() ? std::array<double, 2>{0.0, 0.0} : it->second;
}

void StaticSolution::write_vtu(const std::filesystem::path& path) const { impl_->model->write_vtu(impl_->u, path); }

const RunStats& StaticSolution::stats() const { return impl_->stats; }

}  // namespace ddafrac::fem
