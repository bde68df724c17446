#pragma once
// The DDA time stepper: composes block terms, contacts, the open-close iteration, the linear
// solver and the time-step control into one accepted step at a time. No global state: all of it
// lives in an Engine object; several engines can run side by side.

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "ddafrac/dda/block_system.hpp"
#include "ddafrac/dda/contact.hpp"
#include "ddafrac/dda/contact_mechanics.hpp"
#include "ddafrac/dda/energy_ledger.hpp"
#include "ddafrac/dda/linear_system.hpp"
#include "ddafrac/dda/stress_average.hpp"
#include "ddafrac/meshes/mesh.hpp"
#include "ddafrac/scene/scene.hpp"

namespace ddafrac::dda {

struct EngineOptions {
  SolverSettings solver;
  bool bond_virtual_joints = true;       // same-body shared edges start as bonded joints
  double anchor_penalty_factor = 100.0;  // fixed/prescribed point springs = factor·penalty (N/m)
  double allowed_displacement = 0.0;     // m; 0 = max_displacement_ratio · half model height
  double dt_cut_factor = 0.3;            // dt ×= this on a failed step
  double dt_grow_factor = 1.2;           // dt ×= this after an easy step, up to dt_max
  int easy_open_close = 2;               // "easy" = converged within this many iterations
  double dt_floor_fraction = 1e-6;       // dt below dt_max·this = numerical trouble
  double state_tolerance = 1e-4;         // open-close hysteresis / allowed step displacement
  DetectionParams detection;             // search_distance and skin: from the scene's analysis
  std::vector<PointLoad> point_loads;    // extra loads (tests, benchmarks)
  std::vector<Anchor> anchors;           // extra fixed/prescribed points
};

/// Wall time per phase, s.
struct PhaseTimes {
  double detection = 0.0, assembly = 0.0, solve = 0.0, judgement = 0.0, fracture = 0.0, update = 0.0, output = 0.0;
  double total() const { return detection + assembly + solve + judgement + fracture + update + output; }
};

/// One virtual joint breaking: at the end of the accepted step at time t.
struct CrackEvent {
  double t = 0.0;           // s
  double x = 0.0, y = 0.0;  // joint midpoint, m
  CrackType type = CrackType::None;
  Index joint = -1;           // BlockSystem::joints index
  double r1 = 0.0, r2 = 0.0;  // f_n / f_t,max and |f_s| / f_s,max at the break
};

/// Cumulative crack counts.
struct CrackCounts {
  long total = 0, tensile = 0, shear = 0;
};

/// Forces of one joint from its contacts (N/m): tension positive, shear along node_a -> node_b
/// as the force on block_a.
struct JointForce {
  double normal = 0.0, shear = 0.0;
  // The normal force its springs would carry undamaged at the same gaps (= normal while
  // Joint::damage is 0): what drives a softening joint's damage.
  double normal_undamaged = 0.0;
  // Likewise the shear force: the intact spring ks of the set at the same slips, which the
  // damaged part's friction does not count towards (Contact::damaged_ks).
  double shear_undamaged = 0.0;
  int contacts = 0;
  /// An intact joint that carries contacts: the joints the fracture check judges.
  bool judged(const Joint& j) const { return !j.broken && contacts > 0; }
};

/// The load the blocks' stress puts on joint j (N/m, as JointForce; contacts = 0): the mean
/// stress σ of its two blocks on block_a's face, F = σ·n·l with n block_a's outward normal;
/// normal = n·F (tension positive), shear = t·F with t along node_a -> node_b. In a continuum it
/// is the joint's load: the joint's own forces differ from it by what other contacts carry past
/// the joint (docs/design.md §5).
JointForce stress_traction(const BlockSystem& blocks, const Joint& j);
/// The load a stress σ = (σxx, σyy, τxy) puts on joint j, as stress_traction.
JointForce stress_traction(const BlockSystem& blocks, const Joint& j, const Vec3& stress);

/// How much of the load their blocks' stress puts on the intact virtual joints (stress_traction)
/// the joints carry themselves: the least-squares slope of their forces on those loads over every
/// intact joint that carries contacts, Σ f·F / Σ F², normal and shear apart. 1 where the joints
/// alone carry their blocks' load; below 1, other contacts (the node contacts of an intact body)
/// carry part of it past the joints, and the fracture criterion judges less than the blocks'
/// stress says (docs/design.md §5). NaN where no such joint is loaded.
struct JointLoadShare {
  double normal = std::numeric_limits<double>::quiet_NaN();
  double shear = std::numeric_limits<double>::quiet_NaN();
  long joints = 0;  // intact joints carrying contacts
};
JointLoadShare joint_load_share(const BlockSystem& blocks, const std::vector<JointForce>& forces);

/// Failure ratios of a joint: r1 = f_n/(σt·l) (tension, 0 under compression),
/// r2 = |f_s|/(c·l + f_n,c·tanφ) with f_n,c the compressive normal force. A zero strength
/// under a nonzero load gives +inf.
struct FailureRatios {
  double r1 = 0.0, r2 = 0.0;
  bool broken() const { return r1 > 1.0 || r2 > 1.0; }
  double largest() const { return std::max(r1, r2); }  // the joint's utilisation, 1 at the strength
  CrackType type() const { return r1 > r2 ? CrackType::Tensile : CrackType::Shear; }
};
FailureRatios failure_ratios(const JointForce& f, double length, const scene::JointSet& strength);

struct StepReport {
  long step = 0;                  // number of this accepted step (1-based)
  double time = 0.0;              // s, at the end of the step
  double dt = 0.0;                // s, accepted
  int open_close = 0;             // iterations of the accepted attempt
  int cg_iterations = 0;          // over all solves of the step, retries included
  int cuts = 0;                   // dt cuts before acceptance
  std::size_t new_cracks = 0;     // joints broken by this step's fracture check
  CrackCounts cracks;             // cumulative, after this step
  double max_displacement = 0.0;  // m, largest vertex displacement of the step
  double max_penetration = 0.0;   // m, deepest closed contact after the step
  std::size_t contacts = 0, closed = 0, sliding = 0;
  Energies energy;
  EnergyLedger ledger;  // cumulative, after this step
};

struct Statistics {
  long steps = 0;
  double dt_min = 0.0, dt_max = 0.0, dt_sum = 0.0;
  long cuts_displacement = 0, cuts_open_close = 0, cuts_solver = 0;
  long open_close_total = 0;
  int open_close_max = 0;
  long solves = 0, cg_total = 0;
  int cg_max = 0;
  double max_penetration = 0.0;
  long cohesion_failures = 0;  // cohesive real-joint contacts that lost cohesion and tension
  // Contacts that came in deep (after step 1): first detected already deeper than one step's
  // allowed displacement, or whose spring took more than kDeepContactEnergyFraction of the energy
  // balance's scale at detection beyond what its record held the step before (a contact passed
  // to a deeper line, e.g. a node corner to a copy that sank within one step, design §4.6). The
  // overlap built up unseen and the spring releases ½·kn·d² at once, energy that no work put in.
  // Mostly triangles of one body that share only a mesh node; at kn/E >= 1e3 this energy wrecks
  // the run (stability study).
  long missed_contacts = 0;
  double deepest_missed = 0.0;  // m
  // Contacts of the first step overlapping by more than one step's allowed displacement: the
  // mesh's cells or bodies interpenetrate at t = 0, and their springs push them apart at once.
  long initial_overlaps = 0;
  double deepest_initial_overlap = 0.0;  // m
  long pair_list_builds = 0;             // contact pair list (Verlet list) builds
  // Ties (scene::IntactNodes::Tie) whose contact vanished from detection while intact joints at
  // their node still connected their two blocks: the tie was released for geometry alone (the
  // contact's line no longer ends at the other copy), and its energy was booked as a joint break.
  long ties_lost = 0;
  PhaseTimes times;
};

/// Which terms the time loop composed (summary.json lists them).
struct ActiveTerms {
  bool dynamic = true, elasticity = true, initial_stress = true, gravity = false, point_loads = false, anchors = false,
       contacts = false, friction = false, cohesion = false, bonded_joints = false, fracture = false, damping = false;
  std::vector<std::string> names() const;
};

/// The run ended on numerical trouble (NaN, dt below its floor, open-close never converging).
class NumericalTrouble : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Fraction of the energy balance's scale (EnergyLedger::scale) one contact's spring may take at
/// detection, beyond what its record held the step before, before it counts as come in deep
/// (Statistics::missed_contacts): a tenth of the 1% the balance is held to.
constexpr double kDeepContactEnergyFraction = 1e-3;

class Engine {
 public:
  Engine(scene::Scene scene, const meshes::Mesh& mesh, EngineOptions options = {});

