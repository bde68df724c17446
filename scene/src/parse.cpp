// The scene schema: which tables and keys a scene file has, their types, ranges and units,
// and the checks that relate one key to another.

#include "ddafrac/scene/parse.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "ddafrac/common/angles.hpp"
#include "ddafrac/scene/defaults.hpp"
#include "document.hpp"
#include "toml_reader.hpp"

namespace ddafrac::scene {

namespace {

/// The scene's top-level keys that name and describe it and change nothing a run computes.
constexpr const char* kNameKey = "name";
constexpr const char* kDescriptionKey = "description";

std::string toml_text_of(const toml::table& document) {
  std::ostringstream text;
  text << document;
  return std::move(text).str();
}

using detail::Diagnostics;
using detail::Need;
using detail::NumberRule;
using detail::TableReader;

constexpr double kDegree = common::kRadiansPerDegree;

/// Default rim arc (half-angle) over which the FEM holds the impact patch, degrees.
constexpr double kDefaultPatchHalfAngleDeg = 5.0;
/// Most output intervals a run may have: each writes a VTU snapshot, and more than this fills
/// a disk before it tells anything a coarser interval would not.
constexpr double kMaxOutputIntervals = 10'000;
/// Most crack-count intervals: crack_intervals.csv holds one row per interval.
constexpr double kMaxCrackIntervals = 100'000;
/// Most blocks a generated mesh may target: gmsh meshes 10 million for minutes before the
/// engine's memory (about 10 kB per block) is even asked for.
constexpr long long kMaxTargetBlocks = 2'000'000;
/// Relative tolerance on the DDA block count when [mesh] gives none.
constexpr double kDefaultBlockTolerance = 0.02;
// mesh.slot_end_size, in slot widths: finer than a twentieth of the width, the tip blocks would
// need a time step far below any scene's to resolve their contact period; coarser than ten
// widths, the ends are no longer graded at all at the study's sizes (≤ 3 mm far field, 0.4 mm slots).
constexpr double kSmallestSlotEndSize = 0.05;
constexpr double kLargestSlotEndSize = 10.0;

const std::vector<std::string> kGenerators{"plain_disc", "flattened_disc", "slit_disc", "impact_disc"};

struct ParsedGeometry {
  meshes::Geometry geometry;
  std::vector<std::string> bodies;  // the bodies this geometry makes, empty for a user .msh
  double diameter = 0.0;            // 0 for a user .msh
  bool slotted = false;             // has slots or slits (mesh.slot_end_size applies)
};

std::vector<std::string> names_of(const std::vector<Material>& v) {
  std::vector<std::string> out;
  for (const auto& m : v) out.push_back(m.name);
  return out;
}

std::vector<std::string> names_of(const std::vector<JointSet>& v) {
  std::vector<std::string> out;
  for (const auto& j : v) out.push_back(j.name);
  return out;
}

/// Refuses an interval that cuts end_time into more than `most` pieces, saying the smallest one.
void check_interval_count(TableReader& t, std::string_view key, double interval, double end_time, double most) {
  if (!(interval > 0 && end_time > 0) || end_time / interval <= most) return;
  t.problem(key,
            fmt::format("makes {:.3g} intervals of analysis.end_time ({:g} s), more than {:g}: use at least {:.3g} s",
                        end_time / interval, end_time, most, end_time / most));
}

Analysis parse_analysis(TableReader t) {
  Analysis a;
  if (auto mode = t.choice("mode", {"dynamic", "static"}, Need::Required))
    a.mode = *mode == "static" ? Mode::Static : Mode::Dynamic;
  if (auto plane = t.choice("plane", {"stress", "strain"}, Need::Required))
    a.plane = *plane == "strain" ? PlaneModel::Strain : PlaneModel::Stress;
  a.dt_max = t.number("dt_max", NumberRule::positive("s"), Need::Required).value_or(0.0);
  a.max_displacement_ratio =
      t.number("max_displacement_ratio", NumberRule::open(0.0, 1.0), Need::Required).value_or(0.0);
  a.penalty = t.number("penalty", NumberRule::positive("N/m, contact stiffness kn"), Need::Required).value_or(0.0);
  a.end_time = t.number("end_time", NumberRule::positive("s"), Need::Required).value_or(0.0);
  a.output_interval = t.number("output_interval", NumberRule::positive("s"), Need::Required).value_or(0.0);
  if (auto g = t.vec2("gravity", "m/s^2", Need::Optional)) a.gravity = *g;
  if (auto n = t.integer("open_close_max", 1, 50, Need::Optional)) a.open_close_max = static_cast<int>(*n);
  if (auto solver = t.choice("solver", {"pcg", "direct"}, Need::Optional))
    a.solver = *solver == "direct" ? Solver::Direct : Solver::Pcg;
  if (auto nodes =
          t.choice("intact_nodes", {to_string(IntactNodes::Contact), to_string(IntactNodes::Tie)}, Need::Optional))
    a.intact_nodes = *nodes == to_string(IntactNodes::Tie) ? IntactNodes::Tie : IntactNodes::Contact;
  if (auto load =
          t.choice("fracture_load", {to_string(FractureLoad::JointSprings), to_string(FractureLoad::BlockStress)},
                   Need::Optional))
    a.fracture_load =
        *load == to_string(FractureLoad::BlockStress) ? FractureLoad::BlockStress : FractureLoad::JointSprings;
  if (auto radius = t.number("fracture_stress_radius",
                             NumberRule::non_negative("m, radius of the blocks whose mean stress judges a joint"),
                             Need::Optional)) {
    a.fracture_stress_radius = *radius;
    if (a.fracture_stress_radius > 0.0 && a.fracture_load != FractureLoad::BlockStress)
      t.problem("fracture_stress_radius",
                fmt::format("averages the blocks' stress the criterion judges: it needs analysis.fracture_load = "
                            "\"{}\"",
                            to_string(FractureLoad::BlockStress)));
  }
  if (auto tol = t.number("solver_tolerance",
                          NumberRule::closed(kSmallestSolverTolerance, kLargestSolverTolerance,
                                             "PCG's relative residual |b - K·x| / |b|"),
                          Need::Optional))
    a.solver_tolerance = *tol;
  if (auto f = t.number("search_distance_factor",
                        NumberRule::positive("contact search distance / allowed step displacement"), Need::Optional))
    a.search_distance_factor = *f;
  if (auto f = t.number("pair_list_skin_factor", NumberRule::non_negative("pair-list skin / search distance"),
                        Need::Optional))
    a.pair_list_skin_factor = *f;
  if (auto eta =
          t.number("mass_damping", NumberRule::non_negative("1/s, η of the damping force −η·M·v"), Need::Optional)) {
    a.mass_damping = *eta;
    if (a.mode == Mode::Static && a.mass_damping > 0.0)
      t.problem("mass_damping",
                "has no effect in static mode (velocities are reset every step): use 0 or leave it out");
  }
  if (a.end_time > 0 && a.output_interval > a.end_time)
    t.problem("output_interval", fmt::format("must not exceed analysis.end_time ({:g} s)", a.end_time));
  check_interval_count(t, "output_interval", a.output_interval, a.end_time, kMaxOutputIntervals);
  if (a.dt_max > 0 && a.end_time > 0 && a.dt_max > a.end_time)
    t.problem("dt_max", fmt::format("must not exceed analysis.end_time ({:g} s)", a.end_time));
  t.reject_unknown_keys();
  return a;
}

std::vector<Material> parse_materials(TableReader t) {
  std::vector<Material> out;
  for (const std::string& name : t.entry_names()) {
    TableReader m = t.table(name, Need::Required);
    Material material;
    material.name = name;
    material.density = m.number("density", NumberRule::positive("kg/m^3"), Need::Required).value_or(0.0);
    material.young = m.number("young", NumberRule::positive("Pa, Young's modulus"), Need::Required).value_or(0.0);
    material.poisson = m.number("poisson", NumberRule::half_open(0.0, 0.5), Need::Required).value_or(0.0);
    m.reject_unknown_keys();
    out.push_back(material);
  }
  if (t.present() && out.empty()) t.problem("", "expected at least one material, e.g. [materials.rock]");
  return out;
}

std::vector<JointSet> parse_joint_sets(TableReader t, const Analysis& analysis) {
  std::vector<JointSet> out;
  for (const std::string& name : t.entry_names()) {
    TableReader j = t.table(name, Need::Required);
    JointSet set;
    set.name = name;
    set.friction_angle =
        kDegree * j.number("friction_angle", NumberRule::half_open(0.0, 90.0, "degrees"), Need::Required).value_or(0.0);
    set.cohesion = j.number("cohesion", NumberRule::non_negative("Pa"), Need::Required).value_or(0.0);
    set.tensile_strength = j.number("tensile_strength", NumberRule::non_negative("Pa"), Need::Required).value_or(0.0);
    set.normal_stiffness =
        j.number("normal_stiffness", NumberRule::positive("N/m"), Need::Optional).value_or(analysis.penalty);
    set.shear_stiffness = j.number("shear_stiffness", NumberRule::positive("N/m"), Need::Optional)
                              .value_or(kDefaultShearToNormalStiffness * set.normal_stiffness);
    set.fracture_energy =
        j.number("fracture_energy", NumberRule::non_negative("J/m^2, 0 for brittle joints"), Need::Optional)
            .value_or(0.0);
    set.shear_fracture_energy = j.number(
        "shear_fracture_energy", NumberRule::non_negative("J/m^2, 0 for joints brittle in shear"), Need::Optional);
    if (const auto interaction =
            j.choice("mode_interaction", {to_string(ModeInteraction::None), to_string(ModeInteraction::Quadratic)},
                     Need::Optional)) {
      set.mode_interaction =
          *interaction == to_string(ModeInteraction::Quadratic) ? ModeInteraction::Quadratic : ModeInteraction::None;
      if (set.mode_interaction == ModeInteraction::Quadratic && !set.softens())
        j.problem("mode_interaction",
                  "combines the modes of a softening joint: it needs fracture_energy or "
                  "shear_fracture_energy above 0");
    }
    // Softening weakens a joint's own springs: it needs them to be what the criterion judges and
    // to carry the tension across the joint alone.
    const char* softening_key = set.fracture_energy > 0.0 ? "fracture_energy" : "shear_fracture_energy";
    if (set.softens() && analysis.fracture_load != FractureLoad::JointSprings)
      j.problem(softening_key, fmt::format("softens the joint's springs, which the criterion judges only with "
                                           "analysis.fracture_load = \"{}\"",
                                           to_string(FractureLoad::JointSprings)));
    if (set.softens() && analysis.intact_nodes != IntactNodes::Contact)
      j.problem(softening_key, fmt::format("softens the joint's springs, but ties would still hold the blocks "
                                           "together: it needs analysis.intact_nodes = \"{}\"",
                                           to_string(IntactNodes::Contact)));
    j.reject_unknown_keys();
    out.push_back(set);
  }
  return out;
}

/// A central slit: slit_length, slit_width (m) and slit_angle (degrees), all required.
meshes::Slit parse_slit(TableReader& t, double diameter) {
  meshes::Slit slit;
  slit.length = t.number("slit_length", NumberRule::positive("m"), Need::Required).value_or(0.0);
  slit.width = t.number("slit_width", NumberRule::positive("m"), Need::Required).value_or(0.0);
  slit.inclination =
      kDegree * t.number("slit_angle", NumberRule::any("degrees, from the x axis"), Need::Required).value_or(0.0);
  if (diameter > 0 && slit.length >= diameter)
    t.problem("slit_length", fmt::format("must be shorter than the diameter ({:g} m)", diameter));
  if (slit.length > 0 && slit.width >= slit.length)
    t.problem("slit_width", fmt::format("must be smaller than slit_length ({:g} m)", slit.length));
  return slit;
}

ParsedGeometry parse_geometry(TableReader t, const std::filesystem::path& scene_file) {
  ParsedGeometry out;
  const bool has_file = t.has("file");
  const bool has_generator = t.has("generator");
  if (has_file && has_generator) {
    t.problem("file", "give either geometry.generator or geometry.file, not both");
  }
  if (has_file) {
    if (auto file = t.text("file", Need::Required)) {
      const std::filesystem::path source = t.where("file").path ? *t.where("file").path : scene_file.string();
      out.geometry = meshes::MshFile{source.parent_path() / *file};
    }
    t.reject_unknown_keys();
    return out;
  }
  const auto generator = t.choice("generator", kGenerators, Need::Required);
  const double diameter = t.number("diameter", NumberRule::positive("m"), Need::Required).value_or(0.0);
  out.diameter = diameter;
  if (generator == "plain_disc") {
    meshes::PlainDisc g;
    g.diameter = diameter;
    g.load_half_angle =
        kDegree *
        t.number("load_half_angle", NumberRule::half_open(0.0, 90.0, "degrees"), Need::Optional).value_or(0.0);
    out.geometry = g;
    out.bodies = {"disc"};
  } else if (generator == "flattened_disc") {
    meshes::FlattenedDisc g;
    g.diameter = diameter;
    g.flat_angle = kDegree * t.number("flat_angle", NumberRule::open(0.0, 180.0, "degrees, central angle of each flat"),
                                      Need::Required)
                                 .value_or(0.0);
    g.with_platens = t.boolean("platens", Need::Optional).value_or(true);
    g.platen_thickness =
        t.number("platen_thickness", NumberRule::positive("m"), g.with_platens ? Need::Required : Need::Optional)
            .value_or(0.0);
    g.platen_width = t.number("platen_width", NumberRule::positive("m"), Need::Optional).value_or(diameter);
    const bool slit_given = t.has("slit_length") || t.has("slit_width") || t.has("slit_angle");
    if (slit_given) g.slit = parse_slit(t, diameter);
    out.slotted = slit_given;
    out.geometry = g;
    out.bodies = g.with_platens ? std::vector<std::string>{"disc", "top_platen", "bottom_platen"}
                                : std::vector<std::string>{"disc"};
  } else if (generator == "slit_disc") {
    meshes::SlitDisc g;
    g.diameter = diameter;
    g.slit = parse_slit(t, diameter);
    out.slotted = true;
    out.geometry = g;
    out.bodies = {"disc"};
  } else if (generator == "impact_disc") {
    meshes::ImpactDisc g;
    g.diameter = diameter;
    g.joint_angle =
        kDegree *
        t.number("joint_angle", NumberRule::any("degrees, joint-slope angle θ"), Need::Required).value_or(0.0);
    g.connectivity = t.number("connectivity", NumberRule::open(0.0, 1.0, "γ = joint length / diameter"), Need::Required)
                         .value_or(0.0);
    g.joint_width = t.number("joint_width", NumberRule::positive("m"), Need::Required).value_or(0.0);
    g.plate_width = t.number("plate_width", NumberRule::positive("m"), Need::Required).value_or(0.0);
    g.plate_height = t.number("plate_height", NumberRule::positive("m"), Need::Required).value_or(0.0);
    g.patch_half_angle = kDegree * t.number("patch_half_angle", NumberRule::open(0.0, 90.0, "degrees"), Need::Optional)
                                       .value_or(kDefaultPatchHalfAngleDeg);
    const double joint_length = g.connectivity * diameter;
    if (joint_length > 0 && g.joint_width >= joint_length)
      t.problem("joint_width", fmt::format("must be smaller than the joint length γ·D ({:g} m)", joint_length));
    out.slotted = true;
    out.geometry = g;
    out.bodies = {"disc", "plate"};
  }
  // Keys of an unknown generator cannot be judged: the generator's own problem says enough.
  if (generator) t.reject_unknown_keys();
  return out;
}

meshes::MeshControl parse_mesh(TableReader t, const ParsedGeometry& geometry) {
  const bool generated = !std::holds_alternative<meshes::MshFile>(geometry.geometry);
  meshes::MeshControl control;
  if (auto blocks = t.integer("blocks", 1, kMaxTargetBlocks, generated ? Need::Required : Need::Optional))
    control.target_blocks = static_cast<int>(*blocks);
  control.block_tolerance =
      t.number("tolerance", NumberRule::open(0.0, 0.5, "relative"), Need::Optional).value_or(kDefaultBlockTolerance);
  if (!generated && t.has("blocks")) t.problem("blocks", "only a generated geometry has a target block count");
  if (auto algorithm = t.choice("algorithm", {"frontal-delaunay", "delaunay"}, Need::Optional)) {
    control.algorithm =
        *algorithm == "delaunay" ? meshes::MeshAlgorithm::Delaunay : meshes::MeshAlgorithm::FrontalDelaunay;
    if (!generated) t.problem("algorithm", "only a generated geometry is meshed here");
  }
  if (auto size = t.number("slot_end_size", NumberRule::half_open(kSmallestSlotEndSize, kLargestSlotEndSize, "slot widths"),
                           Need::Optional)) {
    control.slot_end_size_per_width = *size;
    if (!geometry.slotted) t.problem("slot_end_size", "the geometry has no slot or slit to mesh finer at its ends");
  }
  t.reject_unknown_keys();
  return control;
}

std::vector<Body> parse_bodies(TableReader t, const std::vector<Material>& materials,
                               const std::vector<JointSet>& joint_sets, Mode mode) {
  std::vector<Body> out;
  const auto material_names = names_of(materials);
  const auto joint_names = names_of(joint_sets);
  for (const std::string& name : t.entry_names()) {
    TableReader b = t.table(name, Need::Required);
    Body body;
    body.name = name;
    if (const std::string why = detail::name_problem(name); !why.empty()) t.problem(name, why);
    body.material = b.reference("material", material_names, "materials", Need::Required).value_or(0);
    if (auto role = b.choice("role", {"disc", "platen", "plate"}, Need::Required))
      body.role = *role == "platen" ? Role::Platen : *role == "plate" ? Role::Plate : Role::Disc;
    if (auto motion = b.choice("motion", {"free", "fixed", "prescribed"}, Need::Required))
      body.motion = *motion == "fixed" ? Motion::Fixed : *motion == "prescribed" ? Motion::Prescribed : Motion::Free;
    body.virtual_joints = b.reference("virtual_joints", joint_names, "joint sets", Need::Optional);
    if (auto v = b.vec2("velocity", "m/s, initial velocity", Need::Optional)) {
      body.initial_velocity = *v;
      if (mode == Mode::Static && (v->at(0) != 0.0 || v->at(1) != 0.0))
        b.problem("velocity", "an initial velocity has no effect in static mode (velocities are reset every step)");
    }
    const bool prescribed = body.motion == Motion::Prescribed;
    if (auto v = b.vec2("prescribed_velocity", "m/s", prescribed ? Need::Required : Need::Optional)) {
      body.prescribed_velocity = *v;
      if (!prescribed) b.problem("prescribed_velocity", "given, but motion is not \"prescribed\"");
    }
    b.reject_unknown_keys();
    out.push_back(body);
  }
  return out;
}

void check_bodies(TableReader& t, const std::vector<Body>& bodies, const std::vector<std::string>& expected,
                  const std::string& origin) {
  for (const Body& body : bodies) {
    if (std::find(expected.begin(), expected.end(), body.name) == expected.end()) {
      const std::string hint = detail::closest_match(body.name, expected);
      t.problem(body.name,
                fmt::format("{} has no body of this name; its bodies are: {}{}", origin, fmt::join(expected, ", "),
                            hint.empty() ? "" : fmt::format(" (did you mean \"{}\"?)", hint)));
    }
  }
  for (const std::string& name : expected) {
    const bool described = std::any_of(bodies.begin(), bodies.end(), [&](const Body& b) { return b.name == name; });
    if (!described)
      t.problem(name, fmt::format("missing: {} makes a body \"{}\"; describe it in [bodies.{}]", origin, name, name));
  }
}

std::vector<Gauge> parse_gauges(std::vector<TableReader> tables, double diameter) {
  std::vector<Gauge> out;
  for (TableReader& g : tables) {
    Gauge gauge;
    gauge.name = g.name("name", Need::Required).value_or("");
    if (auto p = g.vec2("position", "m", Need::Required)) {
      gauge.position = *p;
      const double radius = 0.5 * diameter;
      if (diameter > 0 && std::hypot(gauge.position[0], gauge.position[1]) >= radius)
        g.problem("position", fmt::format("lies outside the disc (radius {:g} m, centre at the origin)", radius));
    }
    const bool repeated =
        std::any_of(out.begin(), out.end(), [&](const Gauge& other) { return other.name == gauge.name; });
    if (repeated && !gauge.name.empty()) g.problem("name", fmt::format("a second gauge is named \"{}\"", gauge.name));
    g.reject_unknown_keys();
    out.push_back(gauge);
  }
  return out;
}

Output parse_output(TableReader t, double end_time) {
  Output out;
  out.vtk = t.boolean("vtk", Need::Optional).value_or(out.vtk);
  out.figures = t.boolean("figures", Need::Optional).value_or(out.figures);
  out.crack_interval =
      t.number("crack_interval", NumberRule::positive("s"), Need::Optional).value_or(out.crack_interval);
  check_interval_count(t, "crack_interval", out.crack_interval, end_time, kMaxCrackIntervals);
  // Times past the end of a (shortened) run are drawn at the last snapshot, not refused.
  out.figure_times =
      t.numbers("figure_times", NumberRule::non_negative("s"), Need::Optional).value_or(std::vector<double>{});
  t.reject_unknown_keys();
  return out;
}

std::optional<Verification> parse_verification(TableReader t) {
  if (!t.present()) return std::nullopt;
  Verification v;
  v.load = t.number("load", NumberRule::positive("N/m"), Need::Optional);
  const NumberRule relative = NumberRule::positive("relative error");
  v.centre_stress = t.number("centre_stress", relative, Need::Optional);
  v.field_l2 = t.number("field_l2", relative, Need::Optional);
  v.arrival_time = t.number("arrival_time", relative, Need::Optional);
  v.gauge_rms = t.number("gauge_rms", relative, Need::Optional);
  t.reject_unknown_keys();
  return v;
}

Scene parse_document(const toml::table& document, const std::filesystem::path& file, Diagnostics& diagnostics) {
  toml::source_region top_region{};
  top_region.path = std::make_shared<const std::string>(file.string());
  TableReader top(&document, "", top_region, diagnostics);

  Scene scene;
  scene.source = file;
  scene.name = top.name_or_file_stem(kNameKey, file);
  scene.description = top.text(kDescriptionKey, Need::Optional).value_or("");
  scene.analysis = parse_analysis(top.table("analysis", Need::Required));
  scene.materials = parse_materials(top.table("materials", Need::Required));
  scene.joint_sets = parse_joint_sets(top.table("joints", Need::Required), scene.analysis);

  TableReader contacts = top.table("contacts", Need::Required);
  scene.real_joints =
      contacts.reference("real_joints", names_of(scene.joint_sets), "joint sets", Need::Required).value_or(0);
  if (!scene.joint_sets.empty() && scene.joint_sets[scene.real_joints].softens())
    contacts.problem("real_joints", fmt::format("joint set \"{}\" has a fracture energy (fracture_energy or "
                                                "shear_fracture_energy), which only virtual joints "
                                                "use (real joints keep a brittle cohesion)",
                                                scene.joint_sets[scene.real_joints].name));
  contacts.reject_unknown_keys();

  ParsedGeometry geometry = parse_geometry(top.table("geometry", Need::Required), file);
  scene.geometry = geometry.geometry;
  const bool generated = !std::holds_alternative<meshes::MshFile>(scene.geometry);
  scene.mesh = parse_mesh(top.table("mesh", generated ? Need::Required : Need::Optional), geometry);

  TableReader bodies = top.table("bodies", Need::Required);
  scene.bodies = parse_bodies(bodies, scene.materials, scene.joint_sets, scene.analysis.mode);
  if (generated && !geometry.bodies.empty())
    check_bodies(bodies, scene.bodies, geometry.bodies, "the geometry generator");

  scene.gauges = parse_gauges(top.table_array("gauges", Need::Optional), geometry.diameter);
  scene.output = parse_output(top.table("output", Need::Optional), scene.analysis.end_time);
  scene.verification = parse_verification(top.table("verification", Need::Optional));
  top.reject_unknown_keys();
  return scene;
}

}  // namespace

std::string Problem::to_string() const {
  const std::string where = line > 0 ? fmt::format("{}:{}:{}", file, line, column) : file;
  return key.empty() ? fmt::format("{}: {}", where, message) : fmt::format("{}: {}: {}", where, key, message);
}

SceneError::SceneError(std::vector<Problem> problems)
    : std::runtime_error([&] {
        std::string text = fmt::format("{} problem{} found:", problems.size(), problems.size() == 1 ? "" : "s");
        for (const Problem& p : problems) text += "\n  " + p.to_string();
        return text;
      }()),
      problems_(std::move(problems)) {}

Scene parse_scene(const std::string& toml_text, const std::filesystem::path& file_name,
                  const std::vector<std::string>& overrides) {
  Diagnostics diagnostics(file_name.string());
  toml::table document = detail::load_document(toml_text, file_name, diagnostics);
  detail::apply_overrides(document, overrides, diagnostics);
  if (!diagnostics.empty()) throw SceneError(diagnostics.take());
  Scene scene = parse_document(document, file_name, diagnostics);
  if (!diagnostics.empty()) throw SceneError(diagnostics.take());
  scene.resolved_text = toml_text_of(document);
  toml::table unnamed = document;
  unnamed.erase(kNameKey);
  unnamed.erase(kDescriptionKey);
  scene.unnamed_text = toml_text_of(unnamed);
  return scene;
}

Scene load_scene(const std::filesystem::path& path) { return load_scene(path, {}); }

Scene load_scene(const std::filesystem::path& path, const std::vector<std::string>& overrides) {
  Diagnostics diagnostics(path.string());
  const std::optional<std::string> text = detail::read_text(path, diagnostics);
  if (!text) throw SceneError(diagnostics.take());
  return parse_scene(*text, path, overrides);
}

void check_bodies_against_mesh(const Scene& scene, const std::vector<std::string>& mesh_bodies) {
  Diagnostics diagnostics(scene.source.string());
  toml::source_region region{};
  region.path = std::make_shared<const std::string>(scene.source.string());
  TableReader bodies(nullptr, "bodies", region, diagnostics);
  check_bodies(bodies, scene.bodies, mesh_bodies, "the mesh file");
  if (!diagnostics.empty()) throw SceneError(diagnostics.take());
}

}  // namespace ddafrac::scene
