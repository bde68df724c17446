#include "ddafrac/dda/run.hpp"

#include <fmt/core.h>
#include <omp.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <system_error>

namespace ddafrac::dda {

namespace fs = std::filesystem;

namespace {
/// Relative slack when comparing simulated times with output times.
constexpr double kTimeSlack = 1e-9;

const char* mode_name(scene::Mode m) { return m == scene::Mode::Dynamic ? "dynamic" : "static"; }
const char* plane_name(scene::PlaneModel p) { return p == scene::PlaneModel::Stress ? "stress" : "strain"; }

std::string history_header() {
  return "step,t,dt,open_close_iterations,cg_iterations,dt_cuts,kinetic_energy,strain_energy,contact_energy,"
         "max_penetration,contacts,closed,sliding\n";
}

std::string history_row(const StepReport& r) {
  return fmt::format("{},{:.17g},{:.17g},{},{},{},{:.17g},{:.17g},{:.17g},{:.17g},{},{},{}\n", r.step, r.time, r.dt,
                     r.open_close, r.cg_iterations, r.cuts, r.energy.kinetic, r.energy.strain, r.energy.contact,
                     r.max_penetration, r.contacts, r.closed, r.sliding);
}

struct Snapshot {
  double time;
  std::string file;  // relative to the run directory
};

std::string pvd_document(const std::vector<Snapshot>& snaps) {
  std::string s = "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n  <Collection>\n";
  for (const auto& p : snaps)
    s += fmt::format("    <DataSet timestep=\"{:.17g}\" group=\"\" part=\"0\" file=\"{}\"/>\n", p.time, p.file);
  s += "  </Collection>\n</VTKFile>\n";
  return s;
}

nlohmann::json summary_json(const Engine& e, const RunOptions& o, const RunResult& r, double setup_wall) {
  using nlohmann::json;
  const auto& sc = e.scene();
  const auto& an = sc.analysis;
  const Statistics& st = e.statistics();
  json j;
  j["ddafrac_version"] = DDAFRAC_VERSION;
  j["scene"] = {{"name", sc.name},
                {"source", sc.source.string()},
                {"mode", mode_name(an.mode)},
                {"plane", plane_name(an.plane)},
                {"dt_max", an.dt_max},
                {"max_displacement_ratio", an.max_displacement_ratio},
                {"penalty", an.penalty},
                {"end_time", an.end_time},
                {"output_interval", an.output_interval},
                {"gravity", {an.gravity[0], an.gravity[1]}},
                {"open_close_max", an.open_close_max},
                {"blocks", e.blocks().block_count()},
                {"virtual_joints", e.blocks().joints.size()}};
  j["threads"] = o.threads;
  j["solver"] = to_string(e.options().solver.kind);
  j["allowed_step_displacement"] = e.allowed_displacement();
  j["contact_search_distance"] = e.options().detection.search_distance;
  const PhaseTimes& t = st.times;
  j["wall_time"] = {{"setup", setup_wall},     {"detection", t.detection}, {"assembly", t.assembly},
                    {"solve", t.solve},        {"judgement", t.judgement}, {"update", t.update},
                    {"output", t.output},      {"total", r.wall}};
  j["steps"] = st.steps;
  j["simulated_time"] = e.time();
  j["dt"] = {{"min", st.dt_min},
             {"max", st.dt_max},
             {"mean", st.steps > 0 ? st.dt_sum / static_cast<double>(st.steps) : 0.0},
             {"cuts_displacement", st.cuts_displacement},
             {"cuts_open_close", st.cuts_open_close},
             {"cuts_solver", st.cuts_solver}};
  j["open_close"] = {{"total", st.open_close_total},
                     {"mean", st.steps > 0 ? static_cast<double>(st.open_close_total) / static_cast<double>(st.steps) : 0.0},
                     {"max", st.open_close_max}};
  j["cg"] = {{"solves", st.solves},
             {"total", st.cg_total},
             {"mean", st.solves > 0 ? static_cast<double>(st.cg_total) / static_cast<double>(st.solves) : 0.0},
             {"max", st.cg_max}};
  j["max_penetration"] = st.max_penetration;
  j["contacts"] = e.contacts().contacts.size();
  j["active_terms"] = e.active_terms().names();
  j["cracks"] = {{"total", 0}, {"tensile", 0}, {"shear", 0}};
  j["exit"] = {{"status", r.exit_status}, {"reason", r.reason}, {"message", r.message}};
  return j;
}

}  // namespace

void write_file_atomically(const fs::path& path, const std::string& content) {
  const fs::path tmp = path.string() + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error("cannot write " + tmp.string());
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
    out.flush();
    if (!out) throw std::runtime_error("cannot write " + tmp.string());
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) throw std::runtime_error("cannot rename " + tmp.string() + " to " + path.string() + ": " + ec.message());
}

