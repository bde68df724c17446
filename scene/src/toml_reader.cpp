#include "toml_reader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>

namespace ddafrac::scene::detail {

namespace {

/// A suggestion is offered when at most this share of the word's letters must change.
constexpr double kSuggestionEditShare = 0.34;
/// Shorter words are not taken as abbreviations of a key.
constexpr std::size_t kMinPrefixLength = 3;

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      const std::size_t substitution = diagonal + (a[i - 1] == b[j - 1] ? 0 : 1);
      row[j] = std::min({above + 1, row[j - 1] + 1, substitution});
      diagonal = above;
    }
  }
  return row[b.size()];
}

std::string type_name(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::string: return "a string";
    case toml::node_type::integer:
    case toml::node_type::floating_point: return "a number";
    case toml::node_type::boolean: return "a boolean";
    case toml::node_type::array: return "an array";
    case toml::node_type::table: return "a table";
    default: return "a date/time";
  }
}

std::string format_number(double v) { return fmt::format("{:g}", v); }

std::optional<double> as_double(const toml::node& node) {
  if (auto i = node.as_integer()) return static_cast<double>(i->get());
  if (auto f = node.as_floating_point()) return f->get();
  return std::nullopt;
}

std::string quoted_list(const std::vector<std::string>& options) {
  std::string out;
  for (std::size_t i = 0; i < options.size(); ++i) {
    if (i) out += i + 1 == options.size() ? " or " : ", ";
    out += '"' + options[i] + '"';
  }
  return out;
}

/// A name longer than this is taken for a mistake (it becomes a folder name; 255 bytes is the limit).
constexpr std::size_t kMaxNameBytes = 64;

/// The length of the UTF-8 sequence starting at text[i], or 0 if it is not a valid one.
std::size_t utf8_sequence_length(std::string_view text, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char lead = byte(i);
  const std::size_t length = lead < 0x80           ? 1
                             : (lead >> 5) == 0x6  ? 2
                             : (lead >> 4) == 0xe  ? 3
                             : (lead >> 3) == 0x1e ? 4
                                                   : 0;
  if (length == 0 || i + length > text.size()) return 0;
  for (std::size_t k = 1; k < length; ++k)
    if ((byte(i + k) >> 6) != 0x2) return 0;
  return length;
}

bool allowed_ascii_in_name(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || std::string_view(" _-.+()").find(c) != std::string_view::npos;
}

}  // namespace

bool valid_utf8(std::string_view text) {
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t length = utf8_sequence_length(text, i);
    if (length == 0) return false;
    i += length;
  }
  return true;
}

std::string name_problem(std::string_view name) {
  constexpr std::string_view kRule =
      "a name of letters, digits, spaces and _ - . + ( ), not starting with a dot or a space";
  if (name.empty()) return fmt::format("expected {}, got an empty string", kRule);
  if (name.size() > kMaxNameBytes)
    return fmt::format("expected {}, at most {} bytes long, got {} bytes", kRule, kMaxNameBytes, name.size());
  for (std::size_t i = 0; i < name.size();) {
    const std::size_t length = utf8_sequence_length(name, i);
    if (length == 0) return "not valid UTF-8 (byte " + std::to_string(i + 1) + ")";
    if (length == 1 && !allowed_ascii_in_name(name[i]))
      return fmt::format("expected {}, got {:?} (the character {:?} is not allowed)", kRule, name, name.substr(i, 1));
    i += length;
  }
  if (name.front() == '.' || name.front() == ' ') return fmt::format("expected {}, got {:?}", kRule, name);
  return {};
}

void Diagnostics::report(const toml::source_region& where, std::string key, std::string message) {
  Problem p;
  p.file = where.path ? *where.path : fallback_file_;
  const bool command_line = p.file.compare(0, kOverrideOrigin.size(), kOverrideOrigin) == 0;
  p.line = command_line ? 0 : static_cast<int>(where.begin.line);
  p.column = command_line ? 0 : static_cast<int>(where.begin.column);
  p.key = std::move(key);
  p.message = std::move(message);
  problems_.push_back(std::move(p));
}

