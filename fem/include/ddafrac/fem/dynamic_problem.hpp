#pragma once
// Contact-free elastodynamics of a disc: the disc moves at v0 towards the plate and the impact
// patch is held (u = 0) from t = 0, launching the impact waves; or, as an option, the disc loaded
// by a prescribed pressure pulse on the patch. Newmark time stepping with a
// selectable (beta, gamma); consistent mass; the effective matrix is built once and factorised
// once (sparse Cholesky on one rank, MUMPS distributed over several) or given an AMG once.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "ddafrac/fem/elasticity.hpp"
#include "ddafrac/meshes/mesh.hpp"

namespace ddafrac::fem {

/// (1/4, 1/2): trapezoidal rule, energy conserving, second order.
/// (1/2, 1): the DDA's scheme, first order and dissipative.
struct Newmark {
  double beta = 0.25;
  double gamma = 0.5;
};

/// Prescribed pressure pulse on the impact patch instead of holding it: p(t) = peak sin(pi t / T)
/// for 0 <= t <= T, then 0 (positive pushes into the body). The patch is then free.
struct TractionPulse {
  double peak = 0.0;      // Pa
  double duration = 0.0;  // s, T
  double pressure(double t) const;
};

/// Linear solver of the effective matrix K + c_u M of the Newmark step.
enum class StepSolverKind {
  automatic,  // cholmod on one MPI rank, mumps on more
  cholmod,    // sparse Cholesky (SuiteSparse), whole on every rank: gathers the matrix
  mumps,      // sparse LDL^T (MUMPS through Trilinos Amesos), distributed like the matrix
  cg_amg,     // CG + ML AMG, warm-started from the previous step, stopped at `cg`
};

// CG's stopping criterion for the Newmark step, |r| <= tol |b|: b = M (c_u u + ...) is large
// beside the step's stress, so this is tighter than the static problem's 1e-10.
constexpr double kStepCgTolerance = 1e-13;

struct GaugePoint {
  std::string name;
  double x = 0.0;  // m
  double y = 0.0;  // m
};

struct DynamicProblem {
  meshes::Mesh mesh;
  Material material;
  Discretisation discretisation;
  Newmark newmark;
  double v0 = 3.5;                          // m/s, initial speed of the disc towards -y
  std::string held_group = "impact_patch";  // boundary group held from t = 0 (or pulsed)
  /// If set, the patch is loaded by this pulse instead of held (v0 still sets the initial rigid
  /// motion; use 0 for a disc at rest).
  std::optional<TractionPulse> pulse;
  double dt = 1e-7;               // s
  double end_time = 20e-6;        // s
  double output_interval = 1e-7;  // s between gauge/energy samples
  std::vector<GaugePoint> gauges;
  StepSolverKind step_solver = StepSolverKind::automatic;
  SolverSettings cg{kStepCgTolerance, SolverSettings{}.max_iterations};  // for cg_amg
  /// With a directory and an interval > 0: VTU snapshots (displacement, velocity, sxx, syy,
  /// txy, s1, s3) at t = 0 and every interval: the record vtk/snapshot_NNNNNN.pvtu with one
  /// piece per MPI rank, vtk/snapshot_NNNNNN.RANK.vtu (each rank writes its own cells), the
  /// records listed in run.pvd (rewritten after each snapshot by rank 0). Files are written whole.
  std::filesystem::path snapshot_directory;
  double snapshot_interval = 0.0;  // s
};

struct GaugeRecord {
  double t = 0.0;         // s
  std::size_t gauge = 0;  // index into DynamicProblem::gauges
  StressSample sample;
};

struct EnergyRecord {
  double t = 0.0;        // s
  double kinetic = 0.0;  // J per unit thickness
  double strain = 0.0;   // J per unit thickness
};

struct SnapshotRecord {
  double t = 0.0;    // s
  std::string file;  // the .pvtu record, relative to the snapshot directory
};

/// Wall time of the setup by phase (s); their sum is RunStats::setup_seconds.
struct SetupTimes {
  double model = 0.0;     // triangulation (whole mesh built and partitioned on every rank), DoFs, geometry
  double assembly = 0.0;  // constraints, gauges located, K and M assembled
  double solver = 0.0;    // factorisation or AMG set-up of K + c_u M
};

/// Wall time of the time loop by phase, summed over all steps (s): where a step's time goes.
struct StepTimes {
  double rhs = 0.0;     // Newmark right-hand side: vector updates and the product with M
  double solve = 0.0;   // the linear solve of the effective system
  double update = 0.0;  // acceleration, velocity and displacement from the solution
  double gauges = 0.0;  // stress at the gauge points
  double energy = 0.0;  // kinetic and strain energy
  double output = 0.0;  // VTU snapshots
};

struct DynamicResult {
  std::vector<GaugeRecord> gauges;
  std::vector<SnapshotRecord> snapshots;
  std::vector<EnergyRecord> energy;
  RunStats stats;
  SetupTimes setup;
  StepTimes times;
  int steps = 0;
};

DynamicResult run_dynamic(const DynamicProblem& problem);

}  // namespace ddafrac::fem
