#include "model.hpp"

#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_reordering.h>
#include <deal.II/grid/manifold_lib.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/data_postprocessor.h>

#include <Teuchos_ParameterList.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>

#include <limits>
#include "ddafrac/common/whole_file.hpp"

namespace ddafrac::fem::detail {
namespace {

using BoundaryId = dealii::types::boundary_id;
using dealii::types::global_dof_index;

constexpr dealii::types::manifold_id rim_manifold = 1;
constexpr BoundaryId unnamed_boundary = 0;  // boundary faces of no named group
// Boundary groups that lie on the circle of the disc (centre at the origin).
constexpr std::array<const char*, 4> curved_groups{"rim", "load_top", "load_bottom", "impact_patch"};
// Newton on the geometry map: unit-coordinate step below which it has converged.
constexpr double newton_tolerance = 1e-13;
constexpr int newton_max_iterations = 30;
// A point belongs to a cell if its unit coordinates are inside within this tolerance; a point
// just outside the (polygonal, degree 1) boundary is extrapolated from the nearest cell if it
// is within `extrapolation_tolerance` (unit coordinates).
constexpr double inside_tolerance = 1e-9;
constexpr double extrapolation_tolerance = 0.05;
constexpr int ml_smoother_sweeps = 2;
constexpr unsigned int partial_face_copies = 32;
constexpr double ml_aggregation_threshold = 0.02;

struct Lame {
  double lambda;  // effective lambda of the plane model
  double mu;
};

Lame lame(const Material& m) {
  const double e = m.elastic.young, nu = m.elastic.poisson;
  const double mu = e / (2.0 * (1.0 + nu));
  if (m.plane == PlaneModel::Strain) return {e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)), mu};
  return {e * nu / (1.0 - nu * nu), mu};
}

Stress2 stress_of(const Lame& l, const dealii::Tensor<2, dim>& grad_u) {
  const double exx = grad_u[0][0], eyy = grad_u[1][1];
  const double gxy = grad_u[0][1] + grad_u[1][0];
  const double trace = exx + eyy;
  return {l.lambda * trace + 2.0 * l.mu * exx, l.lambda * trace + 2.0 * l.mu * eyy, l.mu * gxy};
}

bool is_curved_group(const std::string& name) {
  return std::find(curved_groups.begin(), curved_groups.end(), name) != curved_groups.end();
}

/// How far (unit coordinates) a point lies outside the reference cell; 0 inside.
double outside_distance(const Point& u, bool simplex) {
  if (simplex) return std::max({0.0, -u[0], -u[1], u[0] + u[1] - 1.0});
  return std::max({0.0, -u[0], -u[1], u[0] - 1.0, u[1] - 1.0});
}

class StressPostprocessor : public dealii::DataPostprocessor<dim> {
 public:
  explicit StressPostprocessor(const Lame& l) : lame_(l) {}
  void evaluate_vector_field(const dealii::DataPostprocessorInputs::Vector<dim>& in,
                             std::vector<dealii::Vector<double>>& out) const override {
    for (std::size_t q = 0; q < out.size(); ++q) {
      dealii::Tensor<2, dim> g;
      for (unsigned int c = 0; c < dim; ++c) g[c] = in.solution_gradients[q][c];
      const Stress2 s = stress_of(lame_, g);
      const auto p = reference::principal(s);
      out[q][0] = s.xx;
      out[q][1] = s.yy;
      out[q][2] = s.xy;
      out[q][3] = p.s1;
      out[q][4] = p.s3;
    }
  }
  std::vector<std::string> get_names() const override { return {"sxx", "syy", "txy", "s1", "s3"}; }
  dealii::UpdateFlags get_needed_update_flags() const override { return dealii::update_gradients; }

 private:
  Lame lame_;
};

}  // namespace