  /// One accepted step no longer than max_dt (the driver uses it to land on output times).
  /// After the step is accepted, the fracture check judges every intact joint on the converged
  /// state; joints that break are recorded as crack events and become real joints from the next
  /// step on (the breaking step is not re-solved: a joint carries at most one step's load
  /// increment beyond its strength, test dda_fracture/tension_break_at_the_tensile_strength).
  /// Throws NumericalTrouble naming the step, time and worst block or contact.
  /// The phases of a step, file by file: docs/design.md §8; the step-size control: §7.
  StepReport step(double max_dt = 1e300);

  double time() const { return time_; }
  double dt() const { return dt_; }
  double allowed_displacement() const { return allowed_; }
  const scene::Scene& scene() const { return scene_; }
  const BlockSystem& blocks() const { return blocks_; }
  BlockSystem& blocks() { return blocks_; }  // tests may break joints before a step (Joint::broken)
  const ContactSet& contacts() const { return set_; }
  /// The contact detection's state: its pair list and how much narrow-phase work it did (counts of
  /// work, not of results: not carried by checkpoints).
  const DetectionWorkspace& detection() const { return detection_; }
  const Statistics& statistics() const { return stats_; }
  Statistics& statistics() { return stats_; }
  const ActiveTerms& active_terms() const { return active_; }
  const EngineOptions& options() const { return options_; }
  Energies energies() const;
  /// Energy ledger so far (stored energies as of the last accepted step).
  const EnergyLedger& ledger() const { return ledger_; }
  /// Block displacement of the last accepted step (D per block).
  const BlockVector& last_displacement() const { return d_; }

