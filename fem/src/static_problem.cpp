#include "ddafrac/fem/static_problem.hpp"

#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>
#include <deal.II/lac/full_matrix.h>

#include <cmath>
#include <map>
#include <optional>
#include <tuple>

#include "model.hpp"

namespace ddafrac::fem {

using dealii::types::boundary_id;
using dealii::types::global_dof_index;
using detail::Model;
using detail::Point;

struct StaticSolution::Impl {
  std::unique_ptr<Model> model;
  detail::Vec u;     // ghosted
  detail::Vec load;  // applied nodal forces
  std::map<std::string, std::array<double, 2>> applied;
  RunStats stats;
};

namespace {

constexpr double half_pi = 1.5707963267948966;

/// Makes the load orthogonal to the rigid-body modes (removes the discrete imbalance of a
/// self-equilibrated load, so that pinning the rigid modes costs no reaction).
void remove_rigid_components(const Model& model, detail::Vec& f) {
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

/// A DoF offered by one rank with the key that ranks it, and the DoF of the other component
/// at the same node.
struct Candidate {
  double key = 0.0;
  Point position;
  global_dof_index dof = 0, sibling = 0;
};

/// The candidate with the smallest key over all ranks; ties are broken by position, not by DoF
/// number, so that every partition picks the same node.
Candidate first_over_ranks(const std::optional<Candidate>& mine) {
  std::vector<double> offer;
  if (mine)
    offer = {mine->key, mine->position[0], mine->position[1], static_cast<double>(mine->dof),
             static_cast<double>(mine->sibling)};
  std::optional<Candidate> best;
  for (const auto& o : dealii::Utilities::MPI::all_gather(MPI_COMM_WORLD, offer)) {
    if (o.empty()) continue;
    const Candidate c{o[0], Point(o[1], o[2]), static_cast<global_dof_index>(o[3]),
                      static_cast<global_dof_index>(o[4])};
    if (!best ||
        std::tie(c.key, c.position[0], c.position[1]) < std::tie(best->key, best->position[0], best->position[1]))
      best = c;
  }
  if (!best) throw FemError("no node to pin");
  return *best;
}

/// The y DoF among `dofs` (locally relevant) with the smallest key(position), over all ranks.
template <class Key>
Candidate first_y_dof(const Model& model, const std::vector<global_dof_index>& dofs, const Key& key) {
  std::optional<Candidate> mine;
  for (const auto i : dofs) {
    if (model.dof_component(i) != 1) continue;
    const Candidate c{key(model.dof_point(i)), model.dof_point(i), i, model.sibling(i)};
    if (!mine ||
        std::tie(c.key, c.position[0], c.position[1]) < std::tie(mine->key, mine->position[0], mine->position[1]))
      mine = c;
  }
  return first_over_ranks(mine);
}

/// Constrains a DoF to zero on the ranks that see it.
void fix(const Model& model, global_dof_index i, detail::Constraints& constraints) {
  if (model.relevant().is_element(i)) constraints.add_line(i);
}

std::vector<global_dof_index> owned_dofs(const Model& model) {
  std::vector<global_dof_index> out;
  model.owned().fill_index_vector(out);
  return out;
}

/// Pins the three rigid-body modes: both components of the node nearest the centre, and the
/// y component of the node farthest from it in x.
void pin_rigid_modes(const Model& model, detail::Constraints& constraints) {
  const auto owned = owned_dofs(model);
  const Candidate centre = first_y_dof(model, owned, [](const Point& p) { return p.norm(); });
  const double xc = centre.position[0];
  const Candidate far = first_y_dof(model, owned, [xc](const Point& p) { return -std::abs(p[0] - xc); });
  for (const global_dof_index i : {centre.sibling, centre.dof, far.dof}) fix(model, i, constraints);
}

std::array<double, 2> resultant(const Model& model, const detail::Vec& f) {
  std::array<double, 2> sum{0.0, 0.0};
  for (const auto i : model.owned()) sum[model.dof_component(i)] += f[i];
  detail::sum_over_ranks(sum.data(), sum.size());
  return sum;
}

}  // namespace

StaticSolution solve_static(const StaticProblem& problem) {
  dealii::Timer timer;
  auto impl = std::make_unique<StaticSolution::Impl>();
  impl->model = std::make_unique<Model>(problem.mesh, problem.material, problem.discretisation);
  const Model& model = *impl->model;
  detail::Constraints constraints(model.relevant());
  detail::Vec load = model.make_vector();

  // Applies a pressure on the faces of the groups, remembering each group's resultant.
  auto apply = [&](double pressure, const std::vector<std::string>& groups, const Model::FaceSelector& extra) {
    for (const auto& group : groups) {
      const boundary_id id = model.require_boundary(group);
      detail::Vec part = model.make_vector();
      model.add_pressure(
          pressure, [&](const Point& q, boundary_id b) { return b == id ? extra(q, b) : 0.0; }, part);
      impl->applied[group] = resultant(model, part);
      load += part;
    }
  };
  const auto everywhere = [](const Point&, boundary_id) { return 1.0; };

  if (const auto* arc = std::get_if<ArcPressure>(&problem.load)) {
    if (model.boundary_id("load_top") && model.boundary_id("load_bottom")) {
      apply(arc->pressure, {"load_top", "load_bottom"}, everywhere);
    } else {
      const double half_angle = arc->half_angle;
      apply(arc->pressure, {"rim"}, [half_angle](const Point& q, boundary_id) {
        const bool on_arc = std::abs(half_pi - std::abs(std::atan2(q[1], q[0]))) < half_angle;
        return on_arc ? 1.0 : 0.0;
      });
    }
    remove_rigid_components(model, load);
    pin_rigid_modes(model, constraints);
  } else {
    const auto& flat = std::get<FlatLoad>(problem.load);
    const auto bottom = model.boundary_dofs(model.require_boundary("flat_bottom"), 1);
    for (const auto i : bottom) fix(model, i, constraints);
    // The x dof of the bottom node nearest x = 0.
    fix(model, first_y_dof(model, bottom, [](const Point& p) { return std::abs(p[0]); }).sibling, constraints);
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
  detail::Vec rhs = model.make_vector();
  model.assemble(constraints, stiffness, nullptr, &rhs);
  detail::Vec free_load = load;  // the load on the unconstrained DoFs
  for (const auto i : model.owned())
    if (constraints.is_constrained(i)) free_load[i] = 0.0;
  free_load.compress(dealii::VectorOperation::insert);
  rhs += free_load;
  const detail::ElasticSolver solver(stiffness, model, problem.solver);
  impl->stats.setup_seconds = timer.wall_time();
  impl->stats.solver = detail::ElasticSolver::name;

  timer.restart();
  detail::Vec x = model.make_vector();
  impl->stats.iterations = solver.solve(x, rhs);
  constraints.distribute(x);
  impl->u = model.ghosted(x);
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
  const auto probe = impl_->model->probes({Point(x, y)}).front();
  if (!probe) throw FemError("point (" + std::to_string(x) + ", " + std::to_string(y) + ") is outside the FEM body");
  return make_sample(x, y, impl_->model->stresses(impl_->u, {*probe}).front());
}

std::vector<StressSample> StaticSolution::profile(double x0, double y0, double x1, double y1, int n) const {
  if (n < 2) throw FemError("a profile needs at least two points");
  std::vector<Point> points;
  for (int i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) / (n - 1);
    points.emplace_back(x0 + t * (x1 - x0), y0 + t * (y1 - y0));
  }
  const auto found = impl_->model->probes(points);
  std::vector<Point> inside;
  std::vector<Model::Probe> probes;
  for (std::size_t k = 0; k < points.size(); ++k)
    if (found[k]) {
      inside.push_back(points[k]);
      probes.push_back(*found[k]);
    }
  const auto stresses = impl_->model->stresses(impl_->u, probes);
  std::vector<StressSample> out;
  for (std::size_t k = 0; k < inside.size(); ++k) out.push_back(make_sample(inside[k][0], inside[k][1], stresses[k]));
  return out;
}

std::array<double, 2> StaticSolution::boundary_force(const std::string& group) const {
  const Model& model = *impl_->model;
  const auto internal = model.internal_force(impl_->u);
  std::array<double, 2> sum{0.0, 0.0};
  for (const auto i : model.boundary_dofs(model.require_boundary(group), -1))
    if (model.owned().is_element(i)) sum[model.dof_component(i)] += internal[i] - impl_->load[i];
  detail::sum_over_ranks(sum.data(), sum.size());
  return sum;
}

std::array<double, 2> StaticSolution::applied_force(const std::string& group) const {
  const auto it = impl_->applied.find(group);
  return it == impl_->applied.end() ? std::array<double, 2>{0.0, 0.0} : it->second;
}

void StaticSolution::write_vtu(const std::filesystem::path& record) const {
  impl_->model->write_vtu(impl_->u, record.parent_path(), record.stem().string());
}

const RunStats& StaticSolution::stats() const { return impl_->stats; }

}  // namespace ddafrac::fem
