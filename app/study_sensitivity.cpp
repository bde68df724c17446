// `ddafrac study sensitivity [--family mesh,penalty,...] [--blocks N] [study options]`: how far the
// fracture results can be trusted. Runs case 4 and the flattened disc at varied mesh, joint
// stiffness, time step, loading rate and mass damping, and both again with their impact or platen
// speed changed by a few millionths (the scatter of one run), each variant a scene written into DIR/scenes/ (a base
// scene of scenes/ and the values the variant changes, so any run can be repeated alone), then
// writes study.md, study.csv and, through the plotting script, the families' figures and
// analysis.md (convergence orders, indirect tensile strength, verdicts).

#include <fmt/core.h>
#include <fmt/ranges.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <sstream>
#include <string>

#include "commands.hpp"
#include "ddafrac/common/whole_file.hpp"
#include "ddafrac/dda/contact_period.hpp"
#include "ddafrac/dda/engine.hpp"
#include "ddafrac/scene/parse.hpp"
#include "option_checks.hpp"
#include "scene_source.hpp"
#include "study_runs.hpp"
#include "study_source_report.hpp"

namespace ddafrac::app {

namespace {

namespace fs = std::filesystem;

// The base scenes (under scenes/) and what each family varies.
constexpr const char* kImpactCase = "impact/case04.toml";
constexpr const char* kThetaCases[] = {"impact/case01.toml", "impact/case02.toml", "impact/case03.toml",
                                       "impact/case04.toml", "impact/case05.toml", "impact/case06.toml",
                                       "impact/case07.toml"};
constexpr const char* kFlattenedDiscs[] = {"brazilian/flattened_2045.toml", "brazilian/flattened_4107.toml",
                                           "brazilian/flattened_6081.toml"};
/// Case 4's mesh sizes, as fractions of the reference size (--blocks): each doubles the blocks.
constexpr double kMeshFractions[] = {0.25, 0.5, 1.0, 2.0};
/// Contact and joint normal stiffness (analysis.penalty) as multiples of the rock's Young's
/// modulus (×1 m, per unit thickness); the study's own kn (the scene's) is the family's first member.
constexpr double kStiffnessMultiples[] = {1.0, 10.0, 100.0};
/// The θ series once more with a disc as stiff as its rock; the family also runs the series at the
/// scene's kn on the same meshes, so that the two trends are compared at one block count.
constexpr double kThetaStiffnessMultiple = 10.0;
/// The time steps of the time-step family besides the scene's own dt_max (s): with it, three
/// steps that halve, enough for an observed order.
constexpr double kTimeSteps[] = {5e-8, 2.5e-8};
/// Element sizes at the slot's ends (mesh.slot_end_size, slot widths) of the slot-tips family
/// besides the scene's own (1): the tips refined twice by halving at the same block count.
constexpr double kSlotEndSizes[] = {0.5, 0.25};
/// Platen speeds of the loading-rate family (m/s), and the static run at the scene's speed.
constexpr double kPlatenSpeeds[] = {1.0, 0.5, 0.25, 0.125};
/// Static mode keeps the inertia term 2M/Δt² (docs/design.md §3): at the scene's dt_max it is
/// ~300× a disc block's stiffness and the platen barely moves. The static run takes steps this
/// many times longer, with the platen as far per step as in the scene (its speed divided alike),
/// so that the term is ~10⁻⁵ of the stiffness and each step is near equilibrium.
constexpr double kStaticTimeStretch = 1e4;
/// Mass damping η of the damping family (analysis.mass_damping, 1/s), on the flattened disc at the
/// scene's platen speed: about 0.1, 0.2 and 0.5 of critical (η/(2ω)) for the platen force's ringing,
/// 3.9 kHz on the 2045-block disc at 0.25 m/s. It also drags the disc, which moves down at about half
/// the platen's speed, by η·m·v/2. The family runs the disc undamped and in static mode (the rate
/// family's runs) beside them.
constexpr double kMassDampings[] = {5e3, 1e4, 2.5e4};
/// How the node-model family holds the copies of an intact body's mesh nodes and what its
/// fracture check judges (analysis.intact_nodes, analysis.fracture_load; docs/design.md §4.6, §5):
/// the scenes' own model first, then the criterion on the blocks' stress alone, then with ties.
struct NodeModel {
  const char* suffix;  // of the variant's name ("": the scene as it is)
  scene::IntactNodes intact_nodes;
  scene::FractureLoad fracture_load;
};
/// Relative changes of case 4's impact speed and of the flattened disc's platen speed in the
/// spread family, besides the scene's own: far below anything a measurement could tell apart or
/// the physics responds to (the v0 series moves the speed by 14–70%, the rate family the platen's
/// by factors of 2), so that what moves between the runs is how one run's choices fall (which
/// state a contact inside the open–close band settles in, which joint breaks first in a step) —
/// the scatter of a single run's crack results and peak force.
constexpr double kSpeedPerturbations[] = {1e-6, 2e-6, 4e-6, 8e-6};
constexpr NodeModel kNodeModels[] = {{"", scene::IntactNodes::Contact, scene::FractureLoad::JointSprings},
                                     {"-stress", scene::IntactNodes::Contact, scene::FractureLoad::BlockStress},
                                     {"-ties", scene::IntactNodes::Tie, scene::FractureLoad::BlockStress}};
constexpr const char* kPlaten = "top_platen";  // the prescribed body of the Brazilian scenes
constexpr const char* kFamilies[] = {"mesh", "penalty", "penalty-theta", "timestep", "slot-tips",
                                     "rate", "damping", "node-model",    "spread"};
// The names under which study.json records --family and --blocks (StudyKind::options).
constexpr const char* kFamilyOption = "family";
constexpr const char* kBlocksOption = "blocks";

struct SensitivityArguments : StudyArguments {
  std::vector<std::string> families;  // empty: all
  int blocks = 0;                     // case 4's reference size; 0: its scene's
};

/// One run of the study: a base scene and the values it changes (TOML tables), in families.
struct Variant {
  std::string name;
  fs::path base;
  std::vector<std::string> families;
  std::map<std::string, std::map<std::string, std::string>> tables;  // table -> key -> TOML value
};

scene::Scene load(const fs::path& file) {
  try {
    return scene::load_scene(file, {});
  } catch (const scene::SceneError& e) {
    throw CommandFailed(e.what());
  }
}

/// The speed of the scene's top platen (m/s); CommandFailed if it has none.
double platen_speed(const scene::Scene& s, const fs::path& file) {
  const scene::Body* platen = s.find_body(kPlaten);
  if (platen == nullptr) throw CommandFailed(file.string() + ": no body " + kPlaten);
  return std::abs(platen->prescribed_velocity[1]);
}

/// The scene's body named disc (the slotted and flattened discs' rock); CommandFailed if it has none.
const scene::Body& disc_body(const scene::Scene& s, const fs::path& file) {
  const scene::Body* disc = s.find_body("disc");
  if (disc == nullptr) throw CommandFailed(file.string() + ": no body named disc");
  return *disc;
}

std::string number(double v) { return fmt::format("{:.6g}", v); }

/// The largest of 1, 2 or 5 × 10^k not above `x`: a step a reader can recognise.
double round_down_to_1_2_5(double x) {
  const double decade = std::pow(10.0, std::floor(std::log10(x)));
  for (const double m : {5.0, 2.0, 1.0})
    if (m * decade <= x) return m * decade;
  return decade;
}

/// The scene file's stem without the size some carry ("flattened_2045" -> "flattened"): the
/// variants carry their own.
std::string family_stem(const fs::path& scene) {
  const std::string stem = scene.stem().string();
  const auto cut = stem.find_last_of('_');
  const bool sized = cut != std::string::npos && cut + 1 < stem.size() &&
                     stem.find_first_not_of("0123456789", cut + 1) == std::string::npos;
  return sized ? stem.substr(0, cut) : stem;
}

/// The variant's scene file: its base and the changed values, nothing else.
std::string variant_text(const Variant& v) {
  std::string text = fmt::format(
      "# Written by `ddafrac study sensitivity` (families: {}): {} with the values below.\n"
      "# Rewritten when the study runs; to change a family, change the study.\n",
      fmt::join(v.families, ", "), v.base.filename().string());
  text += fmt::format("base = \"{}\"\nname = \"{}\"\n", v.base.string(), v.name);
  for (const auto& [table, values] : v.tables) {
    text += fmt::format("\n[{}]\n", table);
    for (const auto& [key, value] : values) text += fmt::format("{} = {}\n", key, value);
  }
  return text;
}

class VariantBuilder {
 public:
  VariantBuilder(const fs::path& scenes, int reference_blocks, fs::path out) : scenes_(scenes), out_(std::move(out)) {
    const int case_blocks = load(scenes_ / kImpactCase).mesh.target_blocks;
    scale_ = reference_blocks > 0 ? static_cast<double>(reference_blocks) / case_blocks : 1.0;
  }

