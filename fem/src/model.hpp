#pragma once
// Internal: the deal.II side of the FEM reference, shared by the static and dynamic problems.
// One Model = triangulation (from a meshes::Mesh, curved rim), isoparametric mapping, vector
// FE, DoFs, and the operations both problems need (matrices, loads, stress at points, VTU).

#include <deal.II/base/index_set.h>
#include <deal.II/distributed/shared_tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_fe_field.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <array>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "ddafrac/fem/elasticity.hpp"
#include "ddafrac/meshes/mesh.hpp"

namespace ddafrac::fem::detail {

constexpr int dim = 2;
// Every rank holds the whole (small) mesh; cells and DoFs are partitioned among the ranks
// (METIS), so that assembly and the solver are distributed while point evaluation needs no
// communication once the solution is gathered. Works with simplices, unlike p4est.
using Tria = dealii::parallel::shared::Triangulation<dim>;
using DofHandler = dealii::DoFHandler<dim>;
using Matrix = dealii::TrilinosWrappers::SparseMatrix;
using Vec = dealii::TrilinosWrappers::MPI::Vector;
using Constraints = dealii::AffineConstraints<double>;
using Point = dealii::Point<dim>;

class Model {
 public:
  Model(const meshes::Mesh& mesh, const Material& material, const Discretisation& disc);
  Model(const Model&) = delete;
  Model& operator=(const Model&) = delete;

  const DofHandler& dofs() const { return dof_handler_; }
  std::size_t n_dofs() const { return dof_handler_.n_dofs(); }
  std::size_t n_cells() const { return tria_.n_active_cells(); }
  const dealii::IndexSet& owned() const { return owned_; }
  const Material& material() const { return material_; }

  /// deal.II boundary id of a named group, or nullopt if the mesh has no such group.
  std::optional<dealii::types::boundary_id> boundary_id(const std::string& group) const;
  /// Boundary id of a group that must exist (FemError otherwise).
  dealii::types::boundary_id require_boundary(const std::string& group) const;

  /// Support-point position of every DoF (component-wise dofs share their node's position).
  const std::vector<Point>& dof_points() const { return dof_points_; }
  /// Component (0 = x, 1 = y) of every DoF.
  unsigned int dof_component(dealii::types::global_dof_index i) const { return component_[i]; }
  /// The DoF of the other component at the same support point.
  dealii::types::global_dof_index sibling(dealii::types::global_dof_index i) const { return sibling_[i]; }
  /// DoFs (of one component, or both if component < 0) on the faces of a boundary id.
  std::vector<dealii::types::global_dof_index> boundary_dofs(dealii::types::boundary_id id, int component) const;

  void make_sparse_matrix(Matrix& matrix, const Constraints& constraints) const;
  /// Stiffness (and consistent mass, if given) with constraints condensed, each rank
  /// assembling its own cells. With `rhs` (a full vector, the same on every rank afterwards),
  /// inhomogeneous constraints add their -K g to it.
  void assemble(const Constraints& constraints, Matrix& stiffness, Matrix* mass,
                dealii::Vector<double>* rhs = nullptr) const;
  /// Adds the load of a pressure p (Pa, positive pushes into the body) on boundary faces,
  /// scaled at each face quadrature point by `selected(point, boundary id)` (1 = loaded,
  /// 0 = free), so that a loaded arc may end inside a face. `rhs` is a full vector, the same on
  /// every rank afterwards.
  using FaceSelector = std::function<double(const Point& point, dealii::types::boundary_id id)>;
  void add_pressure(double pressure, const FaceSelector& selected, dealii::Vector<double>& rhs) const;
  /// Internal force vector K u (unconstrained, cell by cell), full on every rank.
  dealii::Vector<double> internal_force(const dealii::Vector<double>& u) const;

  /// Three rigid-body modes (x, y translation, rotation about the origin) as DoF vectors.
  std::array<dealii::Vector<double>, 3> rigid_modes() const;

