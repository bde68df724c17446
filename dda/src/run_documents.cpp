#include "run_documents.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

#include "ddafrac/build_commit.hpp"
#include "ddafrac/common/pvd.hpp"
#include "ddafrac/dda/crack_metrics.hpp"
#include "ddafrac/reference/analytic.hpp"

namespace ddafrac::dda {

namespace {

const char* mode_name(scene::Mode m) { return m == scene::Mode::Dynamic ? "dynamic" : "static"; }
const char* plane_name(scene::PlaneModel p) { return p == scene::PlaneModel::Stress ? "stress" : "strain"; }

}  // namespace

std::string history_header() {
  return "step,t,dt,open_close_iterations,cg_iterations,dt_cuts,kinetic_energy,strain_energy,contact_energy,"
         "kinetic_free_energy,kinetic_strain_ratio,max_penetration,contacts,closed,sliding,new_cracks,cracks_total,"
         "cracks_tensile,"
         "cracks_shear,support_energy,work_gravity,work_loads,work_supports,friction_dissipation,joint_break_loss,"
         "numerical_dissipation,damping_dissipation,balance_error,residual_contacts_kept,residual_contacts_reclosed,"
         "residual_contacts_new,"
         "residual_blocks,residual_supports\n";
}

std::string history_row(const StepReport& r) {
  const double ratio = r.energy.strain > 0.0 ? r.energy.kinetic_free / r.energy.strain : 0.0;
  const StepEnergy& w = r.ledger.total;
  const ResidualSources& rs = r.ledger.residual_sources;
  return fmt::format(
      "{},{:.17g},{:.17g},{},{},{},{:.17g},{:.17g},{:.17g},{:.17g},{:.9g},{:.17g},{},{},{},{},{},{},{},"
      "{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.9g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}"
      "\n",
      r.step, r.time, r.dt, r.open_close, r.cg_iterations, r.cuts, r.energy.kinetic, r.energy.strain, r.energy.contact,
      r.energy.kinetic_free, ratio, r.max_penetration, r.contacts, r.closed, r.sliding, r.new_cracks, r.cracks.total,
      r.cracks.tensile, r.cracks.shear, r.energy.support, w.work_gravity, w.work_loads, w.work_supports, w.friction,
      w.joint_breaks, w.numerical, w.damping, r.ledger.balance_error(), rs.contacts_kept, rs.contacts_reclosed,
      rs.contacts_new, rs.blocks, rs.supports);
}

std::string cracks_document(const std::vector<CrackEvent>& cracks) {
  std::string s = "t,x,y,type,joint,r1,r2\n";
  for (const CrackEvent& c : cracks)
    s += fmt::format("{:.17g},{:.17g},{:.17g},{},{},{:.17g},{:.17g}\n", c.t, c.x, c.y, to_string(c.type), c.joint, c.r1,
                     c.r2);
  return s;
}

std::string crack_intervals_document(const std::vector<CrackEvent>& cracks, double width, double time) {
  const auto bins = static_cast<std::size_t>(std::max(1.0, std::ceil(time / width * (1.0 - kTimeSlack))));
  std::vector<CrackCounts> n(bins);
  for (const CrackEvent& c : cracks) {
    const auto k = std::min(bins - 1, static_cast<std::size_t>(std::max(0.0, c.t / width * (1.0 - kTimeSlack))));
    ++n[k].total;
    if (c.type == CrackType::Tensile)
      ++n[k].tensile;
    else
      ++n[k].shear;
  }
  std::string s = "interval_start,interval_end,total,tensile,shear\n";
  for (std::size_t k = 0; k < bins; ++k)
    s += fmt::format("{:.9g},{:.9g},{},{},{}\n", static_cast<double>(k) * width, static_cast<double>(k + 1) * width,
                     n[k].total, n[k].tensile, n[k].shear);
  return s;
}

namespace {

const std::string& body_name(const Engine& e, const BodyCracks& b) {
  return e.scene().bodies[static_cast<std::size_t>(b.body)].name;
}

nlohmann::json optional_time(const std::optional<double>& t) { return t ? nlohmann::json(*t) : nlohmann::json(); }

}  // namespace

std::string fragments_document(const Engine& e) {
  const auto& an = e.scene().analysis;
  const double interval = an.output_interval > 0.0 ? an.output_interval : an.end_time;
  std::vector<double> times;
  for (long k = 0; static_cast<double>(k) * interval <= e.time() * (1.0 + kTimeSlack); ++k)
    times.push_back(static_cast<double>(k) * interval);
  if (times.back() < e.time() * (1.0 - kTimeSlack)) times.push_back(e.time());
  // A crack at an output's step belongs to that output, whatever the last bits of its time.
  std::vector<double> reach(times);
  for (double& t : reach) t *= 1.0 + kTimeSlack;
  const CrackHistory h = crack_history(e.blocks(), e.cracks(), reach);
  std::string s =
      "t,body,cracks_tensile,cracks_shear,crack_length_tensile,crack_length_shear,fragments,through_fragments,"
      "largest_fragment_area,largest_fragment_fraction\n";
  for (std::size_t k = 0; k < times.size(); ++k)
    for (const BodyCracks& b : h.at_times[k])
      s += fmt::format("{:.9g},{},{},{},{:.9g},{:.9g},{},{},{:.9g},{:.9g}\n", times[k], body_name(e, b),
                       b.cracks_tensile, b.cracks_shear, b.length_tensile, b.length_shear, b.fragments,
                       b.through_fragments, b.largest_fragment_area, b.largest_fragment_area / b.area);
  return s;
}

nlohmann::json crack_metrics_json(const Engine& e) {
  const CrackHistory h = crack_history(e.blocks(), e.cracks());
  nlohmann::json j = {
      {"definitions",
       {{"fragment", "blocks of one body still joined by intact virtual joints; areas at t = 0"},
        {"through_crack", "the body is in at least 2 fragments each of at least through_fragment_fraction of its area"},
        {"through_fragment_fraction", kThroughCrackFragmentFraction}}},
      {"units", {{"length", "m"}, {"area", "m^2"}, {"time", "s"}}},
      {"bodies", nlohmann::json::array()}};
  std::optional<double> first, first_through;
  double length_tensile = 0.0, length_shear = 0.0;  // m
  long fragments = 0;
  const auto earliest = [](std::optional<double>& a, const std::optional<double>& b) {
    if (b && (!a || *b < *a)) a = b;
  };
  for (std::size_t k = 0; k < h.now.size(); ++k) {
    const BodyCracks& b = h.now[k];
    j["bodies"].push_back({{"body", body_name(e, b)},
                           {"area", b.area},
                           {"cracks_tensile", b.cracks_tensile},
                           {"cracks_shear", b.cracks_shear},
                           {"crack_length_tensile", b.length_tensile},
                           {"crack_length_shear", b.length_shear},
                           {"fragments", b.fragments},
                           {"through_fragments", b.through_fragments},
                           {"largest_fragment_area", b.largest_fragment_area},
                           {"largest_fragment_fraction", b.largest_fragment_area / b.area},
                           {"first_crack_time", optional_time(h.first_crack[k])},
                           {"first_through_crack_time", optional_time(h.first_through_crack[k])}});
    length_tensile += b.length_tensile;
    length_shear += b.length_shear;
    fragments += b.fragments;
    earliest(first, h.first_crack[k]);
    earliest(first_through, h.first_through_crack[k]);
  }
  j["crack_length_tensile"] = length_tensile;
  j["crack_length_shear"] = length_shear;
  j["fragments"] = fragments;
  j["first_crack_time"] = optional_time(first);
  j["first_through_crack_time"] = optional_time(first_through);
  return j;
}

std::string pvd_document(const std::vector<Snapshot>& snaps) {
  std::vector<common::PvdEntry> entries;
  for (const Snapshot& s : snaps) entries.push_back({s.time, s.file});
  return common::pvd_document(entries);
}

nlohmann::json summary_json(const Engine& e, const RunOptions& o, const RunResult& r, const nlohmann::json& loading) {
  using nlohmann::json;
  const auto& sc = e.scene();
  const auto& an = sc.analysis;
  const Statistics& st = e.statistics();
  json j;
  j["ddafrac_version"] = DDAFRAC_VERSION;
  j["ddafrac_commit"] = DDAFRAC_COMMIT;  // which engine wrote these results
  j["ddafrac_arch"] = DDAFRAC_ARCH;      // and for which instruction set: the last digits depend on it
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
                {"search_distance_factor", an.search_distance_factor},
                {"pair_list_skin_factor", an.pair_list_skin_factor},
                {"solver_tolerance", an.solver_tolerance},
                {"mass_damping", an.mass_damping},
                {"intact_nodes", scene::to_string(an.intact_nodes)},
                {"fracture_load", scene::to_string(an.fracture_load)},
                {"fracture_stress_radius", an.fracture_stress_radius},
                {"blocks", e.blocks().block_count()},
                {"virtual_joints", e.blocks().joints.size()}};
  j["threads"] = o.threads;
  j["threads_fewest"] = r.threads_fewest > 0 ? r.threads_fewest : o.threads;
  j["thread_count_changes"] = r.thread_count_changes;
  j["solver"] = to_string(e.options().solver.kind);
  j["allowed_step_displacement"] = e.allowed_displacement();
  j["contact_search_distance"] = e.options().detection.search_distance;
  const PhaseTimes& t = st.times;
  j["wall_time"] = {{"setup", o.setup_wall}, {"detection", t.detection}, {"assembly", t.assembly},
                    {"solve", t.solve},      {"judgement", t.judgement}, {"fracture", t.fracture},
                    {"update", t.update},    {"output", t.output},       {"total", r.wall}};
  j["steps"] = st.steps;
  j["simulated_time"] = e.time();
  j["dt"] = {{"min", st.dt_min},
             {"max", st.dt_max},
             {"mean", st.steps > 0 ? st.dt_sum / static_cast<double>(st.steps) : 0.0},
             {"cuts_displacement", st.cuts_displacement},
             {"cuts_open_close", st.cuts_open_close},
             {"cuts_solver", st.cuts_solver}};
  j["open_close"] = {
      {"total", st.open_close_total},
      {"mean", st.steps > 0 ? static_cast<double>(st.open_close_total) / static_cast<double>(st.steps) : 0.0},
      {"max", st.open_close_max}};
  j["cg"] = {{"solves", st.solves},
             {"total", st.cg_total},
             {"mean", st.solves > 0 ? static_cast<double>(st.cg_total) / static_cast<double>(st.solves) : 0.0},
             {"max", st.cg_max}};
  const EnergyLedger& ledger = e.ledger();
  j["energy"] = {{"unit", "J/m"},
                 {"initial", ledger.initial},
                 {"stored",
                  {{"kinetic", ledger.stored.kinetic},
                   {"strain", ledger.stored.strain},
                   {"contact", ledger.stored.contact},
                   {"support", ledger.stored.support},
                   {"total", ledger.stored.stored()}}},
                 {"work",
                  {{"gravity", ledger.total.work_gravity},
                   {"loads", ledger.total.work_loads},
                   {"supports", ledger.total.work_supports},
                   {"total", ledger.work()}}},
                 {"dissipated",
                  {{"friction", ledger.total.friction},
                   {"joint_breaks", ledger.total.joint_breaks},
                   {"numerical", ledger.total.numerical},
                   {"damping", ledger.total.damping},
                   {"total", ledger.dissipated()}}},
                 {"residual",
                  {{"contacts_kept", ledger.residual_sources.contacts_kept},
                   {"contacts_reclosed", ledger.residual_sources.contacts_reclosed},
                   {"contacts_new", ledger.residual_sources.contacts_new},
                   {"blocks", ledger.residual_sources.blocks},
                   {"supports", ledger.residual_sources.supports},
                   {"total", ledger.residual()}}},
                 {"balance_error", ledger.balance_error()},
                 {"largest_balance_error", ledger.largest_balance_error}};
  j["max_penetration"] = st.max_penetration;
  j["cohesion_failures"] = st.cohesion_failures;
  j["missed_contacts"] = {{"count", st.missed_contacts}, {"deepest_m", st.deepest_missed}};
  j["ties_lost"] = st.ties_lost;
  j["initial_overlaps"] = {{"count", st.initial_overlaps}, {"deepest_m", st.deepest_initial_overlap}};
  j["contacts"] = e.contacts().contacts.size();
  j["active_terms"] = e.active_terms().names();
  const CrackCounts& cc = e.crack_counts();
  j["cracks"] = {
      {"total", cc.total}, {"tensile", cc.tensile}, {"shear", cc.shear}, {"interval", sc.output.crack_interval}};
  j["crack_metrics"] = crack_metrics_json(e);
  {
    // Joints softening past their strength (JointSet::fracture_energy), not yet broken.
    long softening = 0;
    double largest = 0.0;
    for (const Joint& jt : e.blocks().joints)
      if (!jt.broken && jt.damage > 0.0) {
        ++softening;
        largest = std::max(largest, jt.damage);
      }
    j["joints_softening"] = {{"count", softening}, {"largest_damage", largest}};
  }
  if (!e.blocks().joints.empty()) {
    const JointLoadShare share = joint_load_share(e.blocks(), e.joint_forces());
    j["joint_load_share"] = {
        {"normal", share.normal},
        {"shear", share.shear},
        {"joints", share.joints},
        {"definition",
         "least-squares slope of the intact joints' forces on the load their blocks' mean stress puts on them "
         "(joints/*.csv stress_*_force): 1 where the joints carry their blocks' load, below 1 where other contacts "
         "carry part of it past them"}};
  }
  j["loading"] = loading;
  j["exit"] = {{"status", r.exit_status}, {"reason", r.reason}, {"message", r.message}};
  return j;
}