  /// A scene of scenes/ at its size scaled like case 4's (--blocks), named after it.
  Variant at_scale(const char* scene, double fraction = 1.0) const {
    Variant v;
    v.base = scenes_ / scene;
    const long blocks = std::lround(load(v.base).mesh.target_blocks * scale_ * fraction);
    v.name = fmt::format("{}-{}", family_stem(v.base), blocks);
    v.tables["mesh"]["blocks"] = std::to_string(blocks);
    return v;
  }

  /// Every contact and joint at kn = `multiple` × the disc's Young's modulus (analysis.penalty,
  /// which the scene's joint sets take), with a dt_max that resolves the contact period
  /// (resolving_contact_period). The virtual joints alone would not do: a joint
  /// that breaks becomes a contact of the real joints' kn, and a disc stressed through joints of
  /// kn = E then presses its broken faces ~0.8 mm into each other through springs 30× softer
  /// (measured: the energy balance off by 2400% at 400 µs).
  Variant with_stiffness(Variant v, double multiple) const {
    const scene::Scene base = load(v.base);
    const scene::Body& disc = disc_body(base, v.base);
    for (const scene::JointSet& joints : base.joint_sets)
      if (joints.normal_stiffness != base.analysis.penalty)
        throw CommandFailed(fmt::format(
            "{}: joint set {} has a normal_stiffness of its own; the penalty family sets analysis.penalty, which "
            "it would not take",
            v.base.string(), joints.name));
    const double kn = multiple * base.materials[disc.material].young;  // N/m per unit thickness (×1 m)
    v.name += fmt::format("-kn{:g}E", multiple);
    v.tables["analysis"]["penalty"] = number(kn);
    return resolving_contact_period(std::move(v));
  }

