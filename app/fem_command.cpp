// `ddafrac fem SCENE [--degree p] [--refine k] [--out DIR]`: the deal.II continuum reference of
// the scene's disc. Static scenes (plain disc with load arcs, flattened disc, slit disc) give
// the stress field, profiles along both diameters, gauges and a VTU; the impact scene gives the
// elastodynamic gauge histories (the disc moving at v0 with the impact patch held from t = 0),
// energies and VTU snapshots listed in run.pvd. Under mpirun rank 0 alone meshes, and each rank
// holds and writes only its part of the mesh (VTU pieces under a .pvtu record); rank 0 writes
// the rest.

#include <fmt/core.h>
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <sstream>
#include <variant>

#include "commands.hpp"
#include "ddafrac/build_commit.hpp"
#include "ddafrac/common/angles.hpp"
#include "ddafrac/common/whole_file.hpp"
#include "ddafrac/coupling/scene_fem.hpp"
#include "ddafrac/fem/dynamic_problem.hpp"
#include "ddafrac/fem/mesh_on_first_rank.hpp"
#include "ddafrac/fem/static_problem.hpp"
#include "ddafrac/meshes/generate.hpp"
#include "fem_session.hpp"
#include "option_checks.hpp"
#include "scene_source.hpp"

namespace ddafrac::app {

namespace {

constexpr double default_load = 1.0e6;               // N/m, nominal diametral load
constexpr double default_arc_half_angle_deg = 10.0;  // Hondros arcs when the geometry has none
constexpr int profile_points = 201;

struct FemArguments {
  SceneArguments scene;
  std::string out;
  int degree = 2;
  int refine = 0;
  bool quads = false;
  double element_size = 0.0;  // m; 0 = D/25
  double load = default_load;
  double arc_half_angle_deg = default_arc_half_angle_deg;
  double end_time = 0.0;           // s; 0 = the scene's
  double dt = 0.0;                 // s; 0 = the scene's dt_max
  double snapshot_interval = 0.0;  // s; 0 = the scene's output_interval
  double pulse_peak = 0.0;         // Pa; > 0: the patch is loaded by a half-sine pulse, not held
  double pulse_duration = 4e-6;    // s
  fem::StepSolverKind step_solver = fem::StepSolverKind::automatic;
};

/// Under mpirun every rank computes; rank 0 alone writes the CSVs and summary and prints (each
/// rank writes its own VTU piece).
bool is_root() { return fem::Environment::rank() == 0; }

void write_output(const std::filesystem::path& path, const std::string& text) {
  if (is_root()) common::write_whole_text(path, text);
}

std::string sample_row(const std::string& label, double t, const fem::StressSample& s) {
  return fmt::format("{:.9g},{},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g}\n", t, label, s.stress.xx, s.stress.yy, s.stress.xy,
                     s.s1, s.s3);
}
constexpr const char* gauge_header = "t,gauge,sxx,syy,txy,s1,s3\n";

nlohmann::json stats_json(const fem::RunStats& s) {
  return {{"cells", s.cells},
          {"n_dofs", s.dofs},
          {"solver", s.solver},
          {"iterations", s.iterations},
          {"setup_seconds", s.setup_seconds},
          {"solve_seconds", s.solve_seconds}};
}

/// Where a dynamic step's time goes: ms per step by phase.
nlohmann::json step_times_json(const fem::DynamicResult& r) {
  const auto ms = [&](double seconds) { return 1e3 * seconds / std::max(r.steps, 1); };
  const auto& t = r.times;
  return {{"rhs", ms(t.rhs)},
          {"solve", ms(t.solve)},
          {"update", ms(t.update)},
          {"gauges", ms(t.gauges)},
          {"energy", ms(t.energy)},
          {"output", ms(t.output)},
          {"total", ms(r.stats.solve_seconds)}};
}

nlohmann::json run_static(const FemArguments& args, const scene::Scene& s, meshes::Mesh mesh,
                          const std::filesystem::path& out) {
  const double d = coupling::disc_diameter(s.geometry);
  fem::StaticProblem problem;
  problem.mesh = std::move(mesh);
  problem.material = coupling::disc_material(s);
  problem.discretisation = {args.degree, args.refine};
  nlohmann::json load;
  if (const auto* flattened = std::get_if<meshes::FlattenedDisc>(&s.geometry)) {
    const double width = d * std::sin(0.5 * flattened->flat_angle);
    problem.load = fem::FlatLoad{args.load / width, 0.0};
    load = {{"kind", "flat pressure"}, {"load_N_per_m", args.load}, {"pressure_Pa", args.load / width}};
  } else {
    const auto* plain = std::get_if<meshes::PlainDisc>(&s.geometry);
    const double alpha =
        plain && plain->load_half_angle > 0.0 ? plain->load_half_angle : args.arc_half_angle_deg * common::kPi / 180.0;
    const double pressure = args.load / (alpha * d);
    problem.load = fem::ArcPressure{pressure, alpha};
    load = {{"kind", "Hondros arc pressure"},
            {"load_N_per_m", args.load},
            {"half_angle_rad", alpha},
            {"pressure_Pa", pressure}};
  }
  const auto solution = fem::solve_static(problem);

  std::ostringstream profiles;
  profiles << "profile,x,y,sxx,syy,txy,s1,s3\n";
  const double r = 0.5 * d * (1.0 - 1e-9);
  const auto* flat = std::get_if<meshes::FlattenedDisc>(&s.geometry);
  const double ry = flat ? r * std::cos(0.5 * flat->flat_angle) : r;  // the flats end the diameter
  for (const auto& [name, x0, y0, x1, y1] :
       {std::tuple{"loaded", 0.0, -ry, 0.0, ry}, std::tuple{"horizontal", -r, 0.0, r, 0.0}}) {
    for (const auto& p : solution.profile(x0, y0, x1, y1, profile_points))
      profiles << fmt::format("{},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g}\n", name, p.x, p.y, p.stress.xx,
                              p.stress.yy, p.stress.xy, p.s1, p.s3);
  }
  write_output(out / "profiles.csv", profiles.str());
  std::string gauges = gauge_header;
  for (const auto& g : s.gauges) gauges += sample_row(g.name, 0.0, solution.stress_at(g.position[0], g.position[1]));
  write_output(out / "gauges.csv", gauges);
  solution.write_vtu(out / "stress.pvtu");
  nlohmann::json summary{{"kind", "static"}, {"load", load}, {"stats", stats_json(solution.stats())}};
  const auto centre = solution.profile(0.0, 0.0, 0.0, 0.0, 2);  // empty inside a slit
  if (!centre.empty())
    summary["centre"] = {{"sxx", centre[0].stress.xx}, {"syy", centre[0].stress.yy}, {"txy", centre[0].stress.xy}};
  return summary;
}

nlohmann::json run_dynamic(const FemArguments& args, const scene::Scene& s, meshes::Mesh mesh,
                           const std::filesystem::path& out) {
  fem::DynamicProblem problem;
  problem.mesh = std::move(mesh);
  problem.material = coupling::disc_material(s);
  problem.discretisation = {args.degree, args.refine};
  for (const auto& b : s.bodies)
    if (b.role == scene::Role::Disc) problem.v0 = std::hypot(b.initial_velocity[0], b.initial_velocity[1]);
  problem.dt = args.dt > 0.0 ? args.dt : s.analysis.dt_max;
  problem.end_time = args.end_time > 0.0 ? args.end_time : s.analysis.end_time;
  problem.output_interval = std::max(s.analysis.output_interval, problem.dt);
  for (const auto& g : s.gauges) problem.gauges.push_back({g.name, g.position[0], g.position[1]});
  nlohmann::json loading = {{"kind", "held patch"}, {"v0", problem.v0}};
  if (args.pulse_peak > 0.0) {  // a disc at rest, the patch loaded by the pulse
    problem.v0 = 0.0;
    problem.pulse = fem::TractionPulse{args.pulse_peak, args.pulse_duration};
    loading = {{"kind", "half-sine pressure pulse"}, {"peak_Pa", args.pulse_peak}, {"duration_s", args.pulse_duration}};
  }
  problem.step_solver = args.step_solver;
  if (s.output.vtk) {  // vtk/snapshot_*.pvtu (+ a .vtu piece per rank) and run.pvd
    problem.snapshot_directory = out;
    problem.snapshot_interval = args.snapshot_interval > 0.0 ? args.snapshot_interval : problem.output_interval;
  }
  const auto result = fem::run_dynamic(problem);
  std::string gauges = gauge_header;
  for (const auto& g : result.gauges) gauges += sample_row(problem.gauges[g.gauge].name, g.t, g.sample);
  write_output(out / "gauges.csv", gauges);
  std::string energy = "t,kinetic,strain\n";
  for (const auto& e : result.energy) energy += fmt::format("{:.9g},{:.9g},{:.9g}\n", e.t, e.kinetic, e.strain);
  write_output(out / "energy.csv", energy);
  return {{"kind", "dynamic"},
          {"loading", loading},
          {"v0", problem.v0},
          {"dt", problem.dt},
          {"end_time", problem.end_time},
          {"steps", result.steps},
          {"snapshots", result.snapshots.size()},
          {"newmark", {{"beta", problem.newmark.beta}, {"gamma", problem.newmark.gamma}}},
          {"stats", stats_json(result.stats)},
          {"setup_seconds",
           {{"model", result.setup.model}, {"assembly", result.setup.assembly}, {"solver", result.setup.solver}}},
          {"step_ms", step_times_json(result)}};
}

void run_fem(const FemArguments& args) {
  const FemSession fem_session;
  const scene::Scene s = args.scene.load();
  const auto out = output_directory(args.out, s, "fem");
  if (is_root()) std::filesystem::create_directories(out);
  const auto start = std::chrono::steady_clock::now();
  const double size = args.element_size > 0.0 ? args.element_size
                                              : coupling::disc_diameter(s.geometry) / coupling::kFemElementsPerDiameter;
  meshes::Geometry geometry = s.geometry;
  if (auto* flat = std::get_if<meshes::FlattenedDisc>(&geometry)) flat->with_platens = false;
  nlohmann::json summary;
  try {
    const auto cells = args.quads ? meshes::FemCells::Quadrilaterals : meshes::FemCells::Triangles;
    auto mesh = fem::mesh_on_first_rank([&] { return meshes::generate_fem_mesh(geometry, size, cells); });
    summary = std::holds_alternative<meshes::ImpactDisc>(geometry) ? run_dynamic(args, s, std::move(mesh), out)
                                                                   : run_static(args, s, std::move(mesh), out);
  } catch (const meshes::MeshError& e) {
    throw CommandFailed(fmt::format("{}: cannot mesh the scene: {}", s.source.string(), e.what()));
  } catch (const fem::FemError& e) {
    throw CommandFailed(fmt::format("{}: FEM: {}", s.source.string(), e.what()));
  }
  summary["scene"] = s.name;
  summary["version"] = DDAFRAC_VERSION;
  summary["commit"] = DDAFRAC_COMMIT;
  summary["arch"] = DDAFRAC_ARCH;
  summary["degree"] = args.degree;
  summary["refinements"] = args.refine;
  summary["cells"] = args.quads ? "quadrilaterals" : "triangles";
  summary["element_size_m"] = size;
  summary["mpi_ranks"] = fem::Environment::size();
  summary["wall_seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  summary["exit_status"] = "ok";
  write_output(out / "summary.json", summary.dump(2) + "\n");
  if (is_root())
    fmt::print("wrote {} ({} dofs, {:.2f} s)\n", out.string(), summary["stats"]["n_dofs"].get<std::size_t>(),
               summary["wall_seconds"].get<double>());
}

}  // namespace

void register_fem_command(CLI::App& app) {
  auto args = std::make_shared<FemArguments>();
  CLI::App* command =
      app.add_subcommand("fem", "deal.II continuum reference of the scene's disc (static or impact dynamics)");
  args->scene.add_to(*command);
  command->add_option("--out", args->out, "output directory (default runs/<scene name>/fem)");
  add_fem_degree_option(*command, "--degree", args->degree);
  command->add_option("--refine", args->refine, "uniform refinements of the FEM mesh")
      ->check(CLI::Range(0, 6))
      ->capture_default_str();
  command->add_flag("--quads", args->quads, "quadrilateral cells (FE_Q) instead of triangles (FE_SimplexP)");
  command->add_option("--element-size", args->element_size, "FEM element size in m (default D/25)");
  command->add_option("--load", args->load, "static diametral load in N per m of thickness")->capture_default_str();
  command
      ->add_option("--arc-half-angle", args->arc_half_angle_deg,
                   "Hondros arc half-angle in degrees when the geometry has no load arcs")
      ->capture_default_str();
  command->add_option("--end-time", args->end_time, "dynamic end time in s (default: the scene's)");
  command->add_option("--dt", args->dt, "dynamic time step in s (default: the scene's dt_max)");
  command->add_option("--pulse", args->pulse_peak,
                      "dynamic: load the impact patch of a disc at rest by a half-sine pressure pulse of this peak "
                      "(Pa) instead of holding it");
  command->add_option("--pulse-duration", args->pulse_duration,
                      "duration of the --pulse half-sine in s (default 4e-6)");
  const std::map<std::string, fem::StepSolverKind> step_solvers{{"auto", fem::StepSolverKind::automatic},
                                                                {"cholmod", fem::StepSolverKind::cholmod},
                                                                {"mumps", fem::StepSolverKind::mumps},
                                                                {"cg", fem::StepSolverKind::cg_amg}};
  command
      ->add_option("--step-solver", args->step_solver,
                   "dynamic: solver of the Newmark step: auto (cholmod on one MPI rank, mumps on more), cholmod "
                   "(serial sparse Cholesky), mumps (distributed sparse LDL^T), cg (CG + AMG)")
      ->transform(CLI::CheckedTransformer(step_solvers, CLI::ignore_case));
  command->add_option("--snapshot-interval", args->snapshot_interval,
                      "dynamic VTU snapshot interval in s (default: the scene's output_interval; none if the scene's "
                      "output.vtk is false)");
  command->callback([args] { run_fem(*args); });
}

}  // namespace ddafrac::app
