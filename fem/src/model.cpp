#include "model.hpp"

#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/manifold_lib.h>
#include <deal.II/grid/tria_description.h>
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
#include <tuple>

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
    : material_(material), degree_(disc.degree), tria_(MPI_COMM_WORLD) {
  if (degree_ < 1 || degree_ > 2) throw FemError("FEM degree must be 1 or 2");
  build_triangulation(mesh, disc);
  if (tria_.all_reference_cells_are_simplex())
    scalar_fe_ = std::make_unique<dealii::FE_SimplexP<dim>>(static_cast<unsigned int>(degree_));
  else
    scalar_fe_ = std::make_unique<dealii::FE_Q<dim>>(static_cast<unsigned int>(degree_));
  fe_ = std::make_unique<dealii::FESystem<dim>>(*scalar_fe_, dim);
  dof_handler_.reinit(tria_);
  dof_handler_.distribute_dofs(*fe_);
  owned_ = dof_handler_.locally_owned_dofs();
  relevant_ = dealii::DoFTools::extract_locally_relevant_dofs(dof_handler_);
  build_geometry();
  build_locator();
}

namespace {

/// The disc body of a meshes::Mesh (all cells if it names no "disc") as a serial deal.II
/// triangulation with named boundary ids (group + 1) and the rim on the circle.
void build_coarse(const meshes::Mesh& mesh, dealii::Triangulation<dim>& tria) {
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
  tria.create_triangulation(vertices, cells, boundary);

  // Rim faces follow the circle when refined and in the (isoparametric) mapping.
  for (const auto& cell : tria.active_cell_iterators())
    for (const unsigned int f : cell->face_indices()) {
      const auto face = cell->face(f);
      if (!face->at_boundary() || face->boundary_id() == unnamed_boundary) continue;
      if (is_curved_group(mesh.boundary_names[face->boundary_id() - 1u])) face->set_manifold_id(rim_manifold);
    }
  tria.set_manifold(rim_manifold, dealii::SphericalManifold<dim>(Point()));
}

}  // namespace

/// Rank 0 alone builds the whole mesh, refines it and partitions it (METIS), and sends each
/// rank the description of its own cells and their ghosts. The other ranks read only the mesh's
/// boundary group names (their `mesh` may hold nothing else: mesh_on_first_rank).
void Model::build_triangulation(const meshes::Mesh& mesh, const Discretisation& disc) {
  for (std::size_t g = 0; g < mesh.boundary_names.size(); ++g)
    boundary_ids_[mesh.boundary_names[g]] = static_cast<BoundaryId>(g + 1);
  const auto refinements = static_cast<unsigned int>(std::max(disc.refinements, 0));
  const unsigned int ranks = dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD);
  const auto description =
      dealii::TriangulationDescription::Utilities::create_description_from_triangulation_in_groups<dim, dim>(
          [&](dealii::Triangulation<dim>& whole) {
            build_coarse(mesh, whole);
            if (refinements > 0) whole.refine_global(refinements);
          },
          [ranks](dealii::Triangulation<dim>& whole, const MPI_Comm&, unsigned int) {
            dealii::GridTools::partition_triangulation(ranks, whole);
          },
          MPI_COMM_WORLD, static_cast<int>(ranks));
  tria_.set_manifold(rim_manifold, dealii::SphericalManifold<dim>(Point()));
  tria_.create_triangulation(description);
}

namespace {

/// A cell's place in the whole mesh's active-cell order. Uniform refinement numbers the cells
/// of a level by parent, then child, so that order is the coarse cell, then the child index at
/// each level down to the cell: the same on every rank, whatever the partition.
std::uint64_t order_in_whole_mesh(const typename Tria::cell_iterator& cell) {
  std::vector<unsigned int> path;  // child indices, finest first
  auto ancestor = cell;
  while (ancestor->level() > 0) {
    const auto parent = ancestor->parent();
    path.push_back(parent->child_iterator_to_index(ancestor));
    ancestor = parent;
  }
  std::uint64_t order = ancestor->id().get_coarse_cell_id();
  for (auto child = path.rbegin(); child != path.rend(); ++child)
    order = order * dealii::GeometryInfo<dim>::max_children_per_cell + *child;
  return order;
}

}  // namespace