void principal_stresses(const Vec3& s, double& sigma1, double& sigma3) {
  const double c = 0.5 * (s[0] + s[1]);
  const double r = std::hypot(0.5 * (s[0] - s[1]), s[2]);
  sigma1 = c + r;
  sigma3 = c - r;
}

std::string vtu_document(const Engine& e) {
  const BlockSystem& b = e.blocks();
  const std::size_t nb = b.block_count();
  std::string s;
  s.reserve(200 * b.vertex_count() + 400 * nb);
  s += "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n";
  s += fmt::format("<UnstructuredGrid>\n<Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n", b.vertex_count(), nb);
  s += "<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (std::size_t v = 0; v < b.vertex_count(); ++v) s += fmt::format("{:.12g} {:.12g} 0\n", b.vx[v], b.vy[v]);
  s += "</DataArray>\n</Points>\n<Cells>\n<DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">\n";
  for (std::size_t v = 0; v < b.vertex_count(); ++v) s += fmt::format("{}\n", v);
  s += "</DataArray>\n<DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">\n";
  for (std::size_t c = 0; c < nb; ++c) s += fmt::format("{}\n", b.vertex_offsets[c + 1]);
  s += "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
  for (std::size_t c = 0; c < nb; ++c) s += "7\n";
  s += "</DataArray>\n</Cells>\n<CellData Scalars=\"sigma1\">\n";
  s += "<DataArray type=\"Int32\" Name=\"body\" format=\"ascii\">\n";
  for (std::size_t c = 0; c < nb; ++c) s += fmt::format("{}\n", b.mesh_body[c]);
  s += "</DataArray>\n<DataArray type=\"Float64\" Name=\"stress\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (std::size_t c = 0; c < nb; ++c) s += fmt::format("{:.9g} {:.9g} {:.9g}\n", b.stress[c][0], b.stress[c][1], b.stress[c][2]);
  std::string s1 = "</DataArray>\n<DataArray type=\"Float64\" Name=\"sigma1\" format=\"ascii\">\n";
  std::string s3 = "</DataArray>\n<DataArray type=\"Float64\" Name=\"sigma3\" format=\"ascii\">\n";
  for (std::size_t c = 0; c < nb; ++c) {
    double a, z;
    principal_stresses(b.stress[c], a, z);
    s1 += fmt::format("{:.9g}\n", a);
    s3 += fmt::format("{:.9g}\n", z);
  }
  s += s1 + s3;
  s += "</DataArray>\n<DataArray type=\"Float64\" Name=\"velocity\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (std::size_t c = 0; c < nb; ++c) s += fmt::format("{:.9g} {:.9g} 0\n", b.velocity[c][kU], b.velocity[c][kV]);
  s += "</DataArray>\n</CellData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
  return s;
}

RunResult run_simulation(Engine& engine, const RunOptions& o) {
  const double t0 = omp_get_wtime();
  RunResult r;
  fs::create_directories(o.out_dir);
  if (o.vtk) fs::create_directories(o.out_dir / "vtk");
  const auto& an = engine.scene().analysis;
  const double end = an.end_time;
  const double interval = an.output_interval > 0.0 ? an.output_interval : end;
  std::string history = history_header();
  std::vector<Snapshot> snaps;
  Statistics& st = engine.statistics();
  const double setup_wall = 0.0;

  auto write_outputs = [&](bool snapshot) {
    const double w0 = omp_get_wtime();
    if (snapshot && o.vtk) {
      const std::string name = fmt::format("vtk/snapshot_{:06d}.vtu", snaps.size());
      write_file_atomically(o.out_dir / name, vtu_document(engine));
      snaps.push_back({engine.time(), name});
      write_file_atomically(o.out_dir / "run.pvd", pvd_document(snaps));
    }
    write_file_atomically(o.out_dir / "history.csv", history);
    st.times.output += omp_get_wtime() - w0;
    r.wall = omp_get_wtime() - t0;
    r.steps = st.steps;
    r.time = engine.time();
    write_file_atomically(o.out_dir / "summary.json", summary_json(engine, o, r, setup_wall).dump(2) + "\n");
  };

  r.reason = "running";
  write_outputs(true);
  long next_output = 1;
  double last_progress = -1e300;
  bool snapshot_at_end = false;
  StepReport last;
  try {
    for (;;) {
      if (o.stop && o.stop->load()) {
        r.exit_status = kRunInterrupted;
        r.reason = "interrupted";
        r.message = fmt::format("interrupted at step {}, t = {:.9g} s", st.steps, engine.time());
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
      const StepReport rep = engine.step(t_out - engine.time());
      last = rep;
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
  write_outputs(snapshot_at_end);
  return r;
}

}  // namespace ddafrac::dda
