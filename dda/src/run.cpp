#include "ddafrac/dda/run.hpp"

#include <fmt/core.h>
#include <omp.h>
#include <boost/archive/binary_iarchive.hpp>
#include <boost/archive/binary_oarchive.hpp>
#include <boost/serialization/string.hpp>
#include <boost/serialization/vector.hpp>

#include <algorithm>
#include <cmath>
#include <regex>
#include <sstream>

#include "ddafrac/common/whole_file.hpp"
#include "ddafrac/dda/checkpoint.hpp"
#include "ddafrac/dda/drive.hpp"
#include "ddafrac/reference/analytic.hpp"
#include "run_documents.hpp"

namespace ddafrac::dda {

namespace fs = std::filesystem;

// Found by argument-dependent lookup, so in Snapshot's namespace (not the anonymous one).
template <class Archive>
void serialize(Archive& a, Snapshot& s, unsigned) {
  a& s.time& s.file;
}

namespace {

/// The run directory's files besides the snapshots (vtk/snapshot_NNNNNN.vtu, joints/joints_NNNNNN.csv).
const char* const kRunFiles[] = {"summary.json",        "history.csv",  "cracks.csv", "crack_intervals.csv",
                                 "gauges.csv",          "loading.csv",  "run.pvd",    "checkpoint.bin",
                                 "scene.resolved.toml", "fragments.csv"};

/// NaN or infinity in a step's energies means NaN or infinity in the blocks' state.
void check_finite(const StepReport& r) {
  const double values[] = {r.energy.kinetic, r.energy.strain,   r.energy.contact,
                           r.energy.support, r.max_penetration, r.ledger.balance_error()};
  if (std::all_of(std::begin(values), std::end(values), [](double v) { return std::isfinite(v); })) return;
  throw NumericalTrouble(fmt::format(
      "numerical trouble at step {}, t = {:.9g} s: the energies are not finite (kinetic {:g}, strain {:g}, contact "
      "{:g} J/m), so NaN or infinity is in the blocks' state; a stiffness out of scale (materials.*.young, "
      "analysis.penalty, joints.*.normal_stiffness) or a velocity out of scale does this",
      r.step, r.time, r.energy.kinetic, r.energy.strain, r.energy.contact));
}

/// What the run loop gathers for its files beyond the engine's state: kept in checkpoints, so
/// that a resumed run writes exactly the files of an uninterrupted one.
struct RunLog {
  std::string history, gauges, loading;             // the CSV files' text so far
  double gauges_time = -1.0;                        // s, of the latest gauge rows
  nlohmann::json peaks = nlohmann::json::object();  // peak forces of the prescribed bodies
  std::vector<Snapshot> snapshots;
  long next_output = 1;          // number of the next output interval
  bool snapshot_at_end = false;  // a step was taken since the latest snapshot
  int threads_fewest = 0, thread_count_changes = 0;
  double wall = 0.0;  // s, of the earlier parts of a resumed run
  struct Resume {
    long step = 0;
    double time = 0.0;  // s
  };
  std::vector<Resume> resumes;
};

template <class Archive>
void serialize(Archive& a, RunLog::Resume& r, unsigned) {
  a& r.step& r.time;
}

template <class Archive>
void serialize(Archive& a, RunLog& log, std::string& peaks) {
  a& log.history& log.gauges& log.loading& log.gauges_time& peaks& log.snapshots& log.next_output;
  a& log.snapshot_at_end& log.threads_fewest& log.thread_count_changes& log.wall& log.resumes;
}

/// The log as bytes, its wall time with the `elapsed` seconds of this part of the run.
std::string write_run_log(RunLog log, double elapsed) {
  log.wall += elapsed;
  std::string peaks = log.peaks.dump();
  std::ostringstream bytes(std::ios::binary);
  {
    boost::archive::binary_oarchive archive(bytes);
    serialize(archive, log, peaks);
  }
  return std::move(bytes).str();
}

RunLog read_run_log(const std::string& bytes) {
  RunLog log;
  std::string peaks;
  std::istringstream in(bytes, std::ios::binary);
  boost::archive::binary_iarchive archive(in);
  serialize(archive, log, peaks);
  log.peaks = nlohmann::json::parse(peaks);
  return log;
}

/// Snapshot k's files, relative to the run directory: the VTU and its joint table.
std::string snapshot_file(std::size_t k) { return fmt::format("vtk/snapshot_{:06d}.vtu", k); }
std::string joint_table_file(std::size_t k) { return fmt::format("joints/joints_{:06d}.csv", k); }

/// Removes the snapshots numbered `first` and after: a resumed run writes them again.
void remove_snapshots_from(const fs::path& dir, std::size_t first) {
  std::error_code error;
  for (std::size_t k = first;; ++k) {
    fs::remove(dir / joint_table_file(k), error);
    if (!fs::remove(dir / snapshot_file(k), error)) break;
  }
}

}  // namespace

std::size_t remove_previous_run(const fs::path& dir) {
  std::string names;
  for (const char* file : kRunFiles) {
    const fs::path name(file);
    for (const fs::path& any : {name, common::partial_name(name)})
      names += (names.empty() ? "" : "|") + std::regex_replace(any.string(), std::regex(R"(\.)"), R"(\.)");
  }
  return common::remove_files_matching(dir, std::regex(names)) +
         common::remove_files_matching(dir / "vtk", std::regex(R"(\.?snapshot_\d{6}(\.partial)?\.vtu)")) +
         common::remove_files_matching(dir / "joints", std::regex(R"(\.?joints_\d{6}(\.partial)?\.csv)"));
}

RunResult run_simulation(Engine& engine, const RunOptions& o) {
  const double t0 = omp_get_wtime();
  RunResult r;
  int current_threads = 0;  // as returned by o.between_steps
  fs::create_directories(o.out_dir);
  const bool joint_tables = o.vtk && !engine.blocks().joints.empty();
  if (o.vtk) fs::create_directories(o.out_dir / "vtk");
  if (joint_tables) fs::create_directories(o.out_dir / "joints");
  const auto& an = engine.scene().analysis;
  const double end = an.end_time;
  const double interval = an.output_interval > 0.0 ? an.output_interval : end;
  Statistics& st = engine.statistics();
  const scene::Scene& sc = engine.scene();
  const double crack_width = sc.output.crack_interval > 0.0 ? sc.output.crack_interval : end;

  RunLog log;
  log.history = history_header();
  log.gauges = "t,gauge,sigma_xx,sigma_yy,tau_xy,sigma1,sigma3\n";
  log.loading = "t,body,displacement_y,force_y\n";
  const std::uint64_t initial_state = fingerprint(engine.carried_state());
  if (o.resume) {
    if (o.resume->initial_state != initial_state)
      throw CheckpointError(fmt::format(
          "{}: the scene and mesh rebuilt for the resume are not the ones the run started from (the scene file, a "
          "base scene, the .msh file or ddafrac changed since); run the scene anew",
          (o.out_dir / kCheckpointFile).string()));
    engine.restore_carried_state(o.resume->engine);
    log = read_run_log(o.resume->run_log);
    log.resumes.push_back({o.resume->step, o.resume->time});
    remove_snapshots_from(o.out_dir, log.snapshots.size());
  }
  double last_checkpoint = t0;
  auto checkpoint = [&] {
    write_checkpoint(o.out_dir, {o.invocation, initial_state, st.steps, engine.time(), engine.carried_state(),
                                 write_run_log(log, omp_get_wtime() - t0)});
    last_checkpoint = omp_get_wtime();
  };

  // Gauges: stress of the block that held the point at t = 0, at every output.
  auto sample_gauges = [&] {
    if (engine.time() == log.gauges_time) return;
    log.gauges_time = engine.time();
    for (std::size_t g = 0; g < sc.gauges.size(); ++g) {
      const Vec3& s = engine.blocks().stress[static_cast<std::size_t>(engine.gauge_blocks()[g])];
      const reference::Principal p = reference::principal({s[0], s[1], s[2]});
      log.gauges += fmt::format("{:.17g},{},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g}\n", engine.time(), sc.gauges[g].name,
                                s[0], s[1], s[2], p.s1, p.s3);
    }
  };
  // Loading of fixed and prescribed bodies, every step.
  const bool loaded = !engine.blocks().anchors.empty();
  auto sample_loading = [&] {
    if (!loaded) return;
    for (const Engine::BodyLoad& l : engine.body_loads()) {
      const std::string name = l.body >= 0 ? sc.bodies[static_cast<std::size_t>(l.body)].name : std::string("extra");
      log.loading += fmt::format("{:.17g},{},{:.12g},{:.12g}\n", engine.time(), name, l.uy, l.fy);
      if (l.body < 0 || sc.bodies[static_cast<std::size_t>(l.body)].motion != scene::Motion::Prescribed) continue;
      auto& p = log.peaks[name];
      if (p.is_null() || std::abs(l.fy) > p["peak_abs_force_y"].get<double>())
        p = {{"peak_abs_force_y", std::abs(l.fy)}, {"force_y", l.fy}, {"displacement_y", l.uy}, {"t", engine.time()}};
    }
  };

  // Written last, so that it never speaks of files that were not written.
  auto write_summary = [&] {
    r.wall = log.wall + omp_get_wtime() - t0;
    r.steps = st.steps;
    r.time = engine.time();
    r.threads_fewest = log.threads_fewest;
    r.thread_count_changes = log.thread_count_changes;
    nlohmann::json summary = summary_json(engine, o, r, {{"peak", log.peaks}, {"unit", "N/m"}});
    for (const RunLog::Resume& resume : log.resumes)
      summary["resumed_from"].push_back({{"step", resume.step}, {"t", resume.time}});
    ddafrac::common::write_whole_text(o.out_dir / "summary.json",
                                      summary.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
  };

  auto write_outputs = [&](bool snapshot, bool state_valid = true) {
    const double w0 = omp_get_wtime();
    if (state_valid) sample_gauges();
    if (!sc.gauges.empty()) ddafrac::common::write_whole_text(o.out_dir / "gauges.csv", log.gauges);
    if (loaded) ddafrac::common::write_whole_text(o.out_dir / "loading.csv", log.loading);
    ddafrac::common::write_whole_text(o.out_dir / "cracks.csv", cracks_document(engine.cracks()));
    ddafrac::common::write_whole_text(o.out_dir / "crack_intervals.csv",
                                      crack_intervals_document(engine.cracks(), crack_width, engine.time()));
    if (!engine.blocks().joints.empty())
      ddafrac::common::write_whole_text(o.out_dir / "fragments.csv", fragments_document(engine));
    if (snapshot && o.vtk) {
      const std::string name = snapshot_file(log.snapshots.size());
      if (joint_tables)
        ddafrac::common::write_whole_text(o.out_dir / joint_table_file(log.snapshots.size()), joints_document(engine));
      ddafrac::common::write_whole_text(o.out_dir / name, vtu_document(engine));
      log.snapshots.push_back({engine.time(), name});
      ddafrac::common::write_whole_text(o.out_dir / "run.pvd", pvd_document(log.snapshots));
    }
    ddafrac::common::write_whole_text(o.out_dir / "history.csv", log.history);
    st.times.output += omp_get_wtime() - w0;
    write_summary();
  };
  r.reason = "running";
  if (!sc.resolved_text.empty()) common::write_whole_text(o.out_dir / kResolvedSceneFile, sc.resolved_text);
  if (!o.resume) {
    sample_loading();
    write_outputs(true);
  }
  double last_progress = -1e300;
  StepReport last;
  // Every output interval ends with a step that lands on it (the last one on the end time).
  auto output_time = [&] { return std::min(end, static_cast<double>(log.next_output) * interval); };
  DriveHooks hooks;
  hooks.interrupt = [&] {
    if (const int signal = o.stop ? o.stop->load() : 0) {
      r.exit_status = kSignalExitBase + signal;
      r.reason = "interrupted";
      r.message = fmt::format("interrupted by signal {} at step {}, t = {:.9g} s", signal, st.steps, engine.time());
      return Next::Stop;
    }
    if (o.max_steps > 0 && st.steps >= o.max_steps) {
      r.reason = "max_steps";
      return Next::Stop;
    }
    return Next::Continue;
  };
  hooks.before_step = [&] {
    if (o.between_steps) {
      const int threads = o.between_steps();
      if (log.threads_fewest > 0 && threads != current_threads) ++log.thread_count_changes;
      current_threads = threads;
      log.threads_fewest = log.threads_fewest > 0 ? std::min(log.threads_fewest, threads) : threads;
    }
    return Next::Continue;
  };
  hooks.land_at = output_time;
  hooks.after_step = [&](const StepReport& rep) {
    check_finite(rep);
    last = rep;
    sample_loading();
    if (rep.step % std::max(1, o.history_every) == 0) log.history += history_row(rep);
    log.snapshot_at_end = true;
    if (engine.time() >= output_time() - kTimeSlack * interval) {
      ++log.next_output;
      write_outputs(true);
      log.snapshot_at_end = false;
    }
    if (o.checkpoint_every > 0.0 && omp_get_wtime() - last_checkpoint >= o.checkpoint_every) checkpoint();
    if (o.progress) {
      const double now = omp_get_wtime();
      if (now - last_progress >= o.progress_every) {
        last_progress = now;
        o.progress({engine.time(), end, rep.step, rep.dt, rep.open_close, rep.cg_iterations, log.wall + now - t0});
      }
    }
    return Next::Continue;
  };
  try {
    if (drive(engine, end, hooks) == DriveEnd::Reached) r.reason = "completed";
  } catch (const NumericalTrouble& ex) {
    r.exit_status = kRunNumericalTrouble;
    r.reason = "numerical_trouble";
    r.message = ex.what();
  } catch (const common::WriteError& ex) {
    // Each file keeps its last whole version; more writing would fail as well. The summary is
    // small: it may still fit, and then says why the run stopped.
    r.exit_status = kRunWriteFailed;
    r.reason = "write_failed";
    r.message = ex.what();
    try {
      write_summary();
    } catch (const common::WriteError&) {
    }
    return r;
  }
  // A run that stopped early can be resumed from where it stopped; a finished one has nothing
  // left to resume. After numerical trouble the last checkpoint stays (the state now may hold NaN).
  if (r.reason == "interrupted" || r.reason == "max_steps") checkpoint();
  if (r.reason == "completed") fs::remove(o.out_dir / kCheckpointFile);
  if (o.progress)
    o.progress(
        {engine.time(), end, st.steps, last.dt, last.open_close, last.cg_iterations, log.wall + omp_get_wtime() - t0});
  // After numerical trouble the blocks' state may hold NaN: the files keep the last good one.
  const bool state_valid = r.exit_status != kRunNumericalTrouble;
  write_outputs(log.snapshot_at_end && state_valid, state_valid);
  return r;
}

}  // namespace ddafrac::dda