/// Geometry support points of every cell this rank sees (own and ghost), the DoF positions,
/// components and siblings of its relevant DoFs, and the mapping's coordinate vector.
void Model::build_geometry() {
  const bool simplex = tria_.all_reference_cells_are_simplex();
  std::unique_ptr<dealii::FiniteElement<dim>> linear;
  if (simplex)
    linear = std::make_unique<dealii::FE_SimplexP<dim>>(1);
  else
    linear = std::make_unique<dealii::FE_Q<dim>>(1);
  const auto& unit_points = scalar_fe_->get_unit_support_points();
  const unsigned int n_nodes = scalar_fe_->n_dofs_per_cell();
  Vec geometry = make_vector();
  const auto n_relevant = relevant_.n_elements();
  dof_points_.assign(n_relevant, Point());
  component_.assign(n_relevant, 0);
  sibling_.assign(n_relevant, 0);
  std::vector<global_dof_index> indices(fe_->n_dofs_per_cell());
  const Point unit_centre(0.5, 0.5);
  for (const auto& cell : dof_handler_.active_cell_iterators()) {
    if (cell->is_artificial()) continue;
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
      if (owned_.is_element(indices[i])) geometry[indices[i]] = nodes[node][component];
      const std::size_t at = local(indices[i]);
      dof_points_[at] = nodes[node];
      component_[at] = component;
      sibling_[at] = indices[fe_->component_to_system_index(1 - component, node)];
    }
    if (!cell->is_locally_owned()) continue;
    cells_.push_back(cell);
    cell_order_.push_back(order_in_whole_mesh(cell));
    cell_nodes_.push_back(std::move(nodes));
  }
  geometry.compress(dealii::VectorOperation::insert);
  geometry_ = make_ghosted();
  geometry_ = geometry;
  mapping_ = std::make_unique<dealii::MappingFEField<dim, dim, Vec>>(dof_handler_, geometry_);
}

