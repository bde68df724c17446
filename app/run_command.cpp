// `ddafrac run SCENE [--out DIR] [--threads N] [--set key=value ...]`: one DDA run of a scene,
// with a progress bar on a terminal (plain lines otherwise), writing the run directory;
// `ddafrac run --resume DIR` continues a stopped or killed run from its checkpoint.

#include <fmt/core.h>
#include <omp.h>
#include <sys/prctl.h>
#include <unistd.h>
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <memory>
#include <optional>

#include "commands.hpp"
#include "ddafrac/common/stopwatch.hpp"
#include "ddafrac/common/thread_governor.hpp"
#include "ddafrac/dda/contact_period.hpp"
#include "ddafrac/dda/run.hpp"
#include "ddafrac/scene/parse.hpp"
#include "figures.hpp"
#include "option_checks.hpp"
#include "scene_source.hpp"

namespace ddafrac::app {

namespace {

/// The signal (SIGINT or SIGTERM) received while a run is in progress, 0 while none; the run
/// stops at the next step, writes valid files and exits with 128 + the signal.
std::atomic<int> stop_signal{0};

extern "C" void on_stop_signal(int signal) { stop_signal.store(signal); }

/// Installs the SIGINT and SIGTERM handlers for the lifetime of a run and restores the previous
/// ones after.
class StopSignalGuard {
 public:
  StopSignalGuard() {
    stop_signal.store(0);
    previous_interrupt_ = std::signal(SIGINT, on_stop_signal);
    previous_terminate_ = std::signal(SIGTERM, on_stop_signal);
  }
  ~StopSignalGuard() {
    std::signal(SIGINT, previous_interrupt_);
    std::signal(SIGTERM, previous_terminate_);
  }
  StopSignalGuard(const StopSignalGuard&) = delete;
  StopSignalGuard& operator=(const StopSignalGuard&) = delete;

