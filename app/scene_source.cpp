#include "scene_source.hpp"

#include <CLI/CLI.hpp>

#include "commands.hpp"
#include "ddafrac/scene/parse.hpp"

namespace ddafrac::app {

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

std::filesystem::path default_scene_path() { return std::filesystem::path(DDAFRAC_SOURCE_DIR) / "scenes" / "default.toml"; }

std::filesystem::path output_directory(const std::string& out_option, const scene::Scene& scene,
                                       const std::string& command) {
  if (!out_option.empty()) return out_option;
  return std::filesystem::path("runs") / scene.name / command;
}

}  // namespace ddafrac::app