  /// The slot's ends meshed at `size` slot widths (mesh.slot_end_size), with a dt_max that
  /// resolves the contact period of the smaller blocks there (as for the stiffer joints).
  Variant with_slot_end_size(Variant v, double size) const {
    v.name += fmt::format("-tip{:g}", size);
    v.tables["mesh"]["slot_end_size"] = number(size);
    return resolving_contact_period(std::move(v));
  }

  /// The variant with the longest dt_max (1, 2 or 5 × 10^k, at most the scene's) that gives the
  /// stiffest spring on the lightest block the steps per period the run asks for (run's
  /// warning, docs/design.md §7); unchanged if the scene's dt_max already does.
  Variant resolving_contact_period(Variant v) const {
    const scene::Scene s = load(write(v));
    const meshes::Mesh mesh = dda_mesh(s);
    const dda::Engine engine(s, mesh);
    const dda::ContactPeriod shortest = dda::shortest_contact_period(engine, s.analysis.dt_max);
    if (shortest.unresolved_blocks > 0)
      v.tables["analysis"]["dt_max"] = number(round_down_to_1_2_5(shortest.period / dda::kMinStepsPerContactPeriod));
    return v;
  }

  Variant with_time_step(Variant v, double dt) const {
    v.name += fmt::format("-dt{:g}", dt);
    v.tables["analysis"]["dt_max"] = number(dt);
    return v;
  }

  /// The top platen at `speed` (m/s) over the same travel as the scene's, with its times
  /// (end, outputs, crack intervals, figures) stretched alike.
  Variant with_platen_speed(Variant v, double speed) const {
    const scene::Scene base = load(v.base);
    const double stretch = platen_speed(base, v.base) / speed;
    if (stretch == 1.0) return v;  // the scene as it is
    v.name += fmt::format("-v{:g}", speed);
    return stretched(std::move(v), base, speed, stretch);
  }