bool NumberRule::admits(double v) const {
  if (!std::isfinite(v)) return false;
  if (min && (min_open ? v <= *min : v < *min)) return false;
  if (max && (max_open ? v >= *max : v > *max)) return false;
  return true;
}

std::string NumberRule::describe() const {
  std::string range;
  if (min && max) {
    range = fmt::format(" in {}{}, {}{}", min_open ? '(' : '[', format_number(*min), format_number(*max),
                        max_open ? ')' : ']');
  } else if (min) {
    range = fmt::format(" {} {}", min_open ? ">" : ">=", format_number(*min));
  } else if (max) {
    range = fmt::format(" {} {}", max_open ? "<" : "<=", format_number(*max));
  }
  return "a number" + range + (unit.empty() ? "" : " (" + unit + ")");
}

std::string closest_match(std::string_view word, const std::vector<std::string>& candidates) {
  // A word that is the start of exactly one candidate ("impact" for "impact_disc") means it.
  if (word.size() >= kMinPrefixLength) {
    std::vector<std::string> extensions;
    for (const auto& candidate : candidates)
      if (candidate.size() > word.size() && candidate.compare(0, word.size(), word) == 0)
        extensions.push_back(candidate);
    if (extensions.size() == 1) return extensions.front();
  }
  std::string best;
  std::size_t best_distance = std::max<std::size_t>(
      1, static_cast<std::size_t>(std::ceil(kSuggestionEditShare * static_cast<double>(word.size()))));
  for (const auto& candidate : candidates) {
    const std::size_t d = edit_distance(word, candidate);
    if (d <= best_distance && (best.empty() || d < best_distance)) {
      best = candidate;
      best_distance = d;
    }
  }
  return best;
}

TableReader::TableReader(const toml::table* table, std::string path, const toml::source_region& where,
                         Diagnostics& diagnostics)
    : table_(table), path_(std::move(path)), where_(where), diagnostics_(&diagnostics) {}

std::string TableReader::path_of(std::string_view key) const {
  return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
}

bool TableReader::has(std::string_view key) const { return table_ && table_->contains(key); }

const toml::source_region& TableReader::where(std::string_view key) const {
  if (table_) {
    if (const toml::node* node = table_->get(key)) return node->source();
  }
  return where_;
}

void TableReader::problem(std::string_view key, std::string message) {
  diagnostics_->report(where(key), path_of(key), std::move(message));
}

const toml::node* TableReader::find(std::string_view key, Need need, const std::string& expected) {
  asked_.emplace(key);
  const toml::node* node = table_ ? table_->get(key) : nullptr;
  if (!node && need == Need::Required && !silent_)
    diagnostics_->report(where_, path_of(key), fmt::format("missing required value: {}", expected));
  return node;
}

void TableReader::wrong_type(std::string_view key, const toml::node& node, const std::string& expected) {
  diagnostics_->report(node.source(), path_of(key), fmt::format("expected {}, got {}", expected, type_name(node)));
}

std::optional<double> TableReader::number(std::string_view key, const NumberRule& rule, Need need) {
  const std::string expected = rule.describe();
  const toml::node* node = find(key, need, expected);
  if (!node) return std::nullopt;
  const std::optional<double> value = as_double(*node);
  if (!value) {
    wrong_type(key, *node, expected);
    return std::nullopt;
  }
  if (!rule.admits(*value)) {
    diagnostics_->report(node->source(), path_of(key),
                         fmt::format("expected {}, got {}", expected, format_number(*value)));
    return std::nullopt;
  }
  return value;
}