  /// Crack events so far, in order (within a step: by joint index), and their counts.
  const std::vector<CrackEvent>& cracks() const { return cracks_; }
  const CrackCounts& crack_counts() const { return crack_counts_; }
  /// Current forces of every joint from the contacts of the last accepted step (parallel).
  std::vector<JointForce> joint_forces() const;
  /// What the fracture check judges each joint on (analysis.fracture_load), from the `forces` of
  /// joint_forces(): those forces, or for the joints it judges their blocks' stress load
  /// (stress_traction).
  std::vector<JointForce> fracture_loads(std::vector<JointForce> forces) const;
  /// Failure ratios of every joint under the loads `f` of fracture_loads (zero for broken joints
  /// and joints without contacts), judged in parallel: what the fracture check breaks on.
  std::vector<FailureRatios> joint_ratios(const std::vector<JointForce>& f) const;
  /// Per block, the largest failure ratio max(r1, r2) of its intact virtual joints in the state of
  /// the last accepted step (0 where all have broken, kNoVirtualJoints on a block that never had
  /// any, as a platen): how near its joints are to breaking, 1 at the strength (docs/design.md §5).
  /// The VTU snapshots' `joint_utilisation`.
  std::vector<double> joint_utilisation() const;
  /// joint_utilisation() of a block without virtual joints: no ratio, so outside [0, ∞).
  static constexpr double kNoVirtualJoints = -1.0;

  /// Gauges of the scene: the block holding each gauge point at t = 0 (checked at construction).
  const std::vector<Index>& gauge_blocks() const { return gauge_blocks_; }

  /// Fixed and prescribed bodies: force of their anchor springs on the body (N/m) and mean
  /// displacement of their anchored points from t = 0 (m).
  struct BodyLoad {
    Index body = -1;  // Scene::bodies index
    double ux = 0.0, uy = 0.0, fx = 0.0, fy = 0.0;
  };
  std::vector<BodyLoad> body_loads() const;

  /// The state one step hands to the next (blocks, joints, contacts, pair list, clocks, step-size
  /// control, ledger, cracks, statistics) as bytes, for a checkpoint. Restored into an engine
  /// built from the same scene and mesh, the run continues bit for bit as if never stopped.
  /// Throws boost::archive::archive_exception on bytes that are not such a state.
  std::string carried_state() const;
  void restore_carried_state(const std::string& state);