std::string vtu_document(const Engine& e) {
  const BlockSystem& b = e.blocks();
  const std::size_t nb = b.block_count();
  std::vector<const Joint*> lines;
  for (const Joint& j : b.joints)
    if (j.broken && j.failure != CrackType::None) lines.push_back(&j);
  const std::size_t nl = lines.size();
  std::string s;
  s.reserve(200 * b.vertex_count() + 400 * nb);
  s += "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n";
  s += fmt::format("<UnstructuredGrid>\n<Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n", b.vertex_count(),
                   nb + nl);
  s += "<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (std::size_t v = 0; v < b.vertex_count(); ++v) s += fmt::format("{:.12g} {:.12g} 0\n", b.vx[v], b.vy[v]);
  s += "</DataArray>\n</Points>\n<Cells>\n<DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">\n";
  for (std::size_t v = 0; v < b.vertex_count(); ++v) s += fmt::format("{}\n", v);
  for (const Joint* j : lines) s += fmt::format("{}\n{}\n", j->vertex_a, j->vertex_b);
  s += "</DataArray>\n<DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">\n";
  for (std::size_t c = 0; c < nb; ++c) s += fmt::format("{}\n", b.vertex_offsets[c + 1]);
  for (std::size_t c = 0; c < nl; ++c) s += fmt::format("{}\n", b.vertex_count() + 2 * (c + 1));
  s += "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
  for (std::size_t c = 0; c < nb; ++c) s += "7\n";
  for (std::size_t c = 0; c < nl; ++c) s += "3\n";
  s += "</DataArray>\n</Cells>\n<CellData Scalars=\"sigma1\">\n";
  s += "<DataArray type=\"Int32\" Name=\"body\" format=\"ascii\">\n";
  for (std::size_t c = 0; c < nb; ++c) s += fmt::format("{}\n", b.mesh_body[c]);
  for (std::size_t c = 0; c < nl; ++c) s += "-1\n";
  s += "</DataArray>\n<DataArray type=\"UInt8\" Name=\"crack_type\" format=\"ascii\">\n";
  for (std::size_t c = 0; c < nb; ++c) s += "0\n";
  for (const Joint* j : lines) s += fmt::format("{}\n", static_cast<int>(j->failure));
  s += "</DataArray>\n<DataArray type=\"Float64\" Name=\"stress\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (std::size_t c = 0; c < nb; ++c)
    s += fmt::format("{:.9g} {:.9g} {:.9g}\n", b.stress[c][0], b.stress[c][1], b.stress[c][2]);
  for (std::size_t c = 0; c < nl; ++c) s += "0 0 0\n";
  std::string s1 = "</DataArray>\n<DataArray type=\"Float64\" Name=\"sigma1\" format=\"ascii\">\n";
  std::string s3 = "</DataArray>\n<DataArray type=\"Float64\" Name=\"sigma3\" format=\"ascii\">\n";
  for (std::size_t c = 0; c < nb; ++c) {
    const reference::Principal p = reference::principal({b.stress[c][0], b.stress[c][1], b.stress[c][2]});
    s1 += fmt::format("{:.9g}\n", p.s1);
    s3 += fmt::format("{:.9g}\n", p.s3);
  }
  for (std::size_t c = 0; c < nl; ++c) {
    s1 += "0\n";
    s3 += "0\n";
  }
  s += s1 + s3;
  s += "</DataArray>\n<DataArray type=\"Float64\" Name=\"velocity\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (std::size_t c = 0; c < nb; ++c) s += fmt::format("{:.9g} {:.9g} 0\n", b.velocity[c][kU], b.velocity[c][kV]);
  for (std::size_t c = 0; c < nl; ++c) s += "0 0 0\n";
  s += "</DataArray>\n<DataArray type=\"Float64\" Name=\"joint_utilisation\" format=\"ascii\">\n";
  for (const double u : e.joint_utilisation()) s += fmt::format("{:.6g}\n", u);
  for (std::size_t c = 0; c < nl; ++c) s += "0\n";
  s += "</DataArray>\n</CellData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
  return s;
}