std::optional<long long> TableReader::integer(std::string_view key, long long min, long long max, Need need) {
  const std::string expected = fmt::format("a whole number in [{}, {}]", min, max);
  const auto* integer = find_as<std::int64_t>(key, need, expected);
  if (!integer) return std::nullopt;
  const long long value = integer->get();
  if (value < min || value > max) {
    diagnostics_->report(integer->source(), path_of(key), fmt::format("expected {}, got {}", expected, value));
    return std::nullopt;
  }
  return value;
}

std::optional<bool> TableReader::boolean(std::string_view key, Need need) {
  if (const auto* b = find_as<bool>(key, need, "true or false")) return b->get();
  return std::nullopt;
}

std::optional<std::string> TableReader::text(std::string_view key, Need need) {
  if (const auto* s = find_as<std::string>(key, need, "a string")) return s->get();
  return std::nullopt;
}

std::optional<std::string> TableReader::name(std::string_view key, Need need) {
  std::optional<std::string> value = text(key, need);
  if (!value) return value;
  if (const std::string why = name_problem(*value); !why.empty()) {
    problem(key, why);
    return std::nullopt;
  }
  return value;
}

std::string TableReader::name_or_file_stem(std::string_view key, const std::filesystem::path& file) {
  if (has(key)) return name(key, Need::Required).value_or("");
  const std::string stem = file.stem().string();
  if (const std::string why = name_problem(stem); !why.empty())
    problem(key, fmt::format("missing, and the file name cannot stand in for it: {}; give a {} = \"...\"", why, key));
  return stem;
}

std::optional<std::string> TableReader::choice(std::string_view key, const std::vector<std::string>& options,
                                               Need need) {
  const std::string expected = "one of " + quoted_list(options);
  const auto* s = find_as<std::string>(key, need, expected);
  if (!s) return std::nullopt;
  if (std::find(options.begin(), options.end(), s->get()) != options.end()) return s->get();
  const std::string hint = closest_match(s->get(), options);
  diagnostics_->report(s->source(), path_of(key),
                       fmt::format("expected {}, got \"{}\"{}", expected, s->get(),
                                   hint.empty() ? "" : fmt::format(" (did you mean \"{}\"?)", hint)));
  return std::nullopt;
}

std::optional<std::size_t> TableReader::reference(std::string_view key, const std::vector<std::string>& names,
                                                  std::string_view what, Need need) {
  const std::string expected = fmt::format("the name of one of the {}", what);
  const auto* s = find_as<std::string>(key, need, expected);
  if (!s) return std::nullopt;
  const auto it = std::find(names.begin(), names.end(), s->get());
  if (it != names.end()) return static_cast<std::size_t>(it - names.begin());
  const std::string hint = closest_match(s->get(), names);
  diagnostics_->report(s->source(), path_of(key),
                       fmt::format("no {} is named \"{}\"; defined: {}{}", what, s->get(),
                                   names.empty() ? std::string("none") : quoted_list(names),
                                   hint.empty() ? "" : fmt::format(" (did you mean \"{}\"?)", hint)));
  return std::nullopt;
}

std::optional<std::array<double, 2>> TableReader::vec2(std::string_view key, const std::string& unit, Need need) {
  const std::string expected = fmt::format("an array of two numbers [x, y]{}", unit.empty() ? "" : " (" + unit + ")");
  const toml::node* node = find(key, need, expected);
  if (!node) return std::nullopt;
  const auto* array = node->as_array();
  if (!array || array->size() != 2) {
    diagnostics_->report(node->source(), path_of(key),
                         fmt::format("expected {}, got {}", expected,
                                     array ? fmt::format("an array of {} values", array->size()) : type_name(*node)));
    return std::nullopt;
  }
  std::array<double, 2> out{};
  for (std::size_t i = 0; i < 2; ++i) {
    const std::optional<double> v = as_double(*array->get(i));
    if (!v || !std::isfinite(*v)) {
      wrong_type(key, *array->get(i), expected);
      return std::nullopt;
    }
    out[i] = *v;
  }
  return out;
}

