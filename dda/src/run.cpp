#include "ddafrac/dda/run.hpp"

#include "ddafrac/common/whole_file.hpp"
#include "run_documents.hpp"

#include <fmt/core.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <regex>

namespace ddafrac::dda {

namespace fs = std::filesystem;

namespace {

/// The run directory's files besides the snapshots (vtk/snapshot_NNNNNN.vtu).
const char* const kRunFiles[] = {"summary.json", "history.csv",  "cracks.csv", "crack_intervals.csv",
                                 "gauges.csv",   "loading.csv", "run.pvd"};

/// NaN or infinity in a step's energies means NaN or infinity in the blocks' state.
void check_finite(const StepReport& r) {
  const double values[] = {r.energy.kinetic, r.energy.strain,  r.energy.contact,
                           r.energy.support, r.max_penetration, r.ledger.balance_error()};
  if (std::all_of(std::begin(values), std::end(values), [](double v) { return std::isfinite(v); })) return;
  throw NumericalTrouble(fmt::format(
      "numerical trouble at step {}, t = {:.9g} s: the energies are not finite (kinetic {:g}, strain {:g}, contact "
      "{:g} J/m), so NaN or infinity is in the blocks' state; a stiffness out of scale (materials.*.young, "
      "analysis.penalty, joints.*.normal_stiffness) or a velocity out of scale does this",
      r.step, r.time, r.energy.kinetic, r.energy.strain, r.energy.contact));
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
         common::remove_files_matching(dir / "vtk", std::regex(R"(\.?snapshot_\d{6}(\.partial)?\.vtu)"));
}

RunResult run_simulation(Engine& engine, const RunOptions& o) {
  const double t0 = omp_get_wtime();
  RunResult r;
  int current_threads = 0;  // as returned by o.between_steps
  fs::create_directories(o.out_dir);
  if (o.vtk) fs::create_directories(o.out_dir / "vtk");
  const auto& an = engine.scene().analysis;
  const double end = an.end_time;
  const double interval = an.output_interval > 0.0 ? an.output_interval : end;
  std::string history = history_header();
  std::vector<Snapshot> snaps;
  Statistics& st = engine.statistics();
  const scene::Scene& sc = engine.scene();
  const double crack_width = sc.output.crack_interval > 0.0 ? sc.output.crack_interval : end;

  // Gauges: stress of the block that held the point at t = 0, at every output.
  std::string gauges = "t,gauge,sigma_xx,sigma_yy,tau_xy,sigma1,sigma3\n";
  double gauges_time = -1.0;
  auto sample_gauges = [&] {
    if (engine.time() == gauges_time) return;
    gauges_time = engine.time();
    for (std::size_t g = 0; g < sc.gauges.size(); ++g) {
      const Vec3& s = engine.blocks().stress[static_cast<std::size_t>(engine.gauge_blocks()[g])];
      double s1, s3;
      principal_stresses(s, s1, s3);
      gauges += fmt::format("{:.17g},{},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g}\n", engine.time(), sc.gauges[g].name, s[0],
                            s[1], s[2], s1, s3);
    }
  };
  // Loading of fixed and prescribed bodies, every step.
  const bool loaded = !engine.blocks().anchors.empty();
  std::string loading = "t,body,displacement_y,force_y\n";
  nlohmann::json peaks = nlohmann::json::object();
  auto sample_loading = [&] {
    if (!loaded) return;
    for (const Engine::BodyLoad& l : engine.body_loads()) {
      const std::string name = l.body >= 0 ? sc.bodies[static_cast<std::size_t>(l.body)].name : std::string("extra");
      loading += fmt::format("{:.17g},{},{:.12g},{:.12g}\n", engine.time(), name, l.uy, l.fy);
      if (l.body < 0 || sc.bodies[static_cast<std::size_t>(l.body)].motion != scene::Motion::Prescribed) continue;
      auto& p = peaks[name];
      if (p.is_null() || std::abs(l.fy) > p["peak_abs_force_y"].get<double>())
        p = {{"peak_abs_force_y", std::abs(l.fy)}, {"force_y", l.fy}, {"displacement_y", l.uy}, {"t", engine.time()}};
    }
  };

  auto write_outputs = [&](bool snapshot, bool state_valid = true) {
    const double w0 = omp_get_wtime();
    if (state_valid) sample_gauges();
    if (!sc.gauges.empty()) ddafrac::common::write_whole_text(o.out_dir / "gauges.csv", gauges);
    if (loaded) ddafrac::common::write_whole_text(o.out_dir / "loading.csv", loading);
    ddafrac::common::write_whole_text(o.out_dir / "cracks.csv", cracks_document(engine.cracks()));
    ddafrac::common::write_whole_text(o.out_dir / "crack_intervals.csv",
                                      crack_intervals_document(engine.cracks(), crack_width, engine.time()));
    if (snapshot && o.vtk) {
      const std::string name = fmt::format("vtk/snapshot_{:06d}.vtu", snaps.size());
      ddafrac::common::write_whole_text(o.out_dir / name, vtu_document(engine));
      snaps.push_back({engine.time(), name});
      ddafrac::common::write_whole_text(o.out_dir / "run.pvd", pvd_document(snaps));
    }
    ddafrac::common::write_whole_text(o.out_dir / "history.csv", history);
    st.times.output += omp_get_wtime() - w0;
    r.wall = omp_get_wtime() - t0;
    r.steps = st.steps;
    r.time = engine.time();
    ddafrac::common::write_whole_text(o.out_dir / "summary.json", summary_json(engine, o, r, {{"peak", peaks}, {"unit", "N/m"}}).dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
  };

  r.reason = "running";
  sample_loading();
  write_outputs(true);
  long next_output = 1;
  double last_progress = -1e300;
  bool snapshot_at_end = false;
  StepReport last;
  try {
    for (;;) {
      if (const int signal = o.stop ? o.stop->load() : 0) {
        r.exit_status = kSignalExitBase + signal;
        r.reason = "interrupted";
        r.message = fmt::format("interrupted by signal {} at step {}, t = {:.9g} s", signal, st.steps, engine.time());
        break;
      }
      if (o.max_steps > 0 && st.steps >= o.max_steps) {
        r.reason = "max_steps";
        break;
      }
      if (engine.time() >= end * (1.0 - kTimeSlack)) {
        r.reason = "completed";
        break;
      }
      const double t_out = std::min(end, static_cast<double>(next_output) * interval);
      if (o.between_steps) {
        const int threads = o.between_steps();
        if (r.threads_fewest > 0 && threads != current_threads) ++r.thread_count_changes;
        current_threads = threads;
        r.threads_fewest = r.threads_fewest > 0 ? std::min(r.threads_fewest, threads) : threads;
      }
      const StepReport rep = engine.step(t_out - engine.time());
      check_finite(rep);
      last = rep;
      sample_loading();
      if (rep.step % std::max(1, o.history_every) == 0) history += history_row(rep);
      snapshot_at_end = true;
      if (engine.time() >= t_out - kTimeSlack * interval) {
        ++next_output;
        write_outputs(true);
        snapshot_at_end = false;
      }
      if (o.progress) {
        const double now = omp_get_wtime();
        if (now - last_progress >= o.progress_every) {
          last_progress = now;
          o.progress({engine.time(), end, rep.step, rep.dt, rep.open_close, rep.cg_iterations, now - t0});
        }
      }
    }
  } catch (const NumericalTrouble& ex) {
    r.exit_status = kRunNumericalTrouble;
    r.reason = "numerical_trouble";
    r.message = ex.what();
  }
  if (o.progress)
    o.progress({engine.time(), end, st.steps, last.dt, last.open_close, last.cg_iterations, omp_get_wtime() - t0});
  // After numerical trouble the blocks' state may hold NaN: the files keep the last good one.
  const bool state_valid = r.exit_status != kRunNumericalTrouble;
  write_outputs(snapshot_at_end && state_valid, state_valid);
  return r;
}

}  // namespace ddafrac::dda
