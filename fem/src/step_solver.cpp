#include "step_solver.hpp"

#include <Amesos.h>
#include <Amesos_BaseSolver.h>
#include <Epetra_LinearProblem.h>
#include <Teuchos_ParameterList.hpp>

#include "direct_solver.hpp"

namespace ddafrac::fem::detail {
namespace {

class Cholmod final : public StepSolver {
 public:
  explicit Cholmod(const Matrix& matrix) : direct_(matrix) {}
  int solve(Vec& x, const Vec& b) override {
    direct_.solve(x, b);
    return 0;
  }
  const char* name() const override { return DirectSolver::name; }

 private:
  DirectSolver direct_;
};

/// MUMPS through Trilinos Amesos: the factor is distributed over the ranks like the matrix.
/// The matrix is symmetric positive definite, so MUMPS factorises L D L^T (half the work and
/// memory of its default LU).
class Mumps final : public StepSolver {
 public:
  explicit Mumps(const Matrix& matrix) {
    problem_.SetOperator(const_cast<Epetra_CrsMatrix*>(&matrix.trilinos_matrix()));  // Amesos reads it only
    Amesos factory;
    solver_.reset(factory.Create("Amesos_Mumps", problem_));
    if (!solver_) throw FemError("Trilinos has no Amesos_Mumps");
    Teuchos::ParameterList parameters;
    parameters.set("MatrixProperty", "SPD");
    solver_->SetParameters(parameters);
    if (solver_->SymbolicFactorization() != 0 || solver_->NumericFactorization() != 0)
      throw FemError("MUMPS could not factorise the matrix");
  }
  int solve(Vec& x, const Vec& b) override {
    problem_.SetLHS(&x.trilinos_vector());
    problem_.SetRHS(const_cast<Epetra_MultiVector*>(&b.trilinos_vector()));  // read only
    if (solver_->Solve() != 0) throw FemError("MUMPS solve failed");
    return 0;
  }
  const char* name() const override { return "sparse LDL^T (MUMPS, distributed), factorised once"; }

 private:
  Epetra_LinearProblem problem_;
  std::unique_ptr<Amesos_BaseSolver> solver_;
};

class CgAmg final : public StepSolver {
 public:
  CgAmg(const Matrix& matrix, const Model& model, const SolverSettings& settings) : cg_(matrix, model, settings) {}
  int solve(Vec& x, const Vec& b) override { return cg_.solve(x, b); }
  const char* name() const override { return "CG + ML AMG (set up once, warm-started)"; }

 private:
  ElasticSolver cg_;
};

}  // namespace

std::unique_ptr<StepSolver> make_step_solver(StepSolverKind kind, const Matrix& matrix, const Model& model,
                                             const SolverSettings& cg) {
  if (kind == StepSolverKind::automatic) kind = single_rank() ? StepSolverKind::cholmod : StepSolverKind::mumps;
  switch (kind) {
    case StepSolverKind::cholmod: return std::make_unique<Cholmod>(matrix);
    case StepSolverKind::mumps: return std::make_unique<Mumps>(matrix);
    default: return std::make_unique<CgAmg>(matrix, model, cg);
  }
}

}  // namespace ddafrac::fem::detail