Model::Model(const meshes::Mesh& mesh, const Material& material, const Discretisation& disc)
    : material_(material),
      degree_(disc.degree),
      tria_(MPI_COMM_WORLD, Tria::MeshSmoothing::none, /*allow_artificial_cells=*/false,
            Tria::Settings::partition_metis) {
  if (degree_ < 1 || degree_ > 2) throw FemError("FEM degree must be 1 or 2");
  // Cells of the disc body (all cells if the mesh names no "disc").
  const auto disc_body = std::find(mesh.body_names.begin(), mesh.body_names.end(), "disc");
  const bool all_bodies = disc_body == mesh.body_names.end();
  const auto disc_index = static_cast<meshes::Index>(disc_body - mesh.body_names.begin());
  std::vector<unsigned int> vertex_of(mesh.nodes.size(), dealii::numbers::invalid_unsigned_int);
  std::vector<Point> vertices;
  std::vector<dealii::CellData<dim>> cells;
  std::size_t corners = 0;
  auto vertex = [&](meshes::Index node) {
    if (vertex_of[node] == dealii::numbers::invalid_unsigned_int) {
      vertex_of[node] = static_cast<unsigned int>(vertices.size());
      vertices.emplace_back(mesh.nodes[node].x, mesh.nodes[node].y);
    }
    return vertex_of[node];
  };
  for (std::size_t c = 0; c < mesh.cell_count(); ++c) {
    if (!all_bodies && mesh.cell_body[c] != disc_index) continue;
    const std::size_t n = mesh.cell_size(c);
    if (n != 3 && n != 4) throw FemError("FEM cells must be triangles or quadrilaterals");
    if (corners == 0) corners = n;
    if (n != corners) throw FemError("FEM mesh mixes triangles and quadrilaterals");
    const meshes::Index* node = mesh.cell_begin(c);
    dealii::CellData<dim> cell(static_cast<unsigned int>(n));
    if (n == 3) {
      cell.vertices = {vertex(node[0]), vertex(node[1]), vertex(node[2])};
    } else {  // counter-clockwise -> deal.II's lexicographic order
      cell.vertices = {vertex(node[0]), vertex(node[1]), vertex(node[3]), vertex(node[2])};
    }
    cell.material_id = 0;
    cells.push_back(cell);
  }
  if (cells.empty()) throw FemError("FEM mesh has no cells");
  dealii::SubCellData boundary;
  for (const auto& e : mesh.boundary_edges) {
    if (vertex_of[e.a] == dealii::numbers::invalid_unsigned_int ||
        vertex_of[e.b] == dealii::numbers::invalid_unsigned_int)
      continue;
    dealii::CellData<1> line(2);
    line.vertices = {vertex_of[e.a], vertex_of[e.b]};
    line.boundary_id = static_cast<BoundaryId>(e.group + 1);
    boundary.boundary_lines.push_back(line);
  }
  for (std::size_t g = 0; g < mesh.boundary_names.size(); ++g)
    boundary_ids_[mesh.boundary_names[g]] = static_cast<BoundaryId>(g + 1);
  tria_.create_triangulation(vertices, cells, boundary);

  // Rim faces follow the circle when refined and in the (isoparametric) mapping.
  for (const auto& cell : tria_.active_cell_iterators())
    for (const unsigned int f : cell->face_indices()) {
      const auto face = cell->face(f);
      if (!face->at_boundary() || face->boundary_id() == unnamed_boundary) continue;
      if (is_curved_group(mesh.boundary_names[face->boundary_id() - 1u])) face->set_manifold_id(rim_manifold);
    }
  tria_.set_manifold(rim_manifold, dealii::SphericalManifold<dim>(Point()));
  if (disc.refinements > 0) tria_.refine_global(static_cast<unsigned int>(disc.refinements));

  const bool simplex = corners == 3;
  if (simplex)
    scalar_fe_ = std::make_unique<dealii::FE_SimplexP<dim>>(static_cast<unsigned int>(degree_));
  else
    scalar_fe_ = std::make_unique<dealii::FE_Q<dim>>(static_cast<unsigned int>(degree_));
  fe_ = std::make_unique<dealii::FESystem<dim>>(*scalar_fe_, dim);
  dof_handler_.reinit(tria_);
  dof_handler_.distribute_dofs(*fe_);
  owned_ = dof_handler_.locally_owned_dofs();
  build_geometry();
  build_locator();
}