  /// A damping force −η·M·v on every block (analysis.mass_damping, 1/s).
  Variant with_mass_damping(Variant v, double eta) const {
    v.name += fmt::format("-eta{:g}", eta);
    v.tables["analysis"]["mass_damping"] = number(eta);
    return v;
  }

  /// The copies of intact fans' nodes and the fracture criterion of `model`.
  Variant with_node_model(Variant v, const NodeModel& model) const {
    if (*model.suffix == '\0') return v;
    v.name += model.suffix;
    v.tables["analysis"]["intact_nodes"] = fmt::format("\"{}\"", scene::to_string(model.intact_nodes));
    v.tables["analysis"]["fracture_load"] = fmt::format("\"{}\"", scene::to_string(model.fracture_load));
    return v;
  }

  /// The disc's impact speed × (1 + `change`), in the same direction.
  Variant with_impact_speed_changed(Variant v, double change) const {
    const scene::Scene base = load(v.base);
    const scene::Body& disc = disc_body(base, v.base);
    const double scale = 1.0 + change;
    v.name += fmt::format("-dv{:g}", change);
    // All the digits: the change is in the sixth.
    v.tables["bodies.disc"]["velocity"] =
        fmt::format("[{:.17g}, {:.17g}]", disc.initial_velocity[0] * scale, disc.initial_velocity[1] * scale);
    return v;
  }

  /// The top platen's speed × (1 + `change`), over the scene's times: the travel changes by the
  /// same fraction, far below one output interval's.
  Variant with_platen_speed_changed(Variant v, double change) const {
    const scene::Scene base = load(v.base);
    v.name += fmt::format("-dv{:g}", change);
    // All the digits: the change is in the sixth.
    v.tables["bodies." + std::string(kPlaten)]["prescribed_velocity"] =
        fmt::format("[0.0, {:.17g}]", -platen_speed(base, v.base) * (1.0 + change));
    return v;
  }

  /// Static mode, the platen moving as far per step as in the scene over the same travel
  /// (kStaticTimeStretch).
  Variant in_static_mode(Variant v) const {
    const scene::Scene base = load(v.base);
    v.name += "-static";
    v.tables["analysis"]["mode"] = "\"static\"";
    v.tables["analysis"]["dt_max"] = number(base.analysis.dt_max * kStaticTimeStretch);
    return stretched(std::move(v), base, platen_speed(base, v.base) / kStaticTimeStretch, kStaticTimeStretch);
  }

 private:
  /// The platen at `speed`, the scene's times × `stretch`.
  Variant stretched(Variant v, const scene::Scene& base, double speed, double stretch) const {
    v.tables["bodies." + std::string(kPlaten)]["prescribed_velocity"] = fmt::format("[0.0, {}]", number(-speed));
    v.tables["analysis"]["end_time"] = number(base.analysis.end_time * stretch);
    v.tables["analysis"]["output_interval"] = number(base.analysis.output_interval * stretch);
    std::vector<std::string> times;
    for (const double t : base.output.figure_times) times.push_back(number(t * stretch));
    v.tables["output"]["crack_interval"] = number(base.output.crack_interval * stretch);
    if (!times.empty()) v.tables["output"]["figure_times"] = fmt::format("[{}]", fmt::join(times, ", "));
    return v;
  }

 public:
  /// Writes the variant's scene file (only if its text changed) and returns its path.
  fs::path write(const Variant& v) const {
    const fs::path file = out_ / "scenes" / (v.name + ".toml");
    const std::string text = variant_text(v);
    if (file_text(file) != text) {
      fs::create_directories(file.parent_path());
      common::write_whole_text(file, text);
    }
    return file;
  }

