#pragma once
// Turning scene text into one TOML document: syntax errors, `base` inheritance and `--set`
// overrides. Internal to the scene library.

#include <toml++/toml.h>

#include <filesystem>
#include <string>
#include <vector>

#include "toml_reader.hpp"

namespace ddafrac::scene::detail {

/// The key by which a scene names the scene file it extends.
inline constexpr std::string_view kBaseKey = "base";

/// Parses `text` (named `file` in messages) and merges it over its `base` chain. Syntax errors
/// and unreadable bases are recorded in `diagnostics`; the result is then incomplete.
toml::table load_document(const std::string& text, const std::filesystem::path& file, Diagnostics& diagnostics);

/// Applies "dotted.key=value" overrides to the document.
void apply_overrides(toml::table& document, const std::vector<std::string>& overrides, Diagnostics& diagnostics);

/// Reads a whole file; records a problem and returns nothing if it cannot.
std::optional<std::string> read_text(const std::filesystem::path& path, Diagnostics& diagnostics);

}  // namespace ddafrac::scene::detail
