// The engine's carried state as bytes (Engine::carried_state / restore_carried_state): every
// field that one step hands to the next, written with Boost.Serialization's binary archive
// (exact doubles; a checkpoint is read back on the machine type that wrote it). Fields that the
// constructor rebuilds from the scene and mesh (offsets, materials, masses, joint topology) are
// not stored; the checkpoint's fingerprint of the state at t = 0 makes sure they match
// (docs/design.md §11).

#include <boost/archive/binary_iarchive.hpp>
#include <boost/archive/binary_oarchive.hpp>
#include <boost/serialization/array_wrapper.hpp>
#include <boost/serialization/string.hpp>
#include <boost/serialization/vector.hpp>

#include <sstream>

#include "ddafrac/dda/engine.hpp"

namespace boost::serialization {

template <class Archive, int Rows, int Cols, int Options, int MaxRows, int MaxCols>
void serialize(Archive& archive, Eigen::Matrix<double, Rows, Cols, Options, MaxRows, MaxCols>& m, unsigned) {
  archive& make_array(m.data(), static_cast<std::size_t>(m.size()));
}

}  // namespace boost::serialization

namespace ddafrac::dda {

// A field added to one of these records must be added to its function below as well, or a
// resumed run silently starts from its default: the sizes make the compiler say so.
static_assert(sizeof(Contact) == 264, "Contact changed: update serialize(Contact) in engine_state.cpp");
static_assert(sizeof(Statistics) == 216, "Statistics changed: update serialize(Statistics)");
static_assert(sizeof(Joint) == 48, "Joint changed: update serialize(Joint)");

template <class Archive>
void serialize(Archive& a, PolygonIntegrals& g, unsigned) {
  a& g.area& g.cx& g.cy& g.sxx& g.syy& g.sxy;
}

template <class Archive>
void serialize(Archive& a, Anchor& p, unsigned) {
  a& p.block& p.x& p.y& p.x_start& p.y_start& p.vx& p.vy;
}

template <class Archive>
void serialize(Archive& a, PointLoad& p, unsigned) {
  a& p.block& p.x& p.y& p.fx& p.fy;
}

template <class Archive>
void serialize(Archive& a, Joint& j, unsigned) {
  a& j.block_a& j.block_b& j.node_a& j.node_b& j.vertex_a& j.vertex_b& j.length& j.joint_set& j.broken& j.failure& j
      .damage;
}

template <class Archive>
void serialize(Archive& a, Contact& c, unsigned) {
  a& c.vblock& c.eblock& c.vertex& c.edge0& c.edge1& c.joint& c.joint_set& c.vertex_vertex& c.shared_node& c.tied;
  a& c.state& c.ref_t& c.normal_force& c.shear_force& c.slip& c.slide_sign& c.rest_gap;
  a& c.cohesive& c.cohesive_length& c.stored_normal& c.stored_shear& c.was_bonded;
  a& c.kn& c.ks& c.tan_phi& c.cohesion& c.tensile_strength& c.damage;
  a& c.damaged_ks& c.damaged_slip& c.stored_damaged& c.damaged_state& c.damaged_trial;
  a& c.d0& c.s0& c.edge_length;
  a& c.trial& c.fn_iter& c.friction_force& c.d_iter& c.s_iter& c.cohesion_lost& c.carried& c.same_line;
}

template <class Archive>
void serialize(Archive& a, ContactPair& p, unsigned) {
  a& p.a& p.b& p.first& p.last;
}

template <class Archive>
void serialize(Archive& a, ContactSet& s, unsigned) {
  a& s.contacts& s.pairs& s.block_contact_offsets& s.block_contacts& s.block_pair_offsets& s.block_pairs;
}

template <class Archive>
void serialize(Archive& a, CrackEvent& c, unsigned) {
  a& c.t& c.x& c.y& c.type& c.joint& c.r1& c.r2;
}

template <class Archive>
void serialize(Archive& a, CrackCounts& c, unsigned) {
  a& c.total& c.tensile& c.shear;
}

template <class Archive>
void serialize(Archive& a, PhaseTimes& t, unsigned) {
  a& t.detection& t.assembly& t.solve& t.judgement& t.fracture& t.update& t.output;
}

template <class Archive>
void serialize(Archive& a, Statistics& s, unsigned) {
  a& s.steps& s.dt_min& s.dt_max& s.dt_sum& s.cuts_displacement& s.cuts_open_close& s.cuts_solver;
  a& s.open_close_total& s.open_close_max& s.solves& s.cg_total& s.cg_max& s.max_penetration;
  a& s.cohesion_failures& s.missed_contacts& s.deepest_missed& s.initial_overlaps& s.deepest_initial_overlap;
  a& s.pair_list_builds& s.ties_lost& s.times;
}

template <class Archive>
void serialize(Archive& a, Energies& e, unsigned) {
  a& e.kinetic& e.kinetic_free& e.strain& e.contact& e.support;
}

template <class Archive>
void serialize(Archive& a, StepEnergy& e, unsigned) {
  a& e.work_gravity& e.work_loads& e.work_supports& e.friction& e.joint_breaks& e.numerical& e.damping;
}

template <class Archive>
void serialize(Archive& a, ResidualSources& r, unsigned) {
  a& r.contacts_kept& r.contacts_reclosed& r.contacts_new& r.blocks& r.supports;
}

template <class Archive>
void serialize(Archive& a, EnergyLedger& l, unsigned) {
  a& l.initial& l.stored& l.total& l.residual_sources& l.largest_balance_error;
}

template <class Archive>
void serialize(Archive& a, ActiveTerms& t, unsigned) {
  a& t.dynamic& t.elasticity& t.initial_stress& t.gravity& t.point_loads& t.anchors& t.contacts& t.friction;
  a& t.cohesion& t.bonded_joints& t.fracture& t.damping;
}

template <class Archive>
void Engine::serialize_carried_state(Archive& a) {
  // Blocks: where they are, how they move and what they carry.
  a& blocks_.vx& blocks_.vy& blocks_.geometry& blocks_.min_edge& blocks_.velocity& blocks_.stress& blocks_.strain;
  a& blocks_.anchors& blocks_.loads& blocks_.joints;
  // Contacts (the next detection carries their state over) and the pair list.
  a& set_& detection_.pairs& detection_.built_x& detection_.built_y& detection_.pair_list_builds;
  // The last displacement warm-starts the next solve; the clocks and step-size control.
  a& d_& time_& dt_& dt_prev_& step_;
  a& stats_& active_& ledger_& cracks_& crack_counts_;
}

std::string Engine::carried_state() const {
  std::ostringstream bytes(std::ios::binary);
  {
    boost::archive::binary_oarchive archive(bytes);
    // Saving only reads the members; Boost's one serialize function serves both directions.
    const_cast<Engine*>(this)->serialize_carried_state(archive);
  }
  return std::move(bytes).str();
}

void Engine::restore_carried_state(const std::string& state) {
  std::istringstream bytes(state, std::ios::binary);
  boost::archive::binary_iarchive archive(bytes);
  serialize_carried_state(archive);
  // The pair list's hints are not carried: without them every pair is judged in full until the
  // next build, which finds the same contacts (PairHint), and those of another list must not stay.
  detection_.pair_hints.clear();
}

}  // namespace ddafrac::dda