/// The grid spans the whole mesh with cells of about two mean cell sizes (both from all
/// ranks, so that every rank bins alike); each rank stores the part its own cells cover.
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
  for (unsigned int d = 0; d < dim; ++d) {
    lo[d] = dealii::Utilities::MPI::min(lo[d], MPI_COMM_WORLD);
    hi[d] = dealii::Utilities::MPI::max(hi[d], MPI_COMM_WORLD);
  }
  size = dealii::Utilities::MPI::sum(size, MPI_COMM_WORLD) / static_cast<double>(n_cells());
  // One cell size of margin: points on a curved rim may lie beyond the outermost nodes.
  for (unsigned int d = 0; d < dim; ++d) {
    lo[d] -= size;
    hi[d] += size;
  }
  const double extent = std::max(hi[0] - lo[0], hi[1] - lo[1]);
  const auto grid_n = static_cast<unsigned int>(std::clamp(extent / (2.0 * size), 1.0, 2048.0));
  grid_step_ = extent / grid_n * (1.0 + 1e-12);
  grid_origin_ = lo;
  auto bin = [&](double v, unsigned int d) {
    const double t = std::floor((v - grid_origin_[d]) / grid_step_);
    return static_cast<unsigned int>(std::clamp(t, 0.0, grid_n - 1.0));
  };
  std::vector<std::array<Point, 2>> boxes(cell_nodes_.size());
  std::array<unsigned int, dim> last{};
  grid_first_ = {grid_n, grid_n};
  for (unsigned int c = 0; c < cell_nodes_.size(); ++c) {
    Point a = cell_nodes_[c].front(), b = a;
    for (const auto& p : cell_nodes_[c])
      for (unsigned int d = 0; d < dim; ++d) {
        a[d] = std::min(a[d], p[d]);
        b[d] = std::max(b[d], p[d]);
      }
    const auto margin = 0.05 * (b - a);  // curved edges bulge beyond the nodes slightly
    boxes[c] = {a - margin, b + margin};
    for (unsigned int d = 0; d < dim; ++d) {
      grid_first_[d] = std::min(grid_first_[d], bin(boxes[c][0][d], d));
      last[d] = std::max(last[d], bin(boxes[c][1][d], d));
    }
  }
  for (unsigned int d = 0; d < dim; ++d) grid_count_[d] = cell_nodes_.empty() ? 0 : last[d] - grid_first_[d] + 1;
  grid_cells_.assign(static_cast<std::size_t>(grid_count_[0]) * grid_count_[1], {});
  // Cells in the whole mesh's order within each bin: the first inside is the serial choice.
  std::vector<unsigned int> by_order(cell_nodes_.size());
  for (unsigned int c = 0; c < by_order.size(); ++c) by_order[c] = c;
  std::sort(by_order.begin(), by_order.end(),
            [&](unsigned int a, unsigned int b) { return cell_order_[a] < cell_order_[b]; });
  for (const unsigned int c : by_order)
    for (unsigned int i = bin(boxes[c][0][0], 0); i <= bin(boxes[c][1][0], 0); ++i)
      for (unsigned int j = bin(boxes[c][0][1], 1); j <= bin(boxes[c][1][1], 1); ++j)
        grid_cells_[static_cast<std::size_t>(j - grid_first_[1]) * grid_count_[0] + (i - grid_first_[0])].push_back(c);
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
  const double ti = std::floor((p[0] - grid_origin_[0]) / grid_step_) - grid_first_[0];
  const double tj = std::floor((p[1] - grid_origin_[1]) / grid_step_) - grid_first_[1];
  if (ti < 0 || tj < 0 || ti >= grid_count_[0] || tj >= grid_count_[1]) return std::nullopt;
  const bool simplex = tria_.all_reference_cells_are_simplex();
  const Point start = simplex ? Point(1.0 / 3.0, 1.0 / 3.0) : Point(0.5, 0.5);
  std::optional<Located> best;
  double best_distance = extrapolation_tolerance;
  for (const unsigned int c :
       grid_cells_[static_cast<std::size_t>(tj) * grid_count_[0] + static_cast<std::size_t>(ti)]) {
    Point u = start;
    for (int it = 0; it < newton_max_iterations; ++it) {
      dealii::Tensor<2, dim> j;
      const Point x = geometry_map(c, u, &j);
      const auto step = dealii::invert(j) * (p - x);
      u += step;
      if (step.norm() < newton_tolerance) break;
    }
    const double d = outside_distance(u, simplex);
    if (d <= inside_tolerance) return Located{c, u, 0.0};
    if (d < best_distance) {
      best_distance = d;
      best = Located{c, u, d};
    }
  }
  return best;
}

Model::Probe Model::probe_at(const Located& where) const {
  dealii::Tensor<2, dim> j;
  geometry_map(where.cell, where.unit, &j);
  const auto inverse = dealii::invert(j);
  Probe out;
  out.owner = dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD);
  out.dofs.resize(fe_->n_dofs_per_cell());
  cells_[where.cell]->get_dof_indices(out.dofs);
  for (unsigned int i = 0; i < out.dofs.size(); ++i) {
    const auto [component, node] = fe_->system_to_component_index(i);
    out.components.push_back(component);
    out.gradients.push_back(scalar_fe_->shape_grad(node, where.unit) * inverse);  // J^-T grad
  }
  return out;
}