void Model::build_geometry() {
  const bool simplex = tria_.all_reference_cells_are_simplex();
  std::unique_ptr<dealii::FiniteElement<dim>> linear;
  if (simplex)
    linear = std::make_unique<dealii::FE_SimplexP<dim>>(1);
  else
    linear = std::make_unique<dealii::FE_Q<dim>>(1);
  const auto& unit_points = scalar_fe_->get_unit_support_points();
  const unsigned int n_nodes = scalar_fe_->n_dofs_per_cell();
  geometry_.reinit(dof_handler_.n_dofs());
  dof_points_.assign(dof_handler_.n_dofs(), Point());
  component_.assign(dof_handler_.n_dofs(), 0);
  sibling_.assign(dof_handler_.n_dofs(), 0);
  cell_nodes_.assign(tria_.n_active_cells(), {});
  cells_.assign(tria_.n_active_cells(), {});
  std::vector<global_dof_index> indices(fe_->n_dofs_per_cell());
  const Point unit_centre(0.5, 0.5);
  for (const auto& cell : dof_handler_.active_cell_iterators()) {
    std::vector<Point> nodes(n_nodes);
    for (unsigned int k = 0; k < n_nodes; ++k) {
      Point p;
      for (const unsigned int v : cell->vertex_indices()) p += linear->shape_value(v, unit_points[k]) * cell->vertex(v);
      nodes[k] = p;
    }
    if (degree_ > 1) {
      // Move mid-edge nodes of curved faces onto the circle (and the quad centre by half).
      for (const unsigned int f : cell->face_indices()) {
        const auto face = cell->face(f);
        if (face->manifold_id() != rim_manifold) continue;
        const Point straight = face->center(false);
        const auto shift = face->center(true) - straight;
        const double tol = 1e-9 * face->diameter();
        for (unsigned int k = 0; k < n_nodes; ++k) {
          if (nodes[k].distance(straight) < tol)
            nodes[k] += shift;
          else if (!simplex && unit_points[k].distance(unit_centre) < 1e-12)
            nodes[k] += 0.5 * shift;
        }
      }
    }
    cell->get_dof_indices(indices);
    for (unsigned int i = 0; i < indices.size(); ++i) {
      const auto [component, node] = fe_->system_to_component_index(i);
      geometry_[indices[i]] = nodes[node][component];
      dof_points_[indices[i]] = nodes[node];
      component_[indices[i]] = component;
      sibling_[indices[i]] = indices[fe_->component_to_system_index(1 - component, node)];
    }
    cells_[cell->active_cell_index()] = cell;
    cell_nodes_[cell->active_cell_index()] = std::move(nodes);
  }
  mapping_ = std::make_unique<dealii::MappingFEField<dim, dim, dealii::Vector<double>>>(dof_handler_, geometry_);
}