  Vec make_vector() const { return Vec(owned_, MPI_COMM_WORLD); }

  /// A point located once in the mesh: the DoFs of its cell and the gradient (1/m) of each
  /// one's shape function there, so that reading the stress at the point again is a short sum.
  struct Probe {
    std::vector<dealii::types::global_dof_index> dofs;
    std::vector<unsigned int> components;
    std::vector<dealii::Tensor<1, dim>> gradients;
  };
  /// The probe of a point; nullopt if the point is outside the body.
  std::optional<Probe> probe(const Point& p) const;
  /// Stress of the displacement field u (full vector) at a probe. Local: every rank holds every
  /// cell and the whole of u.
  Stress2 stress_at(const dealii::Vector<double>& u, const Probe& probe) const;
  /// The same at a point (located again at every call); nullopt if it is outside the body.
  std::optional<Stress2> stress_at(const dealii::Vector<double>& u, const Point& p) const;
  /// All cells, written whole by rank 0 (u and the optional velocity full, the same on every
  /// rank).
  void write_vtu(const dealii::Vector<double>& u, const std::filesystem::path& path,
                 const dealii::Vector<double>* velocity = nullptr) const;

  const dealii::Mapping<dim>& mapping() const { return *mapping_; }
  const dealii::FiniteElement<dim>& fe() const { return *fe_; }

 private:
  struct Located {
    typename Tria::active_cell_iterator cell;
    Point unit;
  };
  std::optional<Located> locate(const Point& p) const;
  Point geometry_map(unsigned int cell_index, const Point& unit, dealii::Tensor<2, dim>* jacobian) const;
  void build_geometry();
  void build_locator();

  Material material_;
  int degree_;
  Tria tria_;
  std::map<std::string, dealii::types::boundary_id> boundary_ids_;
  std::unique_ptr<dealii::FiniteElement<dim>> scalar_fe_;
  std::unique_ptr<dealii::FESystem<dim>> fe_;
  DofHandler geometry_dofs_;
  dealii::Vector<double> geometry_;
  std::unique_ptr<dealii::MappingFEField<dim, dim, dealii::Vector<double>>> mapping_;
  std::vector<std::vector<Point>> cell_nodes_;  // geometry support points per active cell
  DofHandler dof_handler_;
  dealii::IndexSet owned_;
  std::vector<Point> dof_points_;
  std::vector<unsigned int> component_;
  std::vector<dealii::types::global_dof_index> sibling_;
  // Point location: uniform grid of cell bounding boxes.
  Point grid_origin_;
  double grid_step_ = 0.0;
  unsigned int grid_n_ = 0;
  std::vector<std::vector<unsigned int>> grid_cells_;
  std::vector<typename Tria::active_cell_iterator> cells_;
};

/// CG + ML AMG (rigid-body modes as the near null space) on one matrix, set up once.
class ElasticSolver {
 public:
  static constexpr const char* name = "CG + ML AMG";
  ElasticSolver(const Matrix& matrix, const Model& model, const SolverSettings& settings);
  ~ElasticSolver();
  /// Solves and returns the iteration count; throws FemError if CG did not converge.
  int solve(Vec& x, const Vec& b) const;

 private:
  const Matrix& matrix_;
  SolverSettings settings_;
  std::vector<double> null_space_;
  dealii::TrilinosWrappers::PreconditionAMG amg_;
};

Vec to_trilinos(const dealii::Vector<double>& v, const Model& model);
/// The whole vector on every rank (gathered).
dealii::Vector<double> to_serial(const Vec& v);
/// Sums a full vector over the ranks (each contributed its own cells' part), in place.
void sum_over_ranks(dealii::Vector<double>& v);
/// True on the rank that writes files.
bool is_root();
/// True if this process is the only rank (it holds every row of every matrix).
bool single_rank();

}  // namespace ddafrac::fem::detail