/// Each rank locates the points in its own cells; the ranks then agree, point by point, on
/// the best cell: inside before extrapolated, then nearer, then first in the whole mesh's
/// order (the serial rule), and the owner of that cell keeps the probe.
std::vector<std::optional<Model::Probe>> Model::probes(const std::vector<Point>& points) const {
  constexpr double not_found = std::numeric_limits<double>::infinity();
  std::vector<std::optional<Located>> here(points.size());
  std::vector<double> claims(2 * points.size(), not_found);  // (distance outside, cell order)
  for (std::size_t k = 0; k < points.size(); ++k) {
    here[k] = locate(points[k]);
    if (!here[k]) continue;
    claims[2 * k] = here[k]->outside;
    claims[2 * k + 1] = static_cast<double>(cell_order_[here[k]->cell]);
  }
  const auto all_claims = dealii::Utilities::MPI::all_gather(MPI_COMM_WORLD, claims);
  const unsigned int me = dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD);
  std::vector<std::optional<Probe>> out(points.size());
  for (std::size_t k = 0; k < points.size(); ++k) {
    std::optional<unsigned int> winner;
    for (unsigned int r = 0; r < all_claims.size(); ++r) {
      const auto claim = std::make_tuple(all_claims[r][2 * k], all_claims[r][2 * k + 1]);
      if (std::get<0>(claim) == not_found) continue;
      if (!winner || claim < std::make_tuple(all_claims[*winner][2 * k], all_claims[*winner][2 * k + 1])) winner = r;
    }
    if (!winner) continue;
    if (*winner == me) {
      out[k] = probe_at(*here[k]);
    } else {
      out[k] = Probe{};
      out[k]->owner = *winner;
    }
  }
  return out;
}

std::vector<Stress2> Model::stresses(const Vec& u, const std::vector<Probe>& probes) const {
  // Exactly one rank fills each probe's entries, so the sum over ranks is exact.
  const Lame l = lame(material_);
  const unsigned int me = dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD);
  std::vector<double> values(3 * probes.size(), 0.0);
  for (std::size_t k = 0; k < probes.size(); ++k) {
    const Probe& probe = probes[k];
    if (probe.owner != me) continue;
    dealii::Tensor<2, dim> grad;
    for (std::size_t i = 0; i < probe.dofs.size(); ++i)
      grad[probe.components[i]] += u[probe.dofs[i]] * probe.gradients[i];
    const Stress2 s = stress_of(l, grad);
    values[3 * k] = s.xx;
    values[3 * k + 1] = s.yy;
    values[3 * k + 2] = s.xy;
  }
  sum_over_ranks(values.data(), values.size());
  std::vector<Stress2> out(probes.size());
  for (std::size_t k = 0; k < probes.size(); ++k) out[k] = {values[3 * k], values[3 * k + 1], values[3 * k + 2]};
  return out;
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
  for (const auto& cell : dof_handler_.active_cell_iterators()) {
    if (cell->is_artificial()) continue;
    for (const unsigned int f : cell->face_indices()) {
      const auto face = cell->face(f);
      if (!face->at_boundary() || face->boundary_id() != id) continue;
      face->get_dof_indices(face_indices);
      for (const auto i : face_indices)
        if (component < 0 || dof_component(i) == static_cast<unsigned int>(component)) out.push_back(i);
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

void Model::make_sparse_matrix(Matrix& matrix, const Constraints& constraints) const {
  dealii::DynamicSparsityPattern pattern(relevant_);
  dealii::DoFTools::make_sparsity_pattern(dof_handler_, pattern, constraints, false);
  dealii::SparsityTools::distribute_sparsity_pattern(pattern, owned_, MPI_COMM_WORLD, relevant_);
  matrix.reinit(owned_, owned_, pattern, MPI_COMM_WORLD);
}

namespace {
dealii::Quadrature<dim> cell_quadrature(bool simplex, int degree) {
  const auto n = static_cast<unsigned int>(degree + 1);
  if (simplex) return dealii::QGaussSimplex<dim>(n);
  return dealii::QGauss<dim>(n);
}
}  // namespace

void Model::assemble(const Constraints& constraints, Matrix& stiffness, Matrix* mass, Vec* rhs) const {
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
  if (rhs) rhs->compress(dealii::VectorOperation::add);
}

void Model::add_pressure(double pressure, const FaceSelector& selected, Vec& rhs) const {
  // Composite rule: a loaded arc that ends inside a face is integrated to O(h / copies).
  const dealii::QIterated<dim - 1> quadrature(dealii::QGauss<1>(static_cast<unsigned int>(degree_ + 1)),
                                              partial_face_copies);
  dealii::FEFaceValues<dim> values(*mapping_, *fe_, quadrature,
                                   dealii::update_values | dealii::update_normal_vectors | dealii::update_JxW_values |
                                       dealii::update_quadrature_points);
  const dealii::FEValuesExtractors::Vector displacement(0);
  const unsigned int n = fe_->n_dofs_per_cell();
  std::vector<global_dof_index> indices(n);
  Vec part = make_vector();  // summed entry by entry in cell order, then added whole
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
        for (unsigned int i = 0; i < n; ++i) {
          const double value = (traction * values[displacement].value(i, q)) * values.JxW(q);
          part.add(1, &indices[i], &value);
        }
      }
    }
  }
  part.compress(dealii::VectorOperation::add);
  rhs += part;
}

