#pragma once
// A whole run: an Engine driven (drive.hpp) to the scene's end time, writing the run
// directory: summary.json, history.csv, vtk/*.vtu + run.pvd, joints/*.csv, scene.resolved.toml, and
// checkpoint.bin while the run is unfinished. Every file is written whole (temporary name, then
// rename), so an interrupted or failed run leaves valid files, and a checkpointed one can be
// resumed.

#include <atomic>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>

#include "ddafrac/dda/checkpoint.hpp"
#include "ddafrac/dda/engine.hpp"

namespace ddafrac::dda {

/// The scene exactly as the run read it (Scene::resolved_text), written into the run directory:
/// what reproduces the run, and what a resumed sweep compares to skip a finished case.
inline constexpr std::string_view kResolvedSceneFile = "scene.resolved.toml";

/// Exit status of a run (also the process exit code of `ddafrac run`).
/// A file could not be written (a full disk): the files keep their last whole version.
enum RunExit : int { kRunCompleted = 0, kRunNumericalTrouble = 3, kRunWriteFailed = 4, kRunInterrupted = 130 };
/// A run stopped by signal s exits with 128 + s, as a shell reports it (130 SIGINT, 143 SIGTERM).
inline constexpr int kSignalExitBase = 128;

struct Progress {
  double time = 0.0, end_time = 0.0;  // s, simulated
  long step = 0;
  double dt = 0.0;
  int open_close = 0, cg_iterations = 0;  // of the latest step
  double wall = 0.0;                      // s since the run started
};

struct RunOptions {
  std::filesystem::path out_dir;
  int threads = 1;  // recorded in summary.json (the caller sets the OpenMP thread count)
  /// Called between steps, where the caller may change the OpenMP thread count (results do not
  /// depend on it); returns the count in use. summary.json records the fewest used and how
  /// often it changed.
  std::function<int()> between_steps;
  double setup_wall = 0.0;      // s the caller spent meshing and building the engine (summary.json)
  long max_steps = 0;           // stop after this many steps (0: run to the scene's end time)
  int history_every = 1;        // history.csv row every N accepted steps
  bool vtk = true;              // snapshots at every output interval
  double progress_every = 0.1;  // wall seconds between progress callbacks
  std::function<void(const Progress&)> progress;
  /// Stop request: the number of the signal received (set by a handler owned by the caller),
  /// 0 while none; checked once per step. The run's exit status is then 128 + the signal.
  const std::atomic<int>* stop = nullptr;
  /// Wall seconds between checkpoints (checkpoint.hpp), 0 for none. A run stopped by a signal
  /// or at max_steps also writes one; a completed run removes it.
  double checkpoint_every = 0.0;
  std::string invocation;  // kept in every checkpoint (Checkpoint::invocation)
  /// Continue from this checkpoint of out_dir instead of from t = 0. The engine must be freshly
  /// built from the run's scene and mesh (checked: CheckpointError otherwise).
  const Checkpoint* resume = nullptr;
};

/// Run directory contents besides the VTU files, all written whole at every
/// output interval: summary.json, history.csv (per step; columns cracks_total, cracks_tensile,
/// cracks_shear are cumulative, kinetic_strain_ratio = kinetic energy of the free blocks
/// (platens excluded) over the strain energy of the blocks: the quasi-static check), cracks.csv,
/// crack_intervals.csv (new cracks per scene.output.crack_interval, up to the interval holding
/// the current time), gauges.csv (stress of the
/// block holding each gauge at t = 0) and, with fixed or prescribed bodies, loading.csv (mean
/// displacement and anchor-spring force per body; summary.json gives the peak |force_y| of the
/// prescribed bodies).
struct RunResult {
  int exit_status = kRunCompleted;
  std::string reason;   // "completed", "max_steps", "interrupted", "numerical_trouble", "write_failed"
  std::string message;  // for numerical trouble: step, time, worst block/contact
  long steps = 0;
  double time = 0.0;
  double wall = 0.0;
  int threads_fewest = 0;  // smallest thread count used (RunOptions::between_steps)
  int thread_count_changes = 0;
};

/// Removes from `dir` the files a previous run_simulation wrote there (summary.json, the CSV
/// files, run.pvd, vtk/snapshot_NNNNNN.vtu and their temporaries) and nothing else, so a new run
/// never sits beside stale snapshots. Returns how many files it removed.
std::size_t remove_previous_run(const std::filesystem::path& dir);

/// Runs the engine to its end time (or max_steps / stop request / numerical trouble). A step
/// whose energies are not finite (NaN or infinity) ends the run as numerical trouble before it
/// reaches any file.
RunResult run_simulation(Engine& engine, const RunOptions& options);

/// VTK XML unstructured grid of the blocks (polygons, VTK type 7) followed by the joints broken
/// by the fracture check (lines, VTK type 3, between block_a's two joint vertices): cell data
/// body (-1 on lines), stress, sigma1, sigma3, velocity, joint_utilisation (Engine::
/// joint_utilisation: -1 on blocks without virtual joints, 0 on lines) and crack_type (0 blocks, 1 tensile, 2 shear).
/// ASCII.
std::string vtu_document(const Engine& engine);

/// The joint table written beside each snapshot (joints/joints_NNNNNN.csv, NNNNNN the
/// snapshot's number) in scenes with virtual joints: every intact joint that carries contacts,
/// the most loaded first (by utilisation, then joint number). Columns: t (s), joint, block_a,
/// block_b, x, y (midpoint, m), length (m), normal_force (N/m, tension positive), shear_force
/// (N/m, along node_a -> node_b, on block_a), r1, r2 (FailureRatios: 1 at the strength),
/// utilisation = max(r1, r2): the joint-level view of the snapshots' joint_utilisation; and
/// stress_normal_force, stress_shear_force: the load its blocks' stress puts on it
/// (stress_traction), which the joint's forces equal where nothing else carries load past it.
std::string joints_document(const Engine& engine);

}  // namespace ddafrac::dda
