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
  int line = 0;    // 1-based; 0 when the problem is not tied to a line (e.g. a missing table)
  int column = 0;
  std::string key; // dotted path, e.g. "analysis.dt_max"
  std::string message;

  std::string to_string() const;  // "file:line:column: key: message"
};

/// Thrown when a scene has problems; what() lists all of them, one per line.
class SceneError : public std::runtime_error {
 public:
  explicit SceneError(std::vector<Problem> problems);
  const std::vector<Problem>& problems() const { return problems_; }

 private:
  std::vector<Problem> problems_;
};

/// Parses TOML text (file_name is used in messages and to resolve relative .msh paths).
Scene parse_scene(const std::string& toml_text, const std::filesystem::path& file_name);

/// Reads and parses a scene file.
Scene load_scene(const std::filesystem::path& path);

/// Replaces values of a parsed TOML document before validation, as in `--set analysis.dt_max=1e-8`.
/// Accepts "dotted.key=value"; the value is parsed as a TOML value.
Scene load_scene(const std::filesystem::path& path, const std::vector<std::string>& overrides);

}  // namespace ddafrac::scene