 private:
  fs::path scenes_, out_;
  double scale_ = 1.0;
};

/// Every family's variants; a run two families share (case 4 as specified is in the mesh,
/// penalty and time-step families) appears once, in both.
std::vector<Variant> variants(const SensitivityArguments& args, const fs::path& out) {
  const VariantBuilder build(fs::path(DDAFRAC_SOURCE_DIR) / "scenes", args.blocks, out);
  const auto wanted = [&](const std::string& family) {
    return args.families.empty() ||
           std::find(args.families.begin(), args.families.end(), family) != args.families.end();
  };
  std::vector<Variant> all;
  const auto add = [&](Variant v, const std::string& family) {
    const auto same = std::find_if(all.begin(), all.end(), [&](const Variant& o) { return o.name == v.name; });
    if (same != all.end()) {
      same->families.push_back(family);
      return;
    }
    v.families = {family};
    all.push_back(std::move(v));
  };
  if (wanted("mesh")) {
    for (const double f : kMeshFractions) add(build.at_scale(kImpactCase, f), "mesh");
    for (const char* disc : kFlattenedDiscs) add(build.at_scale(disc), "mesh");
  }
  if (wanted("penalty")) {
    add(build.at_scale(kImpactCase), "penalty");
    for (const double m : kStiffnessMultiples) add(build.with_stiffness(build.at_scale(kImpactCase), m), "penalty");
  }
  if (wanted("penalty-theta"))
    for (const char* c : kThetaCases) {
      add(build.at_scale(c), "penalty-theta");
      add(build.with_stiffness(build.at_scale(c), kThetaStiffnessMultiple), "penalty-theta");
    }
  if (wanted("timestep")) {
    add(build.at_scale(kImpactCase), "timestep");
    for (const double dt : kTimeSteps) add(build.with_time_step(build.at_scale(kImpactCase), dt), "timestep");
  }
  if (wanted("slot-tips")) {
    add(build.at_scale(kImpactCase), "slot-tips");
    for (const double size : kSlotEndSizes)
      add(build.with_slot_end_size(build.at_scale(kImpactCase), size), "slot-tips");
  }
  if (wanted("rate")) {
    for (const double v : kPlatenSpeeds) add(build.with_platen_speed(build.at_scale(kFlattenedDiscs[0]), v), "rate");
    add(build.in_static_mode(build.at_scale(kFlattenedDiscs[0])), "rate");
  }
  if (wanted("damping")) {
    add(build.at_scale(kFlattenedDiscs[0]), "damping");
    for (const double eta : kMassDampings)
      add(build.with_mass_damping(build.at_scale(kFlattenedDiscs[0]), eta), "damping");
    add(build.in_static_mode(build.at_scale(kFlattenedDiscs[0])), "damping");
  }
  if (wanted("node-model"))
    for (const NodeModel& model : kNodeModels) {
      add(build.with_node_model(build.at_scale(kImpactCase), model), "node-model");
      add(build.with_node_model(build.at_scale(kFlattenedDiscs[0]), model), "node-model");
      add(build.with_node_model(build.in_static_mode(build.at_scale(kFlattenedDiscs[0])), model), "node-model");
    }
  if (wanted("spread")) {
    add(build.at_scale(kImpactCase), "spread");
    for (const double change : kSpeedPerturbations)
      add(build.with_impact_speed_changed(build.at_scale(kImpactCase), change), "spread");
    add(build.at_scale(kFlattenedDiscs[0]), "spread");
    for (const double change : kSpeedPerturbations)
      add(build.with_platen_speed_changed(build.at_scale(kFlattenedDiscs[0]), change), "spread");
  }
  for (const Variant& v : all) build.write(v);
  return all;
}

std::vector<StudyCase> load_study(const SensitivityArguments& args, const std::vector<std::string>& overrides,
                                  const fs::path& out) {
  for (const std::string& o : overrides)
    if (o.rfind("mesh.blocks", 0) == 0)
      throw CommandFailed(
          "study sensitivity: --set mesh.blocks would give every mesh one size; use --blocks N (case "
          "4's reference size, the others scale with it)");
  const std::vector<Variant> all = variants(args, out);
  std::vector<fs::path> files;
  for (const Variant& v : all) files.push_back(out / "scenes" / (v.name + ".toml"));
  std::vector<CaseRun> runs = load_case_runs(files, overrides, out, "the study's cases");
  std::vector<StudyCase> cases;
  for (std::size_t k = 0; k < runs.size(); ++k)
    cases.push_back({fmt::format("{}", fmt::join(all[k].families, "+")), std::move(runs[k]), {}});
  return cases;
}

/// --family and --blocks as the study in `out` recorded them (StudyKind::options): a --status,
/// --report or --resume without them is about the same cases as the run that started it.
void restore_options(SensitivityArguments& args, const std::map<std::string, std::string>& stored,
                     const fs::path& out) {
  const auto bad = [&out](const char* key, const std::string& value, const std::string& expected) {
    return CommandFailed(fmt::format("{}: options.{} is '{}', expected {}; was the file edited?",
                                     study_file(out).string(), key, value, expected));
  };
  if (const auto it = stored.find(kFamilyOption); it != stored.end()) {
    std::stringstream list(it->second);
    for (std::string family; std::getline(list, family, ',');) {
      if (std::find(std::begin(kFamilies), std::end(kFamilies), family) == std::end(kFamilies))
        throw bad(kFamilyOption, it->second, fmt::format("families among {}", fmt::join(kFamilies, ", ")));
      args.families.push_back(family);
    }
  }
  if (const auto it = stored.find(kBlocksOption); it != stored.end()) {
    std::size_t used = 0;
    try {
      args.blocks = std::stoi(it->second, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != it->second.size() || args.blocks < 0)
      throw bad(kBlocksOption, it->second, "a whole number of blocks (0: the scenes' own size)");
  }
}

std::string study_markdown(const std::vector<StudyCase>& cases, const SensitivityArguments& args,
                           const std::vector<std::string>& overrides, const std::vector<std::string>& figures) {
  std::string md = "# How far the fracture results can be trusted: the sensitivity study\n\n";
  md += fmt::format(
      "Written by `ddafrac study sensitivity`{}{}. Each case's scene is in `scenes/` (its base scene and the values "
      "it changes); a case in several families is run once. The analysis (convergence orders, indirect tensile "
      "strength, verdicts) is in [analysis.md](analysis.md), written with the figures.\n\n",
      args.blocks > 0 ? fmt::format(" with case 4 at --blocks {}", args.blocks) : std::string(" at full size"),
      overrides.empty() ? std::string() : fmt::format(" and `--set {}`", fmt::join(overrides, " --set ")));
  md += case_table(cases);
  if (!figures.empty()) {
    md += "\n## Figures\n\n";
    for (const std::string& f : figures) md += fmt::format("![{}]({})\n\n", f, f);
  }
  return md;
}

}  // namespace

void register_study_sensitivity(CLI::App& study) {
  auto args = std::make_shared<SensitivityArguments>();
  CLI::App* command = study.add_subcommand(
      "sensitivity",
      "how crack results move with the mesh, the joints' stiffness, the time step, the slot tips' mesh, the "
      "loading rate and damping of the platen's ringing, and how far they scatter under changes of a few millionths "
      "(case 4 and the flattened disc), as one resumable command");
  command->add_option("--family", args->families, "only these families (comma-separated; default: all)")
      ->delimiter(',')
      ->check(CLI::IsMember(std::vector<std::string>(std::begin(kFamilies), std::end(kFamilies))));
  command
      ->add_option("--blocks", args->blocks,
                   "case 4's reference size (default: its scene's, 5550); every mesh of the study scales with it, "
                   "e.g. --blocks 2800 for a half-size study")
      ->check(whole_number(1));
  add_study_options(
      *command, *args, "study-sensitivity",
      "override a value of every case, e.g. --set analysis.end_time=6e-4 (not mesh.blocks: use --blocks)", [args] {
        const fs::path out(args->out);
        if ((args->status || args->report || args->resume) && args->families.empty() && args->blocks == 0)
          restore_options(*args, stored_study_options(out), out);
        StudyKind kind;
        kind.command = "study sensitivity";
        kind.figures_command = "study-sensitivity";
        kind.load = [args, out](const std::vector<std::string>& overrides) {
          return load_study(*args, overrides, out);
        };
        kind.markdown = [args](const std::vector<StudyCase>& cases, const std::vector<std::string>& overrides,
                               const std::vector<std::string>& figures) {
          return study_markdown(cases, *args, overrides, figures);
        };
        kind.options = {{kFamilyOption, fmt::format("{}", fmt::join(args->families, ","))},
                        {kBlocksOption, std::to_string(args->blocks)}};
        return kind;
      });
}

}  // namespace ddafrac::app
