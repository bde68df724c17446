#include "scene_source.hpp"

#include <CLI/CLI.hpp>

#include <fmt/core.h>

#include <fstream>
#include <optional>

#include "commands.hpp"
#include "ddafrac/meshes/msh_io.hpp"
#include "ddafrac/scene/parse.hpp"

namespace ddafrac::app {

namespace {

/// Memory a DDA model holds per block with its contacts, joints and output text: about 10 kB
/// measured (peak RSS of `ddafrac bench` at 2 000 and 64 000 blocks), plus a margin for gmsh.
constexpr double kBytesPerBlock = 16e3;
constexpr double kBytesPerGigabyte = 1e9;

/// MemAvailable of /proc/meminfo in bytes, if it can be read.
std::optional<double> available_memory() {
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  double kilobytes = 0.0;
  std::string unit;
  while (meminfo >> key >> kilobytes >> unit)
    if (key == "MemAvailable:") return kilobytes * 1024.0;
  return std::nullopt;
}

}  // namespace

void check_memory_for_blocks(double blocks, const std::string& what) {
  const std::optional<double> available = available_memory();
  const double needed = blocks * kBytesPerBlock;
  if (!available || needed <= *available) return;
  throw CommandFailed(
      fmt::format("{}: {:g} blocks need about {:.1f} GB of memory ({:g} kB per block); this machine "
                  "has {:.1f} GB available",
                  what, blocks, needed / kBytesPerGigabyte, kBytesPerBlock / 1e3, *available / kBytesPerGigabyte));
}

void SceneArguments::add_to(CLI::App& command) {
  command.add_option("scene", scene_file, "scene file (TOML); the built-in default scene if omitted");
  command.add_option("--set", overrides, "override a scene value before validation, e.g. --set analysis.dt_max=1e-8")
      ->type_name("KEY=VALUE");
}

scene::Scene SceneArguments::load() const {
  const std::filesystem::path path = scene_file.empty() ? default_scene_path() : std::filesystem::path(scene_file);
  try {
    return scene::load_scene(path, overrides);
  } catch (const scene::SceneError& e) {
    throw CommandFailed(e.what());
  }
}

bool wants_direct_solver(const std::string& solver_option, const scene::Scene& scene) {
  return solver_option.empty() ? scene.analysis.solver == scene::Solver::Direct : solver_option == "direct";
}

meshes::Mesh dda_mesh(const scene::Scene& scene, meshes::QualityReport* quality) {
  try {
    if (const auto* file = std::get_if<meshes::MshFile>(&scene.geometry)) {
      meshes::Mesh mesh = meshes::read_msh(file->path);
      scene::check_bodies_against_mesh(scene, mesh.body_names);
      if (quality) *quality = meshes::measure_quality(mesh);
      return mesh;
    }
    return meshes::generate_dda_mesh(scene.geometry, scene.mesh, quality);
  } catch (const meshes::MeshError& e) {
    throw CommandFailed(fmt::format("{}: cannot mesh the scene: {}", scene.source.string(), e.what()));
  } catch (const scene::SceneError& e) {
    throw CommandFailed(e.what());
  }
}

std::filesystem::path default_scene_path() {
  return std::filesystem::path(DDAFRAC_SOURCE_DIR) / "scenes" / "default.toml";
}

std::filesystem::path output_directory(const std::string& out_option, const scene::Scene& scene,
                                       const std::string& command) {
  if (!out_option.empty()) return out_option;
  return std::filesystem::path("runs") / scene.name / command;
}

}  // namespace ddafrac::app
