#pragma once
// Internal: the deal.II side of the FEM reference, shared by the static and dynamic problems.
// One Model = triangulation (from a meshes::Mesh, curved rim), isoparametric mapping, vector
// FE, DoFs, and the operations both problems need (matrices, loads, stress at points, VTU).

#include <deal.II/base/index_set.h>
#include <deal.II/distributed/fully_distributed_tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_fe_field.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <array>
#include <cstdint>
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
// Each rank holds only its own cells and one layer of ghost cells (a fully distributed
// triangulation, which supports simplices, unlike p4est's in deal.II 9.4), so memory per rank
// falls with the rank count. Rank 0 builds and partitions (METIS) the whole mesh during setup
// and drops it afterwards.
using Tria = dealii::parallel::fullydistributed::Triangulation<dim>;
using DofHandler = dealii::DoFHandler<dim>;
using Matrix = dealii::TrilinosWrappers::SparseMatrix;
// Distributed vector. Made by make_vector(): this rank's entries, writable. Made by
// make_ghosted(): also the entries of the ghost cells, read-only (for reading at cells).
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
  std::size_t n_cells() const { return tria_.n_global_active_cells(); }
  /// DoFs this rank owns, and those it sees on its own and ghost cells.
  const dealii::IndexSet& owned() const { return owned_; }
  const dealii::IndexSet& relevant() const { return relevant_; }
  const Material& material() const { return material_; }

  /// deal.II boundary id of a named group, or nullopt if the mesh has no such group.
  std::optional<dealii::types::boundary_id> boundary_id(const std::string& group) const;
  /// Boundary id of a group that must exist (FemError otherwise).
  dealii::types::boundary_id require_boundary(const std::string& group) const;

  /// Support-point position of a locally relevant DoF (both components of a node share it).
  const Point& dof_point(dealii::types::global_dof_index i) const { return dof_points_[local(i)]; }
  /// Component (0 = x, 1 = y) of a locally relevant DoF.
  unsigned int dof_component(dealii::types::global_dof_index i) const { return component_[local(i)]; }
  /// The DoF of the other component at the same support point (locally relevant DoFs).
  dealii::types::global_dof_index sibling(dealii::types::global_dof_index i) const { return sibling_[local(i)]; }
  /// Locally relevant DoFs (of one component, or both if component < 0) on the faces of a
  /// boundary id.
  std::vector<dealii::types::global_dof_index> boundary_dofs(dealii::types::boundary_id id, int component) const;

  void make_sparse_matrix(Matrix& matrix, const Constraints& constraints) const;
  /// Stiffness (and consistent mass, if given) with constraints condensed, each rank
  /// assembling its own cells. With `rhs`, inhomogeneous constraints add their -K g to it.
  void assemble(const Constraints& constraints, Matrix& stiffness, Matrix* mass, Vec* rhs = nullptr) const;
  /// Adds the load of a pressure p (Pa, positive pushes into the body) on boundary faces,
  /// scaled at each face quadrature point by `selected(point, boundary id)` (1 = loaded,
  /// 0 = free), so that a loaded arc may end inside a face.
  using FaceSelector = std::function<double(const Point& point, dealii::types::boundary_id id)>;
  void add_pressure(double pressure, const FaceSelector& selected, Vec& rhs) const;
  /// Internal force vector K u (unconstrained, cell by cell).
  Vec internal_force(const Vec& u) const;

  /// Three rigid-body modes (x, y translation, rotation about the origin) as DoF vectors.
  std::array<Vec, 3> rigid_modes() const;

  Vec make_vector() const { return Vec(owned_, MPI_COMM_WORLD); }
  Vec make_ghosted() const { return Vec(owned_, relevant_, MPI_COMM_WORLD); }
  /// A ghosted copy of a vector (for reading it at cells).
  Vec ghosted(const Vec& v) const;

  /// A point located once in the mesh, evaluated by the rank that owns its cell: there the
  /// DoFs of the cell and the gradient (1/m) of each one's shape function at the point, so
  /// that reading the stress at the point again is a short sum; on the other ranks empty.
  struct Probe {
    unsigned int owner = 0;  // MPI rank
    std::vector<dealii::types::global_dof_index> dofs;
    std::vector<unsigned int> components;
    std::vector<dealii::Tensor<1, dim>> gradients;
  };
  /// The probes of points (collective); nullopt for a point outside the body. A point on a
  /// cell boundary goes to the cell that comes first in the mesh's cell order, whatever the
  /// partition, so that any rank count samples the same cell.
  std::vector<std::optional<Probe>> probes(const std::vector<Point>& points) const;
  /// Stresses of the displacement u (ghosted) at probes (collective): each owner evaluates its
  /// probes, and every rank receives all of them.
  std::vector<Stress2> stresses(const Vec& u, const std::vector<Probe>& probes) const;
  /// Each rank's cells as one VTU piece (DIRECTORY/STEM.RANK.vtu) and, from rank 0, the record
  /// that lists them (DIRECTORY/STEM.pvtu); u and the optional velocity ghosted. Collective.
  /// Returns the record's file name.
  std::string write_vtu(const Vec& u, const std::filesystem::path& directory, const std::string& stem,
                        const Vec* velocity = nullptr) const;

  const dealii::Mapping<dim>& mapping() const { return *mapping_; }
  const dealii::FiniteElement<dim>& fe() const { return *fe_; }

 private:
  /// Where a point lies in one of this rank's cells (index into cell_nodes_) and how well.
  struct Located {
    unsigned int cell = 0;
    Point unit;
    double outside = 0.0;  // unit-coordinate distance outside the cell, 0 inside
  };
  std::optional<Located> locate(const Point& p) const;
  Probe probe_at(const Located& where) const;
  Point geometry_map(unsigned int cell_index, const Point& unit, dealii::Tensor<2, dim>* jacobian) const;
  void build_triangulation(const meshes::Mesh& mesh, const Discretisation& disc);
  void build_geometry();
  void build_locator();
  std::size_t local(dealii::types::global_dof_index i) const { return relevant_.index_within_set(i); }

  Material material_;
  int degree_;
  Tria tria_;
  std::map<std::string, dealii::types::boundary_id> boundary_ids_;
  std::unique_ptr<dealii::FiniteElement<dim>> scalar_fe_;
  std::unique_ptr<dealii::FESystem<dim>> fe_;
  DofHandler dof_handler_;
  dealii::IndexSet owned_, relevant_;
  Vec geometry_;  // ghosted: support-point coordinates of the isoparametric mapping
  std::unique_ptr<dealii::MappingFEField<dim, dim, Vec>> mapping_;
  // Per locally relevant DoF (indexed by its place in relevant_).
  std::vector<Point> dof_points_;
  std::vector<unsigned int> component_;
  std::vector<dealii::types::global_dof_index> sibling_;
  // This rank's own cells, for point location: geometry support points, the cell, and its
  // place in the whole mesh's cell order (ties between cells of different ranks).
  std::vector<std::vector<Point>> cell_nodes_;
  std::vector<typename DofHandler::active_cell_iterator> cells_;
  std::vector<std::uint64_t> cell_order_;
  // Point location: a uniform grid of cell bounding boxes, the same grid on every rank (origin
  // and step from the whole mesh), stored over this rank's part of it only.
  Point grid_origin_;
  double grid_step_ = 0.0;
  std::array<unsigned int, dim> grid_first_{}, grid_count_{};
  std::vector<std::vector<unsigned int>> grid_cells_;
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

/// Sums values over the ranks, in place (each rank holds its part, zeros elsewhere).
void sum_over_ranks(double* values, std::size_t count);
/// True on the rank that writes files.
bool is_root();
/// True if this process is the only rank (it holds every row of every matrix).
bool single_rank();

}  // namespace ddafrac::fem::detail