void Model::build_locator() {
  Point lo(std::numeric_limits<double>::max(), std::numeric_limits<double>::max());
  Point hi = -lo;
  double size = 0.0;
  for (const auto& nodes : cell_nodes_) {
    for (const auto& p : nodes)
      for (unsigned int d = 0; d < dim; ++d) {
        lo[d] = std::min(lo[d], p[d]);
        hi[d] = std::max(hi[d], p[d]);
      }
    size += nodes.front().distance(nodes.back());
  }
  size /= static_cast<double>(cell_nodes_.size());
  // One cell size of margin: points on a curved rim may lie beyond the outermost nodes.
  for (unsigned int d = 0; d < dim; ++d) {
    lo[d] -= size;
    hi[d] += size;
  }
  const double extent = std::max(hi[0] - lo[0], hi[1] - lo[1]);
  grid_n_ = static_cast<unsigned int>(std::clamp(extent / (2.0 * size), 1.0, 2048.0));
  grid_step_ = extent / grid_n_ * (1.0 + 1e-12);
  grid_origin_ = lo;
  grid_cells_.assign(static_cast<std::size_t>(grid_n_) * grid_n_, {});
  auto bin = [&](double v, unsigned int d) {
    const double t = std::floor((v - grid_origin_[d]) / grid_step_);
    return static_cast<unsigned int>(std::clamp(t, 0.0, grid_n_ - 1.0));
  };
  for (unsigned int c = 0; c < cell_nodes_.size(); ++c) {
    Point a = cell_nodes_[c].front(), b = a;
    for (const auto& p : cell_nodes_[c])
      for (unsigned int d = 0; d < dim; ++d) {
        a[d] = std::min(a[d], p[d]);
        b[d] = std::max(b[d], p[d]);
      }
    const auto margin = 0.05 * (b - a);  // curved edges bulge beyond the nodes slightly
    a -= margin;
    b += margin;
    for (unsigned int i = bin(a[0], 0); i <= bin(b[0], 0); ++i)
      for (unsigned int j = bin(a[1], 1); j <= bin(b[1], 1); ++j)
        grid_cells_[static_cast<std::size_t>(j) * grid_n_ + i].push_back(c);
  }
}

Point Model::geometry_map(unsigned int cell_index, const Point& unit, dealii::Tensor<2, dim>* jacobian) const {
  const auto& nodes = cell_nodes_[cell_index];
  Point x;
  dealii::Tensor<2, dim> j;
  for (unsigned int k = 0; k < nodes.size(); ++k) {
    x += scalar_fe_->shape_value(k, unit) * nodes[k];
    j += dealii::outer_product(nodes[k], scalar_fe_->shape_grad(k, unit));
  }
  if (jacobian) *jacobian = j;
  return x;
}

std::optional<Model::Located> Model::locate(const Point& p) const {
  const double ti = std::floor((p[0] - grid_origin_[0]) / grid_step_);
  const double tj = std::floor((p[1] - grid_origin_[1]) / grid_step_);
  if (ti < 0 || tj < 0 || ti >= grid_n_ || tj >= grid_n_) return std::nullopt;
  const bool simplex = tria_.all_reference_cells_are_simplex();
  const Point start = simplex ? Point(1.0 / 3.0, 1.0 / 3.0) : Point(0.5, 0.5);
  std::optional<Located> best;
  double best_distance = extrapolation_tolerance;
  for (const unsigned int c : grid_cells_[static_cast<std::size_t>(tj) * grid_n_ + static_cast<std::size_t>(ti)]) {
    Point u = start;
    for (int it = 0; it < newton_max_iterations; ++it) {
      dealii::Tensor<2, dim> j;
      const Point x = geometry_map(c, u, &j);
      const auto step = dealii::invert(j) * (p - x);
      u += step;
      if (step.norm() < newton_tolerance) break;
    }
    const double d = outside_distance(u, simplex);
    if (d <= inside_tolerance) return Located{cells_[c], u};
    if (d < best_distance) {
      best_distance = d;
      best = Located{cells_[c], u};
    }
  }
  return best;
}

std::optional<Model::Probe> Model::probe(const Point& p) const {
  const auto where = locate(p);
  if (!where) return std::nullopt;
  dealii::Tensor<2, dim> j;
  geometry_map(where->cell->active_cell_index(), where->unit, &j);
  const auto inverse = dealii::invert(j);
  Probe out;
  out.dofs.resize(fe_->n_dofs_per_cell());
  typename DofHandler::active_cell_iterator cell(&tria_, where->cell->level(), where->cell->index(), &dof_handler_);
  cell->get_dof_indices(out.dofs);
  for (unsigned int i = 0; i < out.dofs.size(); ++i) {
    const auto [component, node] = fe_->system_to_component_index(i);
    out.components.push_back(component);
    out.gradients.push_back(scalar_fe_->shape_grad(node, where->unit) * inverse);  // J^-T grad
  }
  return out;
}