std::string joints_document(const Engine& e) {
  const std::vector<Joint>& joints = e.blocks().joints;
  const std::vector<JointForce> f = e.joint_forces();
  const std::vector<FailureRatios> ratio = e.joint_ratios(e.fracture_loads(f));
  std::vector<std::size_t> carrying;
  for (std::size_t j = 0; j < joints.size(); ++j)
    if (f[j].judged(joints[j])) carrying.push_back(j);
  std::stable_sort(carrying.begin(), carrying.end(),
                   [&](std::size_t i, std::size_t j) { return ratio[i].largest() > ratio[j].largest(); });
  std::string s =
      "t,joint,block_a,block_b,x,y,length,normal_force,shear_force,r1,r2,utilisation,stress_normal_force,"
      "stress_shear_force\n";
  s.reserve(s.size() + 200 * carrying.size());
  for (const std::size_t j : carrying) {
    const Joint& jt = joints[j];
    const meshes::Point mid = e.blocks().joint_midpoint(jt);
    const JointForce traction = stress_traction(e.blocks(), jt);
    s += fmt::format("{:.17g},{},{},{},{:.12g},{:.12g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g}\n",
                     e.time(), j, jt.block_a, jt.block_b, mid.x, mid.y, jt.length, f[j].normal, f[j].shear, ratio[j].r1,
                     ratio[j].r2, ratio[j].largest(), traction.normal, traction.shear);
  }
  return s;
}

}  // namespace ddafrac::dda
