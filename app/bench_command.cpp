// `ddafrac bench`: µs per block-step in total and per phase, for each thread count; table + JSON +
// CSV. Either a glued ring-triangulated disc impacting a plate at several block counts (scaling),
// or the first steps of a real scene (`--scene FILE [--set key=value]`), medians of repeats.

#include <fmt/core.h>
#include <omp.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <filesystem>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "ddafrac/common/whole_file.hpp"
#include "ddafrac/dda/drive.hpp"
#include "ddafrac/dda/run.hpp"
#include "ddafrac/dda/synthetic.hpp"
#include "machine_ceiling.hpp"
#include "option_checks.hpp"
#include "scene_source.hpp"

namespace ddafrac::app {

namespace {

/// The smallest ring disc dda::make_ring_disc_mesh makes: its centre hexagon, six triangles
/// (a smaller target would silently bench those six).
constexpr long long kSmallestRingDisc = 6;
/// Beyond this the engine's memory, not its speed, is what a bench would measure.
constexpr long long kMaxBenchBlocks = 1'000'000;

struct BenchArguments {
  std::vector<int> blocks{1000, 2000, 4000, 8000, 16000};
  std::string scene_file;              // --scene: bench this scene's first steps instead
  std::vector<std::string> overrides;  // --set for --scene
  int repeat = 1;                      // runs per case; the median by total time is reported
  std::vector<int> threads{1, 2};
  int steps = 50;
  int warmup = 5;
  std::string solver;  // empty: the scene's analysis.solver (pcg for the synthetic disc)
  std::string out = "runs/bench";
  bool ceiling = true;  // measure the machine's own parallel ceiling first
};

struct BenchRow {
  int target = 0;
  std::size_t blocks = 0, contacts = 0;
  int threads = 0;
  long steps = 0;
  double cg_mean = 0.0;
  dda::PhaseTimes us;  // µs per block-step
};

/// One bench case: the scene and mesh to run, and the target block count it stands for.
struct BenchCase {
  scene::Scene scene;
  meshes::Mesh mesh;
  int target = 0;
};

/// `count` steps, each as long as the engine allows (no end time).
void take_steps(dda::Engine& e, int count) {
  int taken = 0;
  dda::DriveHooks hooks;
  hooks.before_step = [&] { return taken++ < count ? dda::Next::Continue : dda::Next::Stop; };
  dda::drive(e, std::numeric_limits<double>::infinity(), hooks);
}

BenchRow bench_one(const BenchCase& bc, int threads, const BenchArguments& a) {
  omp_set_num_threads(threads);
  dda::EngineOptions o;
  o.solver.kind = wants_direct_solver(a.solver, bc.scene) ? dda::SolverKind::Direct : dda::SolverKind::Pcg;
  dda::Engine e(bc.scene, bc.mesh, o);
  take_steps(e, a.warmup);
  const dda::Statistics before = e.statistics();
  take_steps(e, a.steps);
  const dda::Statistics& after = e.statistics();
  BenchRow r;
  r.target = bc.target;
  r.blocks = e.blocks().block_count();
  r.contacts = e.contacts().contacts.size();
  r.threads = threads;
  r.steps = after.steps - before.steps;
  const long solves = after.solves - before.solves;
  r.cg_mean = solves > 0 ? static_cast<double>(after.cg_total - before.cg_total) / static_cast<double>(solves) : 0.0;
  const double scale = 1e6 / (static_cast<double>(r.blocks) * static_cast<double>(r.steps));
  r.us.detection = (after.times.detection - before.times.detection) * scale;
  r.us.assembly = (after.times.assembly - before.times.assembly) * scale;
  r.us.solve = (after.times.solve - before.times.solve) * scale;
  r.us.judgement = (after.times.judgement - before.times.judgement) * scale;
  r.us.fracture = (after.times.fracture - before.times.fracture) * scale;
  r.us.update = (after.times.update - before.times.update) * scale;
  return r;
}

/// The row of median total time among `repeat` runs of one case.
BenchRow bench_median(const BenchCase& bc, int threads, const BenchArguments& a) {
  std::vector<BenchRow> runs;
  for (int k = 0; k < a.repeat; ++k) runs.push_back(bench_one(bc, threads, a));
  std::sort(runs.begin(), runs.end(), [](const BenchRow& p, const BenchRow& q) { return p.us.total() < q.us.total(); });
  return runs[runs.size() / 2];
}

std::vector<BenchCase> bench_cases(const BenchArguments& a) {
  std::vector<BenchCase> cases;
  if (!a.scene_file.empty()) {
    scene::Scene s = SceneArguments{a.scene_file, a.overrides}.load();
    meshes::Mesh mesh = dda_mesh(s);
    const int target = s.mesh.target_blocks;
    cases.push_back({std::move(s), std::move(mesh), target});
    return cases;
  }
  check_memory_for_blocks(*std::max_element(a.blocks.begin(), a.blocks.end()), "--blocks");
  for (int target : a.blocks)
    cases.push_back({dda::make_impact_scene(3.5, 1.0), dda::make_ring_disc_mesh(0.1, target), target});
  return cases;
}

void run_bench(const BenchArguments& a) {
  const std::filesystem::path out = a.out;
  std::filesystem::create_directories(out);
  std::vector<BenchRow> rows;
  nlohmann::json ceiling;
  const int most_threads = *std::max_element(a.threads.begin(), a.threads.end());
  if (a.ceiling && most_threads > 1) {
    const MachineCeiling m = measure_machine_ceiling(most_threads);
    fmt::print("machine ceiling with {} threads: compute-bound kernel {:.2f}x, memory-bound kernel {:.2f}x\n",
               m.threads, m.compute_speedup, m.memory_speedup);
    ceiling = {{"threads", m.threads}, {"compute_speedup", m.compute_speedup}, {"memory_speedup", m.memory_speedup}};
  }
  fmt::print("{}, {} steps after {} warm-up steps, solver {}, median of {}; µs per block-step\n",
             a.scene_file.empty() ? std::string("glued disc impacting a plate") : a.scene_file, a.steps, a.warmup,
             a.solver.empty() ? std::string("of the scene") : a.solver, a.repeat);
  fmt::print("{:>7} {:>8} {:>7} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9} {:>7} {:>8}\n", "blocks", "contacts",
             "threads", "total", "detect", "assemble", "solve", "judge", "fracture", "update", "cg/it", "speedup");
  for (const BenchCase& bc : bench_cases(a)) {
    double base = 0.0;
    for (int t : a.threads) {
      const BenchRow r = bench_median(bc, t, a);
      if (base == 0.0) base = r.us.total();
      fmt::print(
          "{:>7} {:>8} {:>7} {:>9.3f} {:>9.3f} {:>9.3f} {:>9.3f} {:>9.3f} {:>9.3f} {:>9.3f} {:>7.2f} {:>7.2f}x\n",
          r.blocks, r.contacts, r.threads, r.us.total(), r.us.detection, r.us.assembly, r.us.solve, r.us.judgement,
          r.us.fracture, r.us.update, r.cg_mean, base / r.us.total());
      std::fflush(stdout);
      rows.push_back(r);
    }
  }
  nlohmann::json cases = nlohmann::json::array();
  std::string csv =
      "blocks,contacts,threads,steps,total_us,detection_us,assembly_us,solve_us,judgement_us,fracture_us,update_us,cg_"
      "mean\n";
  for (const BenchRow& r : rows) {
    cases.push_back({{"blocks", r.blocks},
                     {"contacts", r.contacts},
                     {"threads", r.threads},
                     {"steps", r.steps},
                     {"us_per_block_step",
                      {{"total", r.us.total()},
                       {"detection", r.us.detection},
                       {"assembly", r.us.assembly},
                       {"solve", r.us.solve},
                       {"judgement", r.us.judgement},
                       {"fracture", r.us.fracture},
                       {"update", r.us.update}}},
                     {"cg_iterations_mean", r.cg_mean}});
    csv += fmt::format("{},{},{},{},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.3f}\n", r.blocks, r.contacts,
                       r.threads, r.steps, r.us.total(), r.us.detection, r.us.assembly, r.us.solve, r.us.judgement,
                       r.us.fracture, r.us.update, r.cg_mean);
  }
  const nlohmann::json j = {{"scene", a.scene_file.empty() ? std::string("synthetic ring disc") : a.scene_file},
                            {"overrides", a.overrides},
                            {"steps", a.steps},
                            {"warmup", a.warmup},
                            {"repeat", a.repeat},
                            {"machine_ceiling", ceiling},
                            {"cases", cases}};
  common::write_whole_text(out / "bench.json", j.dump(2) + "\n");
  common::write_whole_text(out / "bench.csv", csv);
  fmt::print("wrote {}/{{bench.json, bench.csv}}\n", out.string());
}

}  // namespace

void register_bench_command(CLI::App& app) {
  auto args = std::make_shared<BenchArguments>();
  CLI::App* command =
      app.add_subcommand("bench",
                         "benchmark the DDA engine: µs per block-step per phase, on a glued disc impacting a "
                         "plate at several sizes or on the first steps of a scene (--scene)");
  command->add_option("--blocks", args->blocks, "block counts (default 1000 2000 4000 8000 16000)")
      ->delimiter(',')
      ->check(whole_number(kSmallestRingDisc, kMaxBenchBlocks));
  command
      ->add_option("--scene", args->scene_file,
                   "bench this scene file's first --steps steps instead of the synthetic disc")
      ->check(CLI::ExistingFile);
  command
      ->add_option("--set", args->overrides,
                   "override a value of the --scene scene, e.g. --set analysis.penalty=1.053e12")
      ->type_name("KEY=VALUE");
  command->add_option("--repeat", args->repeat, "runs per case; the median by total time is reported (default 1)")
      ->check(whole_number(1));
  command->add_option("--threads", args->threads, "thread counts (default 1 2)")
      ->delimiter(',')
      ->check(whole_number(1, kMaxThreads));
  command->add_option("--steps", args->steps, "timed steps per case")->check(whole_number(1));
  command->add_option("--warmup", args->warmup, "untimed steps first")->check(whole_number(0));
  command->add_option("--solver", args->solver, "pcg or direct (default: the scene's analysis.solver)")
      ->check(CLI::IsMember({"pcg", "direct"}));
  command->add_option("--out", args->out, "directory for bench.json and bench.csv");
  command->add_flag("!--no-ceiling", args->ceiling,
                    "skip the machine's own speed-up ceiling (compute- and memory-bound kernels, ~3 s)");
  command->callback([args] { run_bench(*args); });
}

}  // namespace ddafrac::app
