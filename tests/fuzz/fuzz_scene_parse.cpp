// libFuzzer target: any bytes as the text of a scene file and `--set` overrides, through the
// parser the app uses (TOML syntax, `base` chains, overrides, every key's type, range and
// cross-checks). The input is the scene text, then, after a NUL byte if any, one override a
// line. A SceneError is the parser's answer to a bad scene; anything else (another exception, a
// crash, UB, a leak, a hang) is a finding, and so is an accepted scene with a value no run can use.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <initializer_list>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "ddafrac/scene/parse.hpp"

namespace {

using namespace ddafrac;

// The input is named as a file beside the shipped scenes (it is never written), so a seed's
// `base = "impact/case04.toml"` extends a real scene and the base chain is fuzzed too.
constexpr const char* kInputName = DDAFRAC_SOURCE_DIR "/scenes/fuzz_input.toml";

/// Stops the fuzzer (a finding) unless `holds`.
void require(bool holds, const char* what) {
  if (holds) return;
  std::fprintf(stderr, "parse_scene accepted an unusable scene: %s\n", what);
  std::abort();
}

void require_finite(std::initializer_list<double> values, const char* what) {
  for (double v : values) require(std::isfinite(v), what);
}

/// A name becomes a folder name and a CSV field: never empty, a path or a CSV breaker.
void require_plain_name(std::string_view name, const char* what) {
  require(!name.empty() && name != "." && name != "..", what);
  for (const char c : name) {
    require(c != '/' && c != '\\' && c != ',' && c != '"' && static_cast<unsigned char>(c) >= 0x20, what);
  }
}

void check_geometry(const meshes::Geometry& geometry) {
  const auto finite_slit = [](const meshes::Slit& s) {
    require_finite({s.length, s.width, s.inclination}, "a slit value that is not finite");
    require(s.length > 0 && s.width > 0, "a slit without length or width");
  };
  if (const auto* plain = std::get_if<meshes::PlainDisc>(&geometry)) {
    require_finite({plain->diameter, plain->load_half_angle}, "a plain disc value that is not finite");
  } else if (const auto* flattened = std::get_if<meshes::FlattenedDisc>(&geometry)) {
    require_finite({flattened->diameter, flattened->flat_angle, flattened->platen_thickness, flattened->platen_width},
                   "a flattened disc value that is not finite");
    if (flattened->slit) finite_slit(*flattened->slit);
  } else if (const auto* slit_disc = std::get_if<meshes::SlitDisc>(&geometry)) {
    require_finite({slit_disc->diameter}, "a slit disc diameter that is not finite");
    finite_slit(slit_disc->slit);
  } else if (const auto* impact = std::get_if<meshes::ImpactDisc>(&geometry)) {
    require_finite({impact->diameter, impact->joint_angle, impact->connectivity, impact->joint_width,
                    impact->plate_width, impact->plate_height, impact->patch_half_angle},
                   "an impact disc value that is not finite");
  }
}

/// What every accepted scene must be for a run to start: finite values, positive times and
/// moduli, references in range, names that are safe as folder names and CSV fields.
void check_accepted_scene(const scene::Scene& s) {
  const scene::Analysis& a = s.analysis;
  require_finite(
      {a.dt_max, a.max_displacement_ratio, a.penalty, a.end_time, a.output_interval, a.gravity[0], a.gravity[1]},
      "an analysis value that is not finite");
  require(a.dt_max > 0 && a.end_time > 0 && a.output_interval > 0 && a.penalty > 0, "a time or penalty <= 0");
  require(!s.materials.empty() && !s.bodies.empty() && !s.joint_sets.empty(), "no materials, bodies or joint sets");
  for (const scene::Material& m : s.materials) {
    require_finite({m.density, m.young, m.poisson}, "a material value that is not finite");
    require(m.density > 0 && m.young > 0 && m.poisson >= 0 && m.poisson < 0.5, "a material out of range");
  }
  for (const scene::JointSet& j : s.joint_sets) {
    require_finite({j.friction_angle, j.cohesion, j.tensile_strength, j.normal_stiffness, j.shear_stiffness},
                   "a joint value that is not finite");
  }
  require(s.real_joints < s.joint_sets.size(), "real joints of no joint set");
  require_plain_name(s.name, "a scene name unsafe as a folder name");
  for (const scene::Body& b : s.bodies) {
    require_plain_name(b.name, "a body name unsafe as a folder name");
    require(b.material < s.materials.size(), "a body of no material");
    require(!b.virtual_joints || *b.virtual_joints < s.joint_sets.size(), "virtual joints of no joint set");
    require_finite({b.initial_velocity[0], b.initial_velocity[1], b.prescribed_velocity[0], b.prescribed_velocity[1]},
                   "a body velocity that is not finite");
  }
  for (const scene::Gauge& g : s.gauges) {
    require_plain_name(g.name, "a gauge name unsafe as a CSV field");
    require_finite({g.position[0], g.position[1]}, "a gauge position that is not finite");
  }
  require_finite({s.output.crack_interval}, "a crack interval that is not finite");
  require(s.output.crack_interval > 0, "a crack interval <= 0");
  for (double t : s.output.figure_times) require_finite({t}, "a figure time that is not finite");
  check_geometry(s.geometry);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  const std::size_t end_of_scene = std::min(input.find('\0'), input.size());
  std::vector<std::string> overrides;
  for (std::size_t begin = end_of_scene + 1; begin < input.size();) {
    const std::size_t end = std::min(input.find('\n', begin), input.size());
    overrides.emplace_back(input.substr(begin, end - begin));
    begin = end + 1;
  }
  try {
    check_accepted_scene(scene::parse_scene(std::string(input.substr(0, end_of_scene)), kInputName, overrides));
  } catch (const scene::SceneError&) {
  }
  return 0;
}