Vec Model::internal_force(const Vec& u) const {
  Matrix k;
  const Constraints none;
  make_sparse_matrix(k, none);
  assemble(none, k, nullptr, nullptr);
  Vec out = make_vector(), owned_u = make_vector();
  owned_u = u;
  k.vmult(out, owned_u);
  return out;
}

std::array<Vec, 3> Model::rigid_modes() const {
  std::array<Vec, 3> modes{make_vector(), make_vector(), make_vector()};
  for (const auto i : owned_) {
    const auto& p = dof_point(i);
    const unsigned int c = dof_component(i);
    modes[c][i] = 1.0;
    modes[2][i] = c == 0 ? -p[1] : p[0];
  }
  for (auto& m : modes) m.compress(dealii::VectorOperation::insert);
  return modes;
}

Vec Model::ghosted(const Vec& v) const {
  Vec out = make_ghosted();
  out = v;
  return out;
}

std::string Model::write_vtu(const Vec& u, const std::filesystem::path& directory, const std::string& stem,
                             const Vec* velocity) const {
  dealii::DataOut<dim> out;  // this rank's own cells
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
  out.build_patches(*mapping_, static_cast<unsigned int>(degree_));
  auto write = [](const std::filesystem::path& path, const std::function<void(std::ostream&)>& content) {
    common::write_whole_file(path, [&](const std::filesystem::path& tmp) {
      std::ofstream file(tmp);
      if (!file) throw FemError("cannot write " + tmp.string());
      content(file);
      if (!file) throw FemError("cannot write " + tmp.string());
    });
  };
  const auto piece = [&](unsigned int rank) { return stem + "." + std::to_string(rank) + ".vtu"; };
  const unsigned int me = dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD);
  write(directory / piece(me), [&](std::ostream& file) { out.write_vtu(file); });
  const std::string record = stem + ".pvtu";
  if (is_root()) {
    std::vector<std::string> pieces;
    for (unsigned int r = 0; r < dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD); ++r)
      pieces.push_back(piece(r));
    write(directory / record, [&](std::ostream& file) { out.write_pvtu_record(file, pieces); });
  }
  return record;
}

void sum_over_ranks(double* values, std::size_t count) {
  if (single_rank()) return;
  MPI_Allreduce(MPI_IN_PLACE, values, static_cast<int>(count), MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
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
  for (std::size_t k = 0; k < modes.size(); ++k)
    std::copy(modes[k].begin(), modes[k].end(), null_space_.begin() + k * n_local);
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