Stress2 Model::stress_at(const dealii::Vector<double>& u, const Probe& probe) const {
  dealii::Tensor<2, dim> grad;
  for (std::size_t i = 0; i < probe.dofs.size(); ++i)
    grad[probe.components[i]] += u[probe.dofs[i]] * probe.gradients[i];
  return stress_of(lame(material_), grad);
}

std::optional<Stress2> Model::stress_at(const dealii::Vector<double>& u, const Point& p) const {
  const auto where = probe(p);
  if (!where) return std::nullopt;
  return stress_at(u, *where);
}

std::optional<BoundaryId> Model::boundary_id(const std::string& group) const {
  const auto it = boundary_ids_.find(group);
  if (it == boundary_ids_.end()) return std::nullopt;
  return it->second;
}

BoundaryId Model::require_boundary(const std::string& group) const {
  const auto id = boundary_id(group);
  if (!id) throw FemError("FEM mesh has no boundary group \"" + group + "\"");
  return *id;
}

std::vector<global_dof_index> Model::boundary_dofs(BoundaryId id, int component) const {
  std::vector<global_dof_index> out;
  std::vector<global_dof_index> face_indices(fe_->n_dofs_per_face());
  for (const auto& cell : dof_handler_.active_cell_iterators())
    for (const unsigned int f : cell->face_indices()) {
      const auto face = cell->face(f);
      if (!face->at_boundary() || face->boundary_id() != id) continue;
      face->get_dof_indices(face_indices);
      for (const auto i : face_indices)
        if (component < 0 || dof_component(i) == static_cast<unsigned int>(component)) out.push_back(i);
    }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

void Model::make_sparse_matrix(Matrix& matrix, const Constraints& constraints) const {
  const dealii::IndexSet relevant = dealii::DoFTools::extract_locally_relevant_dofs(dof_handler_);
  dealii::DynamicSparsityPattern pattern(relevant);
  dealii::DoFTools::make_sparsity_pattern(dof_handler_, pattern, constraints, false);
  dealii::SparsityTools::distribute_sparsity_pattern(pattern, owned_, MPI_COMM_WORLD, relevant);
  matrix.reinit(owned_, owned_, pattern, MPI_COMM_WORLD);
}

namespace {
dealii::Quadrature<dim> cell_quadrature(bool simplex, int degree) {
  const auto n = static_cast<unsigned int>(degree + 1);
  if (simplex) return dealii::QGaussSimplex<dim>(n);
  return dealii::QGauss<dim>(n);
}
}  // namespace

void Model::assemble(const Constraints& constraints, Matrix& stiffness, Matrix* mass,
                     dealii::Vector<double>* rhs) const {
  const bool simplex = tria_.all_reference_cells_are_simplex();
  dealii::FEValues<dim> values(*mapping_, *fe_, cell_quadrature(simplex, degree_),
                               dealii::update_values | dealii::update_gradients | dealii::update_JxW_values);
  const dealii::FEValuesExtractors::Vector displacement(0);
  const Lame l = lame(material_);
  const double rho = material_.elastic.density;
  const unsigned int n = fe_->n_dofs_per_cell();
  dealii::FullMatrix<double> k_local(n, n), m_local(n, n);
  dealii::Vector<double> f_local(n);
  std::vector<global_dof_index> indices(n);
  std::vector<dealii::SymmetricTensor<2, dim>> strain(n);
  std::vector<double> divergence(n);
  std::vector<dealii::Tensor<1, dim>> shape(n);
  for (const auto& cell : dof_handler_.active_cell_iterators()) {
    if (!cell->is_locally_owned()) continue;
    values.reinit(cell);
    k_local = 0.0;
    m_local = 0.0;
    for (unsigned int q = 0; q < values.n_quadrature_points; ++q) {
      for (unsigned int i = 0; i < n; ++i) {
        strain[i] = values[displacement].symmetric_gradient(i, q);
        divergence[i] = values[displacement].divergence(i, q);
        shape[i] = values[displacement].value(i, q);
      }
      const double jxw = values.JxW(q);
      for (unsigned int i = 0; i < n; ++i)
        for (unsigned int j = 0; j <= i; ++j) {
          k_local(i, j) += (l.lambda * divergence[i] * divergence[j] + 2.0 * l.mu * (strain[i] * strain[j])) * jxw;
          if (mass) m_local(i, j) += rho * (shape[i] * shape[j]) * jxw;
        }
    }
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = i + 1; j < n; ++j) {
        k_local(i, j) = k_local(j, i);
        m_local(i, j) = m_local(j, i);
      }
    cell->get_dof_indices(indices);
    if (rhs) {
      f_local = 0.0;
      constraints.distribute_local_to_global(k_local, f_local, indices, stiffness, *rhs);
    } else {
      constraints.distribute_local_to_global(k_local, indices, stiffness);
    }
    if (mass) constraints.distribute_local_to_global(m_local, indices, *mass);
  }
  stiffness.compress(dealii::VectorOperation::add);
  if (mass) mass->compress(dealii::VectorOperation::add);
  if (rhs) sum_over_ranks(*rhs);
}

