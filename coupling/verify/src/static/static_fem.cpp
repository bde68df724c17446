#include "static/static_fem.hpp"

#include <chrono>

#include "ddafrac/coupling/scene_fem.hpp"
#include "ddafrac/meshes/generate.hpp"

namespace ddafrac::coupling {

StaticFemRun run_static_fem(const scene::Scene& scene, const StaticSetup& st, const VerifyOptions& o) {
  StaticFemRun out;
  const auto start = std::chrono::steady_clock::now();
  out.element_size = st.diameter / kFemElementsPerDiameter;
  fem::StaticProblem problem;
  problem.mesh = meshes::generate_fem_mesh(st.fem_geometry, out.element_size, meshes::FemCells::Triangles);
  problem.material = disc_material(scene);
  problem.discretisation = {o.fem_degree, o.fem_refine};
  if (st.flattened)
    problem.load = fem::FlatLoad{st.pressure, 0.0};
  else
    problem.load = fem::ArcPressure{st.pressure, st.half_angle};
  out.solution.emplace(fem::solve_static(problem));
  out.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  out.dofs = out.solution->stats().dofs;
  out.cells = out.solution->stats().cells;
  out.iterations = out.solution->stats().iterations;
  return out;
}

std::optional<reference::Stress2> fem_stress_at(const fem::StaticSolution& s, double x, double y) {
  for (int k = 0; k <= kFemPullSteps; ++k) {
    const double f = 1.0 - kFemPullStep * k;
    try {
      return s.stress_at(f * x, f * y).stress;
    } catch (const fem::FemError&) {
    }
  }
  return std::nullopt;
}

}  // namespace ddafrac::coupling
