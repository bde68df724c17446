#include "ddafrac/fem/environment.hpp"

#include <deal.II/base/mpi.h>

namespace ddafrac::fem {

struct Environment::Impl {
  // One thread per MPI rank: the FEM is parallelised with MPI, the DDA with OpenMP.
  Impl(int& argc, char**& argv) : mpi(argc, argv, 1) {}
  dealii::Utilities::MPI::MPI_InitFinalize mpi;
};

Environment::Environment(int& argc, char**& argv) : impl_(std::make_unique<Impl>(argc, argv)) {}
Environment::~Environment() = default;

int Environment::rank() { return static_cast<int>(dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD)); }
int Environment::size() { return static_cast<int>(dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD)); }

}  // namespace ddafrac::fem
