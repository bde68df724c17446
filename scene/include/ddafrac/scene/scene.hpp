#pragma once
// A scene: everything one run needs, parsed from one TOML file and validated. SI units
// throughout; angles in radians here (the file gives degrees).

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "ddafrac/common/plane_model.hpp"
#include "ddafrac/meshes/geometry.hpp"
#include "ddafrac/scene/defaults.hpp"

namespace ddafrac::scene {

using Vec2 = std::array<double, 2>;

struct Material {
  std::string name;
  double density = 0.0;  // kg/m^3
  double young = 0.0;    // Pa
  double poisson = 0.0;  // -, in [0, 0.5)
};

/// How a softening joint loaded in tension and shear at once combines the two modes
/// (docs/design.md §5): each mode judged on its own and the larger damage kept, or one drive,
/// the quadratic sum of the two failure ratios, softening on a mix of the two modes' ductilities.
enum class ModeInteraction { None, Quadratic };
/// Its name in a scene file (joints.<set>.mode_interaction).
const char* to_string(ModeInteraction interaction);

/// Strength and stiffness of a family of joints (virtual joints of a body, or real joints).
struct JointSet {
  std::string name;
  double friction_angle = 0.0;    // rad
  double cohesion = 0.0;          // Pa
  double tensile_strength = 0.0;  // Pa
  double normal_stiffness = 0.0;  // N/m per unit thickness (penalty kn)
  double shear_stiffness = 0.0;   // N/m per unit thickness (penalty ks)
  // G_f, J/m² (N/m): the energy a virtual joint of this set dissipates per unit length as it
  // breaks. 0: brittle (a joint breaks in the step its load first exceeds its strength). Above:
  // past its strength the joint softens linearly with further opening and breaks once it has
  // dissipated G_f·l (docs/design.md §5).
  double fracture_energy = 0.0;
  // G_IIf, J/m² (N/m): the energy a virtual joint dissipates per unit length as it breaks in
  // shear, on a softening law of its own (docs/design.md §5). Absent: shear softens with the
  // tension's ductility μ (one fracture energy for both modes). 0: brittle in shear.
  std::optional<double> shear_fracture_energy = std::nullopt;
  // How a softening joint combines tension and shear (ModeInteraction). None: the larger of the
  // two modes' damages, so a joint loaded in both dissipates up to the sum of both modes'
  // energies. Quadratic: onset where r1² + r2² = 1, and G_I/G_f + G_II/G_IIf = 1 at the break
  // under proportional loading.
  ModeInteraction mode_interaction = ModeInteraction::None;