 private:
  void (*previous_interrupt_)(int) = SIG_DFL;
  void (*previous_terminate_)(int) = SIG_DFL;
};

/// A run started by a sweep or a study stops as on SIGTERM (checkpoint, valid files) when the
/// process that started it ends, however it ends: a killed study leaves no run behind that still
/// writes into its folder, and `--resume` continues the stopped ones. Linux asks the kernel for
/// the signal; a parent that ended before that request stops the run at once.
void stop_when_parent_ends(long parent) {
  if (parent == 0) return;
  ::prctl(PR_SET_PDEATHSIG, SIGTERM);
  if (static_cast<long>(::getppid()) != parent) stop_signal.store(SIGTERM);
}

/// Wall seconds the thread governor watches the machine before a run, and between re-measures.
constexpr double kGovernorFirstSample = 0.2;
constexpr double kGovernorInterval = 2.0;

/// Generated meshes of more blocks than this take long enough to say so first.
constexpr int kQuietMeshBlocks = 100'000;

/// Refuses a model too large for the memory, and announces a long meshing.
void check_model_size(const scene::Scene& scene) {
  if (std::holds_alternative<meshes::MshFile>(scene.geometry)) return;
  check_memory_for_blocks(scene.mesh.target_blocks, scene.source.string() + ": mesh.blocks");
  if (scene.mesh.target_blocks > kQuietMeshBlocks) {
    fmt::print("meshing {} blocks (this takes a while) ...\n", scene.mesh.target_blocks);
    std::fflush(stdout);
  }
}

/// Bytes of one snapshot per block: the VTU, 151 measured at t = 0 (impact_small), broken joints add
/// lines (218 in the default scene at 300 µs); and its joint table, 194 there (1.4 joints per block).
constexpr double kSnapshotBytesPerBlock = 420.0;
constexpr double kBytesPerMegabyte = 1e6;

/// The free space of the file system `path` will be on (its nearest existing ancestor).
std::optional<double> free_space_for(std::filesystem::path path) {
  path = std::filesystem::absolute(path);
  std::error_code error;
  while (!std::filesystem::exists(path, error) && path.has_parent_path() && path != path.parent_path())
    path = path.parent_path();
  const std::filesystem::space_info space = std::filesystem::space(path, error);
  if (error) return std::nullopt;
  return static_cast<double>(space.available);
}

/// Refuses a run whose snapshots (VTU and joint table) would not fit on the disk, saying what they
/// would take.
void check_disk_for_snapshots(const scene::Scene& scene, std::size_t blocks, const std::filesystem::path& out) {
  const double snapshots = std::floor(scene.analysis.end_time / scene.analysis.output_interval) + 2.0;
  const double snapshot_bytes = static_cast<double>(blocks) * kSnapshotBytesPerBlock;
  const std::optional<double> available = free_space_for(out);
  if (!available || snapshots * snapshot_bytes <= *available) return;
  throw CommandFailed(
      fmt::format("{}: the run would write {:g} snapshots (VTU and joint table) of about {:.1f} MB ({:.0f} MB in all: "
                  "analysis.output_interval = "
                  "{:g} s) but {} has {:.0f} MB free; use a longer output_interval or --no-vtk",
                  scene.source.string(), snapshots, snapshot_bytes / kBytesPerMegabyte,
                  snapshots * snapshot_bytes / kBytesPerMegabyte, scene.analysis.output_interval, out.string(),
                  *available / kBytesPerMegabyte));
}

/// Clears the run directory of a previous run's files (ours only), so no stale snapshot or
/// figure sits beside the new run's.
void clear_previous_run(const std::filesystem::path& out) {
  const std::size_t removed = dda::remove_previous_run(out) + remove_previous_figures(out);
  if (removed > 0) fmt::print("removed {} file(s) of a previous run from {}\n", removed, out.string());
}

/// Wall seconds between checkpoints by default: a killed run loses at most this much work, and
/// writing a checkpoint (tens of MB at the study's full size) costs well under 1% of it.
constexpr double kDefaultCheckpointEvery = 600.0;

struct RunArguments {
  std::string resume;  // run directory to resume ("": a new run)
  double checkpoint_every = kDefaultCheckpointEvery;
  SceneArguments scene;
  std::string out;
  int threads = 0;
  bool keep_threads = false;  // no thread governor: exactly --threads whatever the machine's load
  std::string solver;         // empty: the scene's analysis.solver
  long max_steps = 0;
  bool no_vtk = false;
  bool no_figures = false;
  double energy_tolerance = dda::kDefaultEnergyBalanceTolerance;
  long parent = 0;  // process whose end stops the run as SIGTERM does (0: none)
};

void show_progress(const dda::Progress& p, bool tty) {
  const double frac = p.end_time > 0.0 ? std::min(1.0, p.time / p.end_time) : 0.0;
  const double eta = frac > 0.0 ? p.wall * (1.0 - frac) / frac : -1.0;
  if (tty) {
    constexpr int kWidth = 30;
    const int filled = static_cast<int>(frac * kWidth);
    fmt::print(stderr, "\r[{}{}] {:5.1f}%  t {:.4g}/{:.4g} s  step {}  dt {:.3g} s  oc {}  cg {}  ETA {}   ",
               std::string(static_cast<std::size_t>(filled), '#'),
               std::string(static_cast<std::size_t>(kWidth - filled), '-'), 100.0 * frac, p.time, p.end_time, p.step,
               p.dt, p.open_close, p.cg_iterations, common::duration_text(eta));
  } else {
    fmt::print("t = {:.6g} s of {:.6g} s ({:.1f}%), step {}, dt {:.3g} s, open-close {}, cg {}, ETA {}\n", p.time,
               p.end_time, 100.0 * frac, p.step, p.dt, p.open_close, p.cg_iterations, common::duration_text(eta));
  }
  std::fflush(tty ? stderr : stdout);
}

/// Warns when the longest step is not a small fraction of the shortest contact period: the
/// blocks would rock and bounce on their contact springs rather than rest on them. Static mode
/// sets the velocities to zero after every step: nothing oscillates, and nothing is warned.
void warn_if_contacts_are_unresolved(const dda::Engine& engine) {
  if (engine.scene().analysis.mode == scene::Mode::Static) return;
  const double dt_max = engine.scene().analysis.dt_max;
  const dda::ContactPeriod shortest = dda::shortest_contact_period(engine, dt_max);
  if (shortest.unresolved_blocks == 0) return;
  fmt::print(stderr,
             "warning: analysis.dt_max = {:.3g} s is {:.2g} steps per period of the stiffest contact spring on the "
             "lightest block (T = 2π·√(m/2 / kn) = {:.3g} s, m = {:.3g} kg/m at ({:.4g}, {:.4g}) m, kn = {:.3g} N/m), "
             "and fewer than {:g} for {} of {} moving blocks: the time scheme does not follow their contact "
             "oscillations, and such a block resting on a contact rocks and bounces. Lower analysis.dt_max to at most "
             "{:.3g} s or the contact stiffness "
             "(analysis.penalty, joints.*.normal_stiffness), or mesh without such small blocks\n",
             dt_max, shortest.period / dt_max, shortest.period, shortest.mass, shortest.x, shortest.y,
             shortest.stiffness, dda::kMinStepsPerContactPeriod, shortest.unresolved_blocks, shortest.moving_blocks,
             shortest.period / dda::kMinStepsPerContactPeriod);
}

/// What a checkpoint keeps of how the run was started: enough to rebuild it on resume.
std::string invocation_of(const RunArguments& args, const scene::Scene& scene, const std::filesystem::path& out) {
  const std::string scene_file =
      args.scene.scene_file.empty() ? std::string() : std::filesystem::absolute(args.scene.scene_file).string();
  const nlohmann::json j = {{"scene_file", scene_file},
                            {"overrides", args.scene.overrides},
                            {"solver", args.solver},
                            {"no_vtk", args.no_vtk},
                            {"out", std::filesystem::absolute(out).string()},
                            {"scene_text", scene.resolved_text}};
  return j.dump();
}

/// The arguments of the run being resumed: how it was started (from its checkpoint), with this
/// command's threads, step limit, checkpoint interval and figure and energy options.
RunArguments resumed_arguments(const RunArguments& given, const dda::Checkpoint& checkpoint) {
  RunArguments args = given;
  const nlohmann::json j = nlohmann::json::parse(checkpoint.invocation);
  args.scene.scene_file = j.at("scene_file").get<std::string>();
  args.scene.overrides = j.at("overrides").get<std::vector<std::string>>();
  args.solver = j.at("solver").get<std::string>();
  args.no_vtk = j.at("no_vtk").get<bool>();
  args.out = j.at("out").get<std::string>();
  return args;
}

/// Refuses to resume with a scene that reads differently now than when the run started, naming
/// the first line that differs.
void check_scene_unchanged(const scene::Scene& scene, const dda::Checkpoint& checkpoint, const std::string& run_dir) {
  const std::string then = nlohmann::json::parse(checkpoint.invocation).at("scene_text").get<std::string>();
  if (then == scene.resolved_text) return;
  std::istringstream a(then), b(scene.resolved_text);
  std::string line_then, line_now;
  int line = 0;
  while (true) {
    ++line;
    const bool more_then = static_cast<bool>(std::getline(a, line_then));
    const bool more_now = static_cast<bool>(std::getline(b, line_now));
    if (!more_then) line_then = "(nothing)";
    if (!more_now) line_now = "(nothing)";
    if (line_then != line_now || (!more_then && !more_now)) break;
  }
  throw CommandFailed(fmt::format(
      "{}: cannot resume: the scene {} (with its base scenes and --set values) changed since the run started; "
      "line {} of the resolved scene was \"{}\", is now \"{}\". Restore it, or run the scene anew",
      run_dir, scene.source.string(), line, line_then, line_now));
}

/// How the run being resumed ended, from its summary.json: a run killed outright never wrote its
/// end there and still says "running".
void report_resume(const std::filesystem::path& out, const dda::Checkpoint& checkpoint) {
  std::string ended = "unknown (no summary.json)";
  std::ifstream in(out / "summary.json");
  const nlohmann::json summary = nlohmann::json::parse(in, nullptr, false);
  if (!summary.is_discarded() && summary.contains("exit")) {
    const std::string reason = summary["exit"].value("reason", "");
    ended = reason == "running" ? fmt::format("was killed (its summary.json, of step {}, still says running)",
                                              summary.value("steps", 0L))
                                : fmt::format("stopped: {}", reason);
  }
  fmt::print("resuming {}: the run {}; continuing from its checkpoint at step {}, t = {:.6g} s\n", out.string(), ended,
             checkpoint.step, checkpoint.time);
}

void run_run(const RunArguments& given) {
  std::optional<dda::Checkpoint> checkpoint;
  if (!given.resume.empty()) {
    try {
      checkpoint = dda::read_checkpoint(given.resume);
    } catch (const dda::CheckpointError& e) {
      throw CommandFailed(e.what());
    }
  }
  const RunArguments args = checkpoint ? resumed_arguments(given, *checkpoint) : given;
  const scene::Scene scene = args.scene.load();
  if (checkpoint) check_scene_unchanged(scene, *checkpoint, given.resume);
  const std::filesystem::path out =
      checkpoint ? std::filesystem::path(given.resume) : output_directory(args.out, scene, "run");
  if (args.threads > 0) omp_set_num_threads(args.threads);
  const int threads = omp_get_max_threads();
  // Threads only on the cores other processes leave free, re-measured every few seconds
  // (common/thread_governor.hpp): a busy core turns every barrier of a step into a wait.
  common::ThreadGovernor governor(threads);
  if (!args.keep_threads && threads > 1) {
    const int free_threads = governor.start(kGovernorFirstSample);
    if (free_threads < threads)
      fmt::print("other processes keep {} core(s) busy: running on {} thread(s) of {} (--keep-threads to insist)\n",
                 threads - free_threads, free_threads, threads);
  }

  const auto setup_start = std::chrono::steady_clock::now();
  check_model_size(scene);
  const meshes::Mesh mesh = dda_mesh(scene);
  dda::EngineOptions options;
  options.solver.kind = wants_direct_solver(args.solver, scene) ? dda::SolverKind::Direct : dda::SolverKind::Pcg;
  std::unique_ptr<dda::Engine> engine;
  try {
    engine = std::make_unique<dda::Engine>(scene, mesh, options);
  } catch (const std::invalid_argument& e) {
    throw CommandFailed(fmt::format("{}: {}", scene.source.string(), e.what()));
  }
  fmt::print("{}: {} blocks, {} virtual joints, {} thread(s), solver {}, end time {:.4g} s -> {}\n", scene.name,
             engine->blocks().block_count(), engine->blocks().joints.size(), threads,
             dda::to_string(options.solver.kind), scene.analysis.end_time, out.string());
  std::fflush(stdout);

  warn_if_contacts_are_unresolved(*engine);

  const bool tty = ::isatty(::fileno(stderr)) != 0;
  dda::RunOptions ro;
  ro.out_dir = out;
  ro.vtk = scene.output.vtk && !args.no_vtk;
  if (ro.vtk) check_disk_for_snapshots(scene, engine->blocks().block_count(), out);
  ro.threads = threads;
  if (!args.keep_threads && threads > 1) ro.between_steps = [&governor] { return governor.update(kGovernorInterval); };
  ro.setup_wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - setup_start).count();
  ro.max_steps = args.max_steps;
  ro.progress_every = tty ? 0.2 : 5.0;
  ro.progress = [tty](const dda::Progress& p) { show_progress(p, tty); };
  ro.checkpoint_every = args.checkpoint_every;
  ro.invocation = invocation_of(args, scene, out);
  ro.resume = checkpoint ? &*checkpoint : nullptr;
  if (checkpoint)
    report_resume(out, *checkpoint);
  else
    clear_previous_run(out);
  dda::RunResult result;
  try {
    StopSignalGuard guard;
    stop_when_parent_ends(args.parent);
    ro.stop = &stop_signal;
    result = dda::run_simulation(*engine, ro);
  } catch (const dda::CheckpointError& e) {
    throw CommandFailed(e.what());
  }
  if (tty) fmt::print(stderr, "\n");
  const auto& st = engine->statistics();
  fmt::print("{}: {} steps, t = {:.6g} s, wall {:.2f} s, dt cuts {}, open-close mean {:.2f}, CG mean {:.2f} max {}\n",
             result.reason, st.steps, engine->time(), result.wall,
             st.cuts_displacement + st.cuts_open_close + st.cuts_solver,
             st.steps ? static_cast<double>(st.open_close_total) / static_cast<double>(st.steps) : 0.0,
             st.solves ? static_cast<double>(st.cg_total) / static_cast<double>(st.solves) : 0.0, st.cg_max);
  const auto& cc = engine->crack_counts();
  fmt::print("cracks: {} ({} tensile, {} shear)\n", cc.total, cc.tensile, cc.shear);
  if (!engine->blocks().joints.empty()) {
    const dda::JointLoadShare share = dda::joint_load_share(engine->blocks(), engine->joint_forces());
    if (share.joints > 0)
      fmt::print(
          "virtual joints carry {:.2f} (normal) and {:.2f} (shear) of the load their blocks' stress puts on them "
          "(summary.json joint_load_share; 1: all of it)\n",
          share.normal, share.shear);
  }
  if (st.missed_contacts > 0)
    fmt::print(
        stderr,
        "warning: {} contact(s) came in deep (deepest {:.3g} m): first detected already deeper than one "
        "step's allowed displacement ({:.3g} m), or their spring took more than {:.2g}% of the energy "
        "balance at once; their springs released energy no work put in. Known sources: a vertex of a broken "
        "joint's second block, which the joint did not hold, found inside the first block at the joint's "
        "compression while the held vertex keeps a contact of its own; a corner of two triangles that share only "
        "a mesh node passes to a copy of the node that sank within one step (see missed_contacts in "
        "summary.json, docs/results/study_full_size.md and docs/design.md §4.6, §4.7)\n",
        st.missed_contacts, st.deepest_missed, engine->allowed_displacement(), 100.0 * dda::kDeepContactEnergyFraction);
  if (st.initial_overlaps > 0)
    fmt::print(stderr,
               "warning: at t = 0, {} contact(s) already overlapped by more than one step's allowed displacement "
               "(deepest {:.3g} m, allowed {:.3g} m): cells or bodies of the mesh interpenetrate, and their springs "
               "pushed them apart in the first step (initial_overlaps in summary.json); check the mesh and the "
               "bodies' placement\n",
               st.initial_overlaps, st.deepest_initial_overlap, engine->allowed_displacement());
  const dda::EnergyLedger& ledger = engine->ledger();
  if (ledger.largest_balance_error > args.energy_tolerance)
    fmt::print(stderr,
               "warning: the energy balance did not close: its error reached {:.3g} (tolerance {:.3g}; at the end "
               "{:.3g}), so the run created or lost energy that no load, support, friction, crack or the time "
               "scheme accounts for (the energy columns of history.csv show when)\n",
               ledger.largest_balance_error, args.energy_tolerance, ledger.balance_error());
  if (result.exit_status != dda::kRunWriteFailed)
    fmt::print("wrote {}/{{summary.json, history.csv, cracks.csv, crack_intervals.csv{}{}{}{}}}\n", out.string(),
               engine->blocks().joints.empty() ? "" : ", fragments.csv", scene.gauges.empty() ? "" : ", gauges.csv",
               engine->blocks().anchors.empty() ? "" : ", loading.csv",
               ro.vtk ? (engine->blocks().joints.empty() ? ", run.pvd, vtk/" : ", run.pvd, vtk/, joints/") : "");
  std::fflush(stdout);
  // Figures of whatever was written (also after an interruption or numerical trouble).
  if (scene.output.figures && !args.no_figures) {
    std::string times;
    for (double t : scene.output.figure_times) times += (times.empty() ? "" : ",") + fmt::format("{:.9g}", t);
    std::vector<std::string> fig{"run", out.string()};
    if (!times.empty()) {
      fig.push_back("--times");
      fig.push_back(times);
    }
    fig.push_back("--crack-interval");
    fig.push_back(fmt::format("{:.9g}", scene.output.crack_interval));
    if (draw_figures(fig)) fmt::print("figures in {}/figures/\n", out.string());
  }
  if (result.reason == "interrupted")
    throw CommandFailed(result.message + "; the files written so far are valid", result.exit_status);
  if (result.exit_status == dda::kRunWriteFailed) {
    const bool resumable = std::filesystem::exists(out / dda::kCheckpointFile);
    throw CommandFailed(
        result.message + "; every file of " + out.string() + " keeps its last whole version" +
            (resumable ? "; free some space and continue with: ddafrac run --resume " + out.string() : std::string()),
        result.exit_status);
  }
  if (result.exit_status != dda::kRunCompleted) throw CommandFailed(result.message, result.exit_status);
}

}  // namespace

