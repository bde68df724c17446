#pragma once
// Static, contact-free linear elasticity of a disc: Hondros arc loading, flattened disc with a
// loaded flat, or any disc mesh (e.g. with a slit) loaded on rim arcs.

#include <array>
#include <filesystem>
#include <memory>
#include <string>
#include <variant>
#include <vector>

#include "ddafrac/fem/elasticity.hpp"
#include "ddafrac/meshes/mesh.hpp"

namespace ddafrac::fem {

/// Uniform radial pressure on the rim arcs of half-angle `half_angle` about the top and bottom
/// points (Hondros). The arcs are the boundary groups "load_top"/"load_bottom" when the mesh
/// has them, otherwise the "rim" edges whose midpoint lies within the half-angle. The load is
/// self-equilibrated; the rigid-body modes are removed by three pinned components (the load
/// vector is made orthogonal to the rigid modes first, so the pins carry no force).
struct ArcPressure {
  double pressure = 0.0;    // Pa
  double half_angle = 0.0;  // rad
};

/// Flattened disc: the bottom flat ("flat_bottom") rests on rollers (u_y = 0, one node also
/// u_x = 0), the top flat ("flat_top") is pushed down by a uniform pressure or, if
/// `displacement` > 0, by a prescribed uniform downward displacement.
struct FlatLoad {
  double pressure = 0.0;      // Pa
  double displacement = 0.0;  // m
};

using StaticLoad = std::variant<ArcPressure, FlatLoad>;

struct StaticProblem {
  meshes::Mesh mesh;  // disc centred at the origin; cells all triangles or all quadrilaterals
  Material material;
  StaticLoad load;
  Discretisation discretisation;
  SolverSettings solver;
};

class StaticSolution {
 public:
  StaticSolution(StaticSolution&&) noexcept;
  StaticSolution& operator=(StaticSolution&&) noexcept;
  ~StaticSolution();

  // Under MPI every sampling call is collective: every rank calls it with the same points
  // (the rank whose cell holds a point evaluates it; every rank gets the answer).

  /// Stress at a point of the body (throws FemError outside it).
  StressSample stress_at(double x, double y) const;
  /// Up to n >= 2 samples from (x0, y0) to (x1, y1), both ends included; points outside the
  /// body (e.g. inside a slit) are left out.
  std::vector<StressSample> profile(double x0, double y0, double x1, double y1, int n) const;
  /// Resultant force (N per unit thickness) that the body exerts on the supports or loads of a
  /// boundary group, from the consistent nodal reactions (internal minus external forces).
  std::array<double, 2> boundary_force(const std::string& group) const;
  /// Resultant of the applied pressure on a boundary group (N per unit thickness).
  std::array<double, 2> applied_force(const std::string& group) const;
  /// ParaView files with displacement, sxx, syy, txy, s1, s3: the record DIR/STEM.pvtu and,
  /// beside it, one piece per MPI rank, DIR/STEM.RANK.vtu (each written whole). Collective.
  void write_vtu(const std::filesystem::path& record) const;
  const RunStats& stats() const;

  struct Impl;
  explicit StaticSolution(std::unique_ptr<Impl> impl);

 private:
  std::unique_ptr<Impl> impl_;
};

StaticSolution solve_static(const StaticProblem& problem);

}  // namespace ddafrac::fem
