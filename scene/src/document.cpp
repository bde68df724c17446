#include "document.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <sstream>

namespace ddafrac::scene::detail {

namespace {

/// A chain of `base` files longer than this is taken for a mistake (or a cycle).
constexpr int kMaxBaseDepth = 8;
/// A dotted key or table header of more parts than this is taken for a mistake: toml++ builds
/// and destroys nested tables recursively, and 100 000 levels overflow the stack.
constexpr std::size_t kMaxKeyParts = 64;
/// A scene is a few kilobytes; a larger file is not one (and would be slow to report on).
constexpr std::size_t kMaxSceneBytes = 1 << 20;

toml::source_region region_of(const std::string& file, std::size_t line = 0) {
  toml::source_region where{};
  where.path = std::make_shared<const std::string>(file);
  where.begin.line = static_cast<toml::source_index>(line);
  where.begin.column = line > 0 ? 1 : 0;
  where.end = where.begin;
  return where;
}

/// The line of the first key (or table header) of more than kMaxKeyParts dotted parts, or 0.
/// Dots are counted outside strings and comments, between the characters that end a key or a
/// value, so a number's decimal point counts once and never adds up along an array.
std::size_t line_of_too_deep_key(std::string_view text) {
  std::size_t line = 1, dots = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '"' || c == '\'') {
      const std::string quote(text.compare(i, 3, std::string(3, c)) == 0 ? 3 : 1, c);  // """ or "
      std::size_t j = i + quote.size();
      while (j < text.size() && text.compare(j, quote.size(), quote) != 0) {
        if (text[j] == '\\' && c == '"') ++j;  // an escape in a basic string
        if (j < text.size() && text[j] == '\n') ++line;
        ++j;
      }
      i = j + quote.size() - 1;
    } else if (c == '#') {
      while (i + 1 < text.size() && text[i + 1] != '\n') ++i;
    } else if (c == '.') {
      if (++dots >= kMaxKeyParts) return line;
    } else if (std::string_view("\n,=[]{}").find(c) != std::string_view::npos) {
      dots = 0;
      if (c == '\n') ++line;
    }
  }
  return 0;
}

/// Parses TOML text after the checks that keep toml++ safe; nothing if it is not TOML.
std::optional<toml::table> parse_safely(const std::string& text, const std::string& file, Diagnostics& diagnostics,
                                        bool report_syntax) {
  if (text.size() > kMaxSceneBytes) {
    diagnostics.report(region_of(file), "",
                       fmt::format("{} bytes is too long for a scene (at most {} bytes)", text.size(), kMaxSceneBytes));
    return std::nullopt;
  }
  if (const std::size_t line = line_of_too_deep_key(text)) {
    diagnostics.report(region_of(file, line), "", fmt::format("a key of more than {} dotted parts", kMaxKeyParts));
    return std::nullopt;
  }
  try {
    return toml::parse(text, file);
  } catch (const toml::parse_error& e) {
    if (report_syntax) diagnostics.report(e.source(), "", fmt::format("not valid TOML: {}", e.description()));
    return std::nullopt;
  }
}

std::optional<toml::table> parse_text(const std::string& text, const std::string& file, Diagnostics& diagnostics) {
  return parse_safely(text, file, diagnostics, true);
}

/// `text` as a TOML basic string: quoted, with quotes, backslashes and control characters escaped.
std::string toml_string(std::string_view text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
      out += fmt::format("\\u{:04x}", static_cast<unsigned char>(c));
    else
      out += c;
  }
  return out + '"';
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
  // Only a regular file of scene size: a device such as /dev/zero would be read for ever.
  std::error_code error;
  const bool scene_sized = std::filesystem::is_regular_file(base_path, error) &&
                           std::filesystem::file_size(base_path, error) <= kMaxSceneBytes && !error;
  std::ifstream in(base_path);
  if (!scene_sized || !in) {
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
  std::error_code error;
  if (std::filesystem::exists(path, error) && !std::filesystem::is_regular_file(path, error)) {
    diagnostics.report(region_of(path.string()), "", "not a regular file (a directory or a device?)");
    return std::nullopt;
  }
  if (const auto size = std::filesystem::file_size(path, error); !error && size > kMaxSceneBytes) {
    diagnostics.report(region_of(path.string()), "",
                       fmt::format("{} bytes is too long for a scene (at most {} bytes)", size, kMaxSceneBytes));
    return std::nullopt;
  }
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
    const std::string origin = fmt::format("{}{}", kOverrideOrigin, assignment);
    const std::size_t equals = assignment.find('=');
    const std::string key = assignment.substr(0, equals);
    const std::vector<std::string> parts = split_key(key);
    const bool bad_key = std::any_of(parts.begin(), parts.end(), [](const std::string& p) { return p.empty(); });
    if (equals == std::string::npos || parts.empty() || bad_key) {
      diagnostics.report(region_of(origin), "", "expected key=value with a dotted key, e.g. analysis.dt_max=1e-8");
      continue;
    }
    if (!valid_utf8(assignment)) {
      diagnostics.report(region_of(fmt::format("{}{:?}", kOverrideOrigin, assignment)), "", "not valid UTF-8");
      continue;
    }
    // Parsed as one line of TOML, so every value (and every table the dotted key makes) carries
    // the override as its source, and messages blame the option, not the scene file.
    const std::string value = assignment.substr(equals + 1);
    std::optional<toml::table> parsed = parse_safely(key + " = " + value, origin, diagnostics, false);
    // A bare word such as `static` is meant as a string.
    if (!parsed) parsed = parse_safely(key + " = " + toml_string(value), origin, diagnostics, false);
    if (!parsed) {
      diagnostics.report(region_of(origin), key,
                         "cannot be read: expected a dotted key of bare words (letters, digits, _ and -) and a "
                         "value in UTF-8, e.g. analysis.dt_max=1e-8");
      continue;
    }
    merge_into(document, std::move(*parsed));
  }
}

}  // namespace ddafrac::scene::detail