void Model::add_pressure(double pressure, const FaceSelector& selected, dealii::Vector<double>& rhs) const {
  // Composite rule: a loaded arc that ends inside a face is integrated to O(h / copies).
  const dealii::QIterated<dim - 1> quadrature(dealii::QGauss<1>(static_cast<unsigned int>(degree_ + 1)),
                                              partial_face_copies);
  dealii::FEFaceValues<dim> values(*mapping_, *fe_, quadrature,
                                   dealii::update_values | dealii::update_normal_vectors | dealii::update_JxW_values |
                                       dealii::update_quadrature_points);
  const dealii::FEValuesExtractors::Vector displacement(0);
  const unsigned int n = fe_->n_dofs_per_cell();
  std::vector<global_dof_index> indices(n);
  dealii::Vector<double> part(rhs.size());
  for (const auto& cell : dof_handler_.active_cell_iterators()) {
    if (!cell->is_locally_owned()) continue;
    for (const unsigned int f : cell->face_indices()) {
      const auto face = cell->face(f);
      if (!face->at_boundary()) continue;
      values.reinit(cell, f);
      cell->get_dof_indices(indices);
      for (unsigned int q = 0; q < values.n_quadrature_points; ++q) {
        const double factor = selected(values.quadrature_point(q), face->boundary_id());
        if (factor == 0.0) continue;
        const auto traction = -pressure * factor * values.normal_vector(q);
        for (unsigned int i = 0; i < n; ++i)
          part[indices[i]] += (traction * values[displacement].value(i, q)) * values.JxW(q);
      }
    }
  }
  sum_over_ranks(part);
  rhs += part;
}

dealii::Vector<double> Model::internal_force(const dealii::Vector<double>& u) const {
  Matrix k;
  const Constraints none;
  make_sparse_matrix(k, none);
  assemble(none, k, nullptr, nullptr);
  Vec out = make_vector();
  k.vmult(out, to_trilinos(u, *this));
  return to_serial(out);
}

std::array<dealii::Vector<double>, 3> Model::rigid_modes() const {
  std::array<dealii::Vector<double>, 3> modes;
  for (auto& m : modes) m.reinit(n_dofs());
  for (global_dof_index i = 0; i < n_dofs(); ++i) {
    const auto& p = dof_points_[i];
    const unsigned int c = dof_component(i);
    modes[c][i] = 1.0;
    modes[2][i] = c == 0 ? -p[1] : p[0];
  }
  return modes;
}