void register_run_command(CLI::App& app) {
  auto args = std::make_shared<RunArguments>();
  CLI::App* command = app.add_subcommand("run", "run the DDA simulation of a scene and write its run directory");
  args->scene.add_to(*command);
  CLI::Option* out = command->add_option("--out", args->out, "run directory (default runs/<scene name>/run)");
  CLI::Option* resume =
      command
          ->add_option("--resume", args->resume,
                       "continue the run in this directory from its checkpoint, with the scene, --set, --solver "
                       "and --no-vtk it was started with; the finished files are those of an uninterrupted run")
          ->type_name("RUN_DIR");
  command
      ->add_option("--checkpoint-every", args->checkpoint_every,
                   fmt::format("wall seconds between checkpoints (default {:g}; 0: only when stopped by a signal "
                               "or --max-steps)",
                               kDefaultCheckpointEvery))
      ->check(non_negative_number());
  command
      ->add_option("--threads", args->threads,
                   "most OpenMP threads (default: OMP_NUM_THREADS or all cores); fewer while other processes keep "
                   "cores busy")
      ->check(whole_number(1, kMaxThreads));
  command->add_flag("--keep-threads", args->keep_threads,
                    "use exactly --threads even while other processes keep cores busy");
  command
      ->add_option(
          "--solver", args->solver,
          "linear solver: pcg (block-Jacobi PCG) or direct (sparse LDLT); default: the scene's analysis.solver")
      ->check(CLI::IsMember({"pcg", "direct"}));
  command->add_option("--max-steps", args->max_steps, "stop after this many steps (0: run to the end time)")
      ->check(whole_number(0));
  command->add_flag("--no-vtk", args->no_vtk, "skip the VTU snapshots and their joint tables");
  command
      ->add_option("--stop-with-parent", args->parent,
                   "stop as on SIGTERM (checkpoint, valid files) when process PID, which started this run, ends "
                   "(sweeps and studies pass their own)")
      ->type_name("PID")
      ->check(whole_number(1));
  command
      ->add_option("--energy-tolerance", args->energy_tolerance,
                   "warn at the end when the energy balance error ever exceeded this fraction (default 0.01)")
      ->check(positive_number());
  command->add_flag("--no-figures", args->no_figures,
                    "skip the PNG figures (also skipped when scene.output.figures is false)");
  // A resumed run is the run it continues: what decides its results cannot change.
  for (CLI::Option* fixed : {out, command->get_option("scene"), command->get_option("--set"),
                             command->get_option("--solver"), command->get_option("--no-vtk")})
    resume->excludes(fixed);
  command->callback([args] { run_run(*args); });
}

}  // namespace ddafrac::app
