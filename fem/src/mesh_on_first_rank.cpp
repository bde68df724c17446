#include "ddafrac/fem/mesh_on_first_rank.hpp"

#include <deal.II/base/mpi.h>

#include <boost/serialization/string.hpp>
#include <boost/serialization/vector.hpp>

#include <string>
#include <utility>
#include <vector>

#include "ddafrac/meshes/generate.hpp"

namespace ddafrac::fem {

namespace {

/// What the other ranks learn from rank 0's meshing: the group names, or why it failed.
struct MeshingOutcome {
  std::vector<std::string> boundary_names;
  bool failed = false;
  std::string error;

  template <class Archive>
  void serialize(Archive& archive, const unsigned int /*version*/) {
    archive& boundary_names& failed& error;
  }
};

}  // namespace

meshes::Mesh mesh_on_first_rank(const std::function<meshes::Mesh()>& generate) {
  constexpr unsigned int first_rank = 0;
  const MPI_Comm comm = MPI_COMM_WORLD;
  const bool first = dealii::Utilities::MPI::this_mpi_process(comm) == first_rank;
  meshes::Mesh mesh;
  MeshingOutcome outcome;
  if (first) {
    try {
      mesh = generate();
      outcome.boundary_names = mesh.boundary_names;
    } catch (const meshes::MeshError& e) {
      outcome.failed = true;
      outcome.error = e.what();
    }
  }
  if (dealii::Utilities::MPI::n_mpi_processes(comm) > 1)
    outcome = dealii::Utilities::MPI::broadcast(comm, outcome, first_rank);
  if (outcome.failed) throw meshes::MeshError(outcome.error);
  if (!first) mesh.boundary_names = std::move(outcome.boundary_names);
  return mesh;
}

}  // namespace ddafrac::fem