std::optional<std::vector<double>> TableReader::numbers(std::string_view key, const NumberRule& rule, Need need) {
  const std::string expected = "an array of numbers, each " + rule.describe();
  const auto* array = find_as<toml::array>(key, need, expected);
  if (!array) return std::nullopt;
  std::vector<double> out;
  for (const toml::node& element : *array) {
    const std::optional<double> v = as_double(element);
    if (!v || !rule.admits(*v)) {
      diagnostics_->report(element.source(), path_of(key),
                           fmt::format("expected {}, got {}", expected, v ? format_number(*v) : type_name(element)));
      return std::nullopt;
    }
    out.push_back(*v);
  }
  return out;
}

std::optional<std::vector<std::string>> TableReader::strings(std::string_view key, const std::string& what, Need need) {
  const std::string expected = "an array of strings (" + what + ")";
  const auto* array = find_as<toml::array>(key, need, expected);
  if (!array) return std::nullopt;
  std::vector<std::string> out;
  for (const toml::node& element : *array) {
    const auto* s = element.as_string();
    if (!s) {
      wrong_type(key, element, expected);
      return std::nullopt;
    }
    out.push_back(s->get());
  }
  return out;
}

TableReader TableReader::table(std::string_view key, Need need) {
  asked_.emplace(key);
  const toml::node* node = table_ ? table_->get(key) : nullptr;
  const bool missing = node == nullptr;
  if (missing && need == Need::Required && !silent_)
    diagnostics_->report(where_, path_of(key), fmt::format("missing required table [{}]", path_of(key)));
  if (node && !node->is_table()) {
    wrong_type(key, *node, "a table");
    node = nullptr;
  }
  TableReader reader(node ? node->as_table() : nullptr, path_of(key), node ? node->source() : where_, *diagnostics_);
  // Problems inside a table that is missing or of the wrong type would only repeat this one.
  reader.silent_ = silent_ || (!node && (need == Need::Required || !missing));
  return reader;
}

std::vector<std::string> TableReader::entry_names() const {
  std::vector<std::pair<toml::source_position, std::string>> ordered;
  if (table_) {
    for (auto&& [k, v] : *table_) ordered.emplace_back(v.source().begin, std::string(k.str()));
  }
  std::stable_sort(ordered.begin(), ordered.end(), [](const auto& a, const auto& b) {
    return a.first.line != b.first.line ? a.first.line < b.first.line : a.first.column < b.first.column;
  });
  std::vector<std::string> names;
  for (auto& entry : ordered) names.push_back(std::move(entry.second));
  return names;
}

std::vector<TableReader> TableReader::table_array(std::string_view key, Need need) {
  const std::string expected = "an array of tables ([[" + path_of(key) + "]])";
  std::vector<TableReader> out;
  const auto* array = find_as<toml::array>(key, need, expected);
  if (!array) return out;
  for (std::size_t i = 0; i < array->size(); ++i) {
    const toml::node& element = *array->get(i);
    if (!element.is_table()) {
      wrong_type(key, element, "a table");
      continue;
    }
    out.emplace_back(element.as_table(), fmt::format("{}[{}]", path_of(key), i), element.source(), *diagnostics_);
  }
  return out;
}

void TableReader::reject_unknown_keys() {
  if (!table_) return;
  const std::vector<std::string> known(asked_.begin(), asked_.end());
  for (auto&& [k, v] : *table_) {
    const std::string name(k.str());
    if (asked_.count(name)) continue;
    const std::string hint = closest_match(name, known);
    diagnostics_->report(
        k.source().begin.line ? k.source() : v.source(), path_of(name),
        fmt::format("unknown key{}", hint.empty() ? fmt::format("; valid keys here: {}", quoted_list(known))
                                                  : fmt::format("; did you mean \"{}\"?", hint)));
  }
}

}  // namespace ddafrac::scene::detail