  /// A joint of this set softens past its strength in one mode or both.
  bool softens() const { return fracture_energy > 0.0 || shear_fracture_energy.value_or(0.0) > 0.0; }
};

enum class Role { Disc, Platen, Plate };
enum class Motion { Free, Fixed, Prescribed };

struct Body {
  std::string name;  // a body (physical surface group) of the geometry
  Role role = Role::Disc;
  Motion motion = Motion::Free;
  std::size_t material = 0;                   // index into Scene::materials
  std::optional<std::size_t> virtual_joints;  // index into Scene::joint_sets; none = not meshed into breakable blocks
  Vec2 initial_velocity{0.0, 0.0};            // m/s
  Vec2 prescribed_velocity{0.0, 0.0};         // m/s, for Motion::Prescribed
};

using common::PlaneModel;
enum class Mode { Dynamic, Static };
enum class Solver { Pcg, Direct };  // block-Jacobi PCG, or a sparse direct factorisation
/// How the copies of a mesh node are held in two blocks of one body that meet only at that node
/// (not along a virtual joint): by a unilateral frictionless contact, or, while intact virtual
/// joints at the node connect the two blocks around it, tied by a bilateral isotropic spring
/// (docs/design.md §4.6).
enum class IntactNodes { Contact, Tie };
/// What the fracture check judges an intact virtual joint on: the forces of its own springs, or
/// the load the mean stress of its two blocks puts on it (docs/design.md §5).
enum class FractureLoad { JointSprings, BlockStress };
/// Their names in a scene file (analysis.intact_nodes, analysis.fracture_load).
const char* to_string(IntactNodes nodes);
const char* to_string(FractureLoad load);

struct Analysis {
  Mode mode = Mode::Dynamic;
  PlaneModel plane = PlaneModel::Stress;
  double dt_max = 0.0;                  // s
  double max_displacement_ratio = 0.0;  // allowed step displacement / half model height
  double penalty = 0.0;                 // contact stiffness kn, N/m (and joint sets' default kn)
  double end_time = 0.0;                // s
  double output_interval = 0.0;         // s between snapshots / gauge samples
  Vec2 gravity{0.0, 0.0};               // m/s^2
  int open_close_max = 6;               // open-close iterations before dt is cut
  Solver solver = Solver::Pcg;
  double solver_tolerance = kDefaultSolverTolerance;  // PCG's relative residual |b - K·x| / |b| at which it stops
  double search_distance_factor = kDefaultSearchDistanceFactor;  // contact search distance / allowed step displacement
  double pair_list_skin_factor = kDefaultPairListSkinFactor;     // skin of the contact pair list / search distance
  // η of the mass-proportional damping force −η·M·v on every block, 1/s (0: none; dynamic mode
  // only). It damps the slow modes most (damping ratio η/(2ω) of a mode of angular frequency ω),
  // such as a platen ringing on a disc, and drags a block moving as a whole by η·m·v.
  double mass_damping = 0.0;
  IntactNodes intact_nodes = IntactNodes::Contact;
  FractureLoad fracture_load = FractureLoad::JointSprings;
  // With FractureLoad::BlockStress, m: 0 judges a joint on the mean stress of its two blocks;
  // above, on the area-weighted mean stress of its body's blocks whose centroids lie within this
  // radius of the joint's midpoint at t = 0 (its two blocks always among them). A material length
  // that does not shrink with the blocks, as a strength criterion at a crack tip needs to give the
  // same crack on every mesh (docs/design.md §5).
  double fracture_stress_radius = 0.0;
};

struct Gauge {
  std::string name;
  Vec2 position{0.0, 0.0};  // m
};

struct Output {
  bool vtk = true;
  bool figures = true;
  double crack_interval = 150e-6;    // s, bin width of incremental crack counts
  std::vector<double> figure_times;  // s, crack-pattern pictures
};

/// Pass/fail tolerances of `ddafrac verify`, relative errors (dimensionless).
/// A key left out is not checked; `ddafrac verify` says which keys its comparison needs.
struct Verification {
  std::optional<double> load;           // N/m, diametral load of a static comparison
  std::optional<double> centre_stress;  // |σ − σ_ref| / |σ_ref| of centre σxx and σyy
  std::optional<double> field_l2;       // relative L2 of (σxx, σyy, τxy) at block centroids
  std::optional<double> arrival_time;   // |t − t_ref| / t_ref of the P-wave arrival at a gauge
  std::optional<double> gauge_rms;      // RMS(σ − σ_ref) / |peak σ_ref| of a gauge history
};

struct Scene {
  std::string name;
  std::string description;
  std::filesystem::path source;  // the TOML file it came from ("" if built in)
  /// The whole scene as read: its `base` chain merged and --set applied, printed as TOML. A
  /// run's checkpoint keeps it, and a resume refuses a scene whose files changed since.
  std::string resolved_text;
  /// resolved_text without the name and description: scenes that differ only in those run
  /// alike (a study runs such a repeat once).
  std::string unnamed_text;
  std::vector<Material> materials;
  std::vector<JointSet> joint_sets;
  meshes::Geometry geometry;
  meshes::MeshControl mesh;
  std::vector<Body> bodies;
  std::size_t real_joints = 0;  // joint set of contacts between bodies, slit faces and broken joints
  Analysis analysis;
  std::vector<Gauge> gauges;
  Output output;
  std::optional<Verification> verification;  // [verification]; absent = not a verification case

  const Body* find_body(const std::string& name) const;
};

}  // namespace ddafrac::scene