void Model::write_vtu(const dealii::Vector<double>& u, const std::filesystem::path& path,
                      const dealii::Vector<double>* velocity) const {
  dealii::DataOut<dim> out;
  out.attach_dof_handler(dof_handler_);
  const std::vector<dealii::DataComponentInterpretation::DataComponentInterpretation> interpretation(
      dim, dealii::DataComponentInterpretation::component_is_part_of_vector);
  out.add_data_vector(u, std::vector<std::string>(dim, "displacement"), dealii::DataOut<dim>::type_dof_data,
                      interpretation);
  if (velocity)
    out.add_data_vector(*velocity, std::vector<std::string>(dim, "velocity"), dealii::DataOut<dim>::type_dof_data,
                        interpretation);
  const StressPostprocessor stress(lame(material_));
  out.add_data_vector(u, stress);
  // Every rank holds every cell and the whole of u: rank 0 writes the whole mesh (the default
  // selection would be its own cells only).
  using CellIterator = typename dealii::DataOut<dim>::cell_iterator;
  out.set_cell_selection([](const dealii::Triangulation<dim>& t) -> CellIterator { return t.begin_active(); },
                         [](const dealii::Triangulation<dim>&, const CellIterator& cell) -> CellIterator {
                           auto next = cell;
                           do ++next;
                           while (next.state() == dealii::IteratorState::valid && !next->is_active());
                           return next;
                         });
  if (!is_root()) return;
  out.build_patches(*mapping_, static_cast<unsigned int>(degree_));
  common::write_whole_file(path, [&](const std::filesystem::path& tmp) {
    std::ofstream file(tmp);
    if (!file) throw FemError("cannot write " + tmp.string());
    out.write_vtu(file);
    if (!file) throw FemError("cannot write " + tmp.string());
  });
}

Vec to_trilinos(const dealii::Vector<double>& v, const Model& model) {
  Vec out = model.make_vector();
  for (const auto i : model.owned()) out[i] = v[i];
  out.compress(dealii::VectorOperation::insert);
  return out;
}

dealii::Vector<double> to_serial(const Vec& v) {
  dealii::Vector<double> out(v.size());
  for (const auto i : v.locally_owned_elements()) out[i] = v[i];
  sum_over_ranks(out);
  return out;
}

void sum_over_ranks(dealii::Vector<double>& v) {
  if (single_rank()) return;
  const dealii::Vector<double> local(v);
  dealii::Utilities::MPI::sum(dealii::make_array_view(local), MPI_COMM_WORLD, dealii::make_array_view(v));
}

bool is_root() { return dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0; }

bool single_rank() { return dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) == 1; }

ElasticSolver::ElasticSolver(const Matrix& matrix, const Model& model, const SolverSettings& settings)
    : matrix_(matrix), settings_(settings) {
  dealii::TrilinosWrappers::PreconditionAMG::AdditionalData data;
  data.elliptic = true;
  data.higher_order_elements = model.fe().degree > 1;
  data.smoother_sweeps = ml_smoother_sweeps;
  data.aggregation_threshold = ml_aggregation_threshold;
  Teuchos::ParameterList parameters;
  std::unique_ptr<Epetra_MultiVector> unused_modes;
  data.set_parameters(parameters, unused_modes, matrix);
  const auto modes = model.rigid_modes();
  const std::size_t n_local = model.owned().n_elements();
  null_space_.resize(modes.size() * n_local);
  for (std::size_t k = 0; k < modes.size(); ++k) {
    std::size_t row = 0;
    for (const auto i : model.owned()) null_space_[k * n_local + row++] = modes[k][i];
  }
  parameters.set("PDE equations", dim);
  parameters.set("null space: type", "pre-computed");
  parameters.set("null space: dimension", static_cast<int>(modes.size()));
  parameters.set("null space: vectors", null_space_.data());
  amg_.initialize(matrix, parameters);
}

ElasticSolver::~ElasticSolver() = default;

int ElasticSolver::solve(Vec& x, const Vec& b) const {
  const double target = settings_.relative_tolerance * b.l2_norm();
  dealii::SolverControl control(static_cast<unsigned int>(settings_.max_iterations),
                                std::max(target, std::numeric_limits<double>::min()));
  dealii::TrilinosWrappers::SolverCG cg(control);
  try {
    cg.solve(matrix_, x, b, amg_);
  } catch (const std::exception& e) {
    throw FemError(std::string("CG did not converge: ") + e.what());
  }
  return static_cast<int>(control.last_step());
}

}  // namespace ddafrac::fem::detail
