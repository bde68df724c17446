#pragma once
// Reading and validating scene files.

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "ddafrac/scene/scene.hpp"

namespace ddafrac::scene {

/// One problem found in a scene file: where, which key, and what was expected.
struct Problem {
  std::string file;
  int line = 0;  // 1-based; 0 when the problem is not tied to a line (e.g. a missing table)
  int column = 0;
  std::string key;  // dotted path, e.g. "analysis.dt_max"
  std::string message;

  std::string to_string() const;  // "file:line:column: key: message"
};

/// Thrown when a scene (or sweep) file has problems; what() lists all of them, one per line.
class SceneError : public std::runtime_error {
 public:
  explicit SceneError(std::vector<Problem> problems);
  const std::vector<Problem>& problems() const { return problems_; }

 private:
  std::vector<Problem> problems_;
};

/// Parses TOML text (file_name is used in messages and to resolve relative paths: `base`, the
/// .msh file). A scene may name a `base` scene file whose tables it extends and overrides.
/// `overrides` replace values before validation, as in load_scene.
Scene parse_scene(const std::string& toml_text, const std::filesystem::path& file_name,
                  const std::vector<std::string>& overrides = {});

/// Reads and parses a scene file.
Scene load_scene(const std::filesystem::path& path);

/// Checks a scene against a mesh read from a user's .msh file: every body of the scene is a
/// body of the mesh and the other way round. Throws SceneError.
void check_bodies_against_mesh(const Scene& scene, const std::vector<std::string>& mesh_bodies);

/// Reads a scene file with values replaced before validation, as in `--set analysis.dt_max=1e-8`.
/// Each override is "dotted.key=value"; the value is read as a TOML value (a bare word that is
/// not valid TOML is taken as a string).
Scene load_scene(const std::filesystem::path& path, const std::vector<std::string>& overrides);

}  // namespace ddafrac::scene