 private:
  template <class Archive>
  void serialize_carried_state(Archive& archive);  // engine_state.cpp
  void detect();
  void start_cohesive(Contact& c) const;
  /// The open-close hysteresis band, m: state_tolerance × the allowed step displacement.
  double state_band() const { return options_.state_tolerance * allowed_; }
  void block_terms(double dt);
  /// The step's matrix and load vector; `whole` = false re-gathers only what the contacts whose
  /// coefficients changed since the previous assembly of the step touch.
  void assemble(bool whole);
  bool judge(int& changed_first);
  /// How the open-close iteration of one trial step ended.
  struct OpenClose {
    bool converged = false;  // no contact changed state
    bool solver_ok = true;   // every solve converged
    int iterations = 0;      // solves made
    int worst_contact = -1;  // first contact that still changed state
  };
  /// Assemble, solve and judge until no contact changes state (at most analysis.open_close_max).
  OpenClose iterate_open_close(StepReport& rep);
  /// The largest vertex displacement of the step's solution, m, and the block it belongs to.
  double largest_step_displacement(Index& worst) const;
  /// Statistics, contact counts and the energy ledger of an accepted step; `linearised_end` is
  /// what accept() returned.
  void record_step(StepReport& rep, const Energies& linearised_end);
  void reset_trials();
  /// The block terms of the step's energy, and what the blocks and their anchors store at the
  /// end of the linearised step, on the geometry it started from (one pass over the blocks).
  struct BlockStepEnergy {
    StepEnergy step;
    Energies linearised_end;  // strain, kinetic and support only
    BlockStepEnergy& operator+=(const BlockStepEnergy& o) {
      step += o.step;
      linearised_end += o.linearised_end;
      return *this;
    }
  };
  BlockStepEnergy block_step_energy(double dt) const;
  /// ½·Vᵀ·M·V and ½·A·σᵀ·C·σ of block i on its current geometry, J/m.
  double block_kinetic_energy(Index i) const;
  double block_strain_energy(Index i) const;
  /// Stretch of anchor p's spring with its material point at (x, y) and its target at time t, m.
  static Eigen::Vector2d anchor_stretch(const Anchor& p, double x, double y, double t);
  /// Books the step's energy, commits the contacts and moves the blocks. Returns the strain,
  /// kinetic and support energies at the end of the linearised step, on the geometry the step
  /// started from (record_step books their difference from the moved geometry's as residual).
  Energies accept(double dt);
  std::size_t fracture_check();
  /// After the fracture check raised the damage of softening joints: their contacts' springs,
  /// forces and stored energies follow at the step's end state. Returns what the springs gave up
  /// (J/m), the energy the softening dissipated.
  double follow_joint_damage();
  [[noreturn]] void trouble(const std::string& what) const;
  std::string describe_block(Index b) const;
  std::string describe_contact(Index c) const;

  scene::Scene scene_;
  EngineOptions options_;
  BlockSystem blocks_;
  ContactSet set_;
  std::vector<Contact> spare_contacts_;  // the previous step's list, refilled by the next detection
  DetectionWorkspace detection_;
  BlockMatrix matrix_;
  std::vector<ContactLinearisation> linear_;  // per contact of set_, from this step's detection
  std::vector<ContactCoefficients> coefficients_;  // per contact, of the latest assembly
  std::vector<std::uint8_t> coefficient_changed_;  // per contact, since the assembly before
  BlockVector base_rhs_, rhs_, d_;
  std::vector<Mat6> base_diag_;
  std::vector<double> saved_slide_sign_;
  SolverWorkspace solver_work_;
  Statistics stats_;
  ActiveTerms active_;
  double time_ = 0.0;
  double dt_ = 0.0;
  double dt_prev_ = 0.0;
  double allowed_ = 0.0;
  double anchor_penalty_ = 0.0;
  long step_ = 0;
  EnergyLedger ledger_;
  std::vector<CrackEvent> cracks_;
  CrackCounts crack_counts_;
  std::vector<Index> gauge_blocks_;
  // The blocks the fracture criterion averages per joint (analysis.fracture_stress_radius > 0),
  // from the geometry at t = 0; empty otherwise.
  StressNeighbourhoods stress_neighbourhoods_;
};

}  // namespace ddafrac::dda
