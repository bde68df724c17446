#pragma once
// Where a command's scene comes from: the file the user named, or the built-in default scene.

#include <filesystem>
#include <string>
#include <vector>

#include "ddafrac/meshes/generate.hpp"
#include "ddafrac/meshes/mesh.hpp"
#include "ddafrac/scene/scene.hpp"

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace ddafrac::app {

/// The scene options shared by the commands that read a scene: SCENE (optional: the default
/// scene is used without it) and --set key=value.
struct SceneArguments {
  std::string scene_file;
  std::vector<std::string> overrides;

  void add_to(CLI::App& command);
  /// Loads and validates the scene; a bad scene becomes a CommandFailed listing its problems.
  scene::Scene load() const;
};

/// Whether a command runs the direct solver: its --solver value ("pcg" or "direct") if given,
/// else the scene's analysis.solver.
bool wants_direct_solver(const std::string& solver_option, const scene::Scene& scene);

/// The scene's DDA mesh: generated, or read from the user's .msh and checked against the
/// scene's bodies. Problems become a CommandFailed naming the scene file.
meshes::Mesh dda_mesh(const scene::Scene& scene, meshes::QualityReport* quality = nullptr);

/// Refuses (CommandFailed) a model of `blocks` blocks that would need more memory than the
/// machine has available, with the estimate; says nothing where /proc/meminfo is not readable.
void check_memory_for_blocks(double blocks, const std::string& what);

/// The scene used when none is named: scenes/default.toml of the source tree.
std::filesystem::path default_scene_path();

/// The run directory: --out if given, else runs/<scene name>/<command>.
std::filesystem::path output_directory(const std::string& out_option, const scene::Scene& scene,
                                       const std::string& command);

}  // namespace ddafrac::app
