#include "document.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <sstream>

namespace ddafrac::scene::detail {

namespace {

/// A chain of `base` files longer than this is taken for a mistake (or a cycle).
constexpr int kMaxBaseDepth = 8;

toml::source_region region_of(const std::string& file, std::size_t line = 0) {
  toml::source_region where{};
  where.path = std::make_shared<const std::string>(file);
  where.begin.line = static_cast<toml::source_index>(line);
  where.begin.column = 0;
  where.end = where.begin;
  return where;
}

std::optional<toml::table> parse_text(const std::string& text, const std::string& file, Diagnostics& diagnostics) {
  try {
    return toml::parse(text, file);
  } catch (const toml::parse_error& e) {
    diagnostics.report(e.source(), "", fmt::format("not valid TOML: {}", e.description()));
    return std::nullopt;
  }
}

/// Moves every value of `over` into `base`; tables merge key by key, anything else replaces.
/// Moving (not copying) keeps each value's source position for messages.
void merge_into(toml::table& base, toml::table&& over) {
  for (auto&& [key, value] : over) {
    toml::node* existing = base.get(key.str());
    if (existing && existing->is_table() && value.is_table()) {
      merge_into(*existing->as_table(), std::move(*value.as_table()));
    } else {
      base.insert_or_assign(toml::key{key}, std::move(value));
    }
  }
}

toml::table load_chain(const std::string& text, const std::filesystem::path& file, Diagnostics& diagnostics,
                       int depth) {
  std::optional<toml::table> document = parse_text(text, file.string(), diagnostics);
  if (!document) return {};
  const toml::node* base_node = document->get(kBaseKey);
  if (!base_node) return std::move(*document);

  const auto* base_name = base_node->as_string();
  if (!base_name) {
    diagnostics.report(base_node->source(), std::string(kBaseKey),
                       "expected a string: the path of the scene file this one extends");
    return std::move(*document);
  }
  if (depth >= kMaxBaseDepth) {
    diagnostics.report(base_node->source(), std::string(kBaseKey),
                       fmt::format("more than {} nested base scenes (is there a cycle?)", kMaxBaseDepth));
    return std::move(*document);
  }
  const std::filesystem::path base_path = file.parent_path() / base_name->get();
  std::ifstream in(base_path);
  if (!in) {
    diagnostics.report(base_node->source(), std::string(kBaseKey),
                       fmt::format("cannot read the base scene \"{}\"", base_path.string()));
    return std::move(*document);
  }
  std::stringstream buffer;
  buffer << in.rdbuf();
  toml::table merged = load_chain(buffer.str(), base_path, diagnostics, depth + 1);
  merged.erase(kBaseKey);
  merge_into(merged, std::move(*document));
  return merged;
}

/// Splits "a.b.c" into its parts; empty parts make the key invalid.
std::vector<std::string> split_key(const std::string& dotted) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream in(dotted);
  while (std::getline(in, part, '.')) parts.push_back(part);
  if (!dotted.empty() && dotted.back() == '.') parts.push_back("");
  return parts;
}

}  // namespace

std::optional<std::string> read_text(const std::filesystem::path& path, Diagnostics& diagnostics) {
  std::ifstream in(path);
  if (!in) {
    diagnostics.report(region_of(path.string()), "", "cannot read the scene file (does it exist?)");
    return std::nullopt;
  }
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

toml::table load_document(const std::string& text, const std::filesystem::path& file, Diagnostics& diagnostics) {
  toml::table document = load_chain(text, file, diagnostics, 0);
  document.erase(kBaseKey);
  return document;
}

void apply_overrides(toml::table& document, const std::vector<std::string>& overrides, Diagnostics& diagnostics) {
  for (const std::string& assignment : overrides) {
    const std::string origin = fmt::format("--set {}", assignment);
    const std::size_t equals = assignment.find('=');
    const std::vector<std::string> parts =
        split_key(equals == std::string::npos ? assignment : assignment.substr(0, equals));
    const bool bad_key = std::any_of(parts.begin(), parts.end(), [](const std::string& p) { return p.empty(); });
    if (equals == std::string::npos || parts.empty() || bad_key) {
      diagnostics.report(region_of(origin), "", "expected key=value with a dotted key, e.g. analysis.dt_max=1e-8");
      continue;
    }
    const std::string value_text = assignment.substr(equals + 1);
    toml::table parsed;
    try {
      parsed = toml::parse("value = " + value_text, origin);
    } catch (const toml::parse_error&) {
      // A bare word such as `static` is meant as a string.
      parsed.insert_or_assign("value", value_text);
    }
    toml::table* target = &document;
    for (std::size_t i = 0; i + 1 < parts.size() && target; ++i) {
      toml::node* next = target->get(parts[i]);
      if (!next) next = &target->insert_or_assign(parts[i], toml::table{}).first->second;
      target = next->as_table();
    }
    if (!target) {
      diagnostics.report(region_of(origin), assignment.substr(0, equals), "cannot set a key inside a value that is not a table");
      continue;
    }
    target->insert_or_assign(parts.back(), std::move(*parsed.get("value")));
  }
}

}  // namespace ddafrac::scene::detail
