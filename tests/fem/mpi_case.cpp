// Helper of fem_mpi (issue 5, test 5): solves a small static Hondros disc and a short
// impact response, and rank 0 writes the centre, profile and gauge values to the CSV named on
// the command line, and the impact's VTU snapshots beside it (OUT_vtk/run.pvd). Run serially and
// under `mpirun -np 2`; the test compares the two. Every rank writes how many mesh nodes it was
// given (OUT.rankK.mesh): only rank 0 meshes. `fem_mpi_case --mesh-error OUT` meshes with a
// generator that fails: every rank writes the error it got (OUT.rankK.error) and exits with 1.

#include <fmt/core.h>

#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>

#include "ddafrac/fem/dynamic_problem.hpp"
#include "ddafrac/fem/environment.hpp"
#include "ddafrac/fem/mesh_on_first_rank.hpp"
#include "ddafrac/fem/static_problem.hpp"
#include "ddafrac/meshes/generate.hpp"
#include "disc_mesh.hpp"

using namespace ddafrac;

namespace {

constexpr double diameter = 0.1;                             // m
constexpr double half_angle = 10.0 * test::test_pi / 180.0;  // Hondros 2 alpha = 20 deg
constexpr double load = 1.0e6;                               // N/m
constexpr int coarse_rings = 6;
constexpr int profile_points = 11;
const reference::Elastic rock{10.53e9, 0.12, 2050.0};

/// Beside OUT, this rank's file OUT.rankK.SUFFIX holding `text`.
void write_rank_file(const std::filesystem::path& out, const std::string& suffix, const std::string& text) {
  std::ofstream(out.string() + fmt::format(".rank{}.{}", fem::Environment::rank(), suffix)) << text << "\n";
}

void write_static(bool quads, std::ofstream& out) {
  fem::StaticProblem p;
  p.mesh = fem::mesh_on_first_rank([quads] {
    auto mesh = test::ring_disc(0.5 * diameter, coarse_rings, half_angle);
    return quads ? test::split_into_quads(mesh, 0.5 * diameter) : mesh;
  });
  p.material.elastic = rock;
  p.load = fem::ArcPressure{load / (half_angle * diameter), half_angle};
  p.discretisation = {2, 1};
  const auto s = fem::solve_static(p);
  const std::string kind = quads ? "static_quad" : "static_tri";
  const double r = 0.45 * diameter;
  for (const auto& [name, x0, y0, x1, y1] :
       {std::tuple{"loaded", 0.0, -r, 0.0, r}, std::tuple{"horizontal", -r, 0.0, r, 0.0}}) {
    int k = 0;
    for (const auto& q : s.profile(x0, y0, x1, y1, profile_points)) {
      out << fmt::format("{},{}{},sxx,{:.17g}\n", kind, name, k, q.stress.xx);
      out << fmt::format("{},{}{},syy,{:.17g}\n", kind, name, k, q.stress.yy);
      out << fmt::format("{},{}{},txy,{:.17g}\n", kind, name, k++, q.stress.xy);
    }
  }
  std::fprintf(stderr, "%s: %zu dofs, %d CG iterations, %.2f s\n", kind.c_str(), s.stats().dofs, s.stats().iterations,
               s.stats().setup_seconds + s.stats().solve_seconds);
}

void write_dynamic(std::ofstream& out, const std::filesystem::path& csv) {
  meshes::ImpactDisc g;
  g.diameter = diameter;
  g.joint_angle = 0.0;
  g.connectivity = 0.25;
  g.patch_half_angle = 0.3;
  fem::DynamicProblem p;
  p.mesh = fem::mesh_on_first_rank([&g] { return meshes::generate_fem_mesh(g, 0.003, meshes::FemCells::Triangles); });
  write_rank_file(csv, "mesh", std::to_string(p.mesh.nodes.size()));
  p.material.elastic = rock;
  p.discretisation = {2, 0};
  p.v0 = 3.5;
  p.dt = 0.1e-6;
  p.end_time = 6e-6;
  p.output_interval = 1e-6;
  for (const double h : {0.003, 0.010, 0.020}) p.gauges.push_back({fmt::format("h{}", h), 0.0, -0.5 * diameter + h});
  p.gauges.push_back({"off_axis", 0.012, -0.02});
  p.snapshot_directory = csv.parent_path() / (csv.stem().string() + "_vtk");
  p.snapshot_interval = 2e-6;
  const auto r = fem::run_dynamic(p);
  for (const auto& rec : r.gauges) {
    const auto& name = p.gauges[rec.gauge].name;
    out << fmt::format("dynamic,{}@{:.3g},sxx,{:.17g}\n", name, rec.t, rec.sample.stress.xx);
    out << fmt::format("dynamic,{}@{:.3g},syy,{:.17g}\n", name, rec.t, rec.sample.stress.yy);
    out << fmt::format("dynamic,{}@{:.3g},txy,{:.17g}\n", name, rec.t, rec.sample.stress.xy);
  }
  for (const auto& e : r.energy) out << fmt::format("energy,{:.3g},total,{:.17g}\n", e.t, e.kinetic + e.strain);
  std::fprintf(stderr, "dynamic: %zu dofs, %d steps, %s, %.2f s\n", r.stats.dofs, r.steps, r.stats.solver.c_str(),
               r.stats.setup_seconds + r.stats.solve_seconds);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const fem::Environment environment(argc, argv);
    if (argc == 3 && std::string(argv[1]) == "--mesh-error") {
      try {
        fem::mesh_on_first_rank([]() -> meshes::Mesh { throw meshes::MeshError("the test's generator fails"); });
      } catch (const meshes::MeshError& e) {
        write_rank_file(argv[2], "error", e.what());
        return 1;
      }
      return 0;
    }
    if (argc != 2) {
      std::fprintf(stderr, "usage: fem_mpi_case OUT.csv | fem_mpi_case --mesh-error OUT\n");
      return 2;
    }
    const bool root = fem::Environment::rank() == 0;
    std::ofstream out;
    if (root) out.open(argv[1]);  // the other ranks write into a closed stream (ignored)
    out << "case,point,quantity,value\n";
    write_static(false, out);
    write_static(true, out);
    write_dynamic(out, argv[1]);
    if (root && !out) {
      std::fprintf(stderr, "cannot write %s\n", argv[1]);
      return 1;
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fem_mpi_case: %s\n", e.what());
    return 1;
  }
}
