#pragma once
// A validating reader over toml++ tables: every read states the expected type, range and unit,
// every problem is recorded with file, line and dotted key, and keys nobody asked for are
// reported as unknown with the closest valid key suggested. Internal to the scene library.

#include <toml++/toml.h>

#include <array>
#include <filesystem>
#include <initializer_list>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "ddafrac/scene/parse.hpp"

namespace ddafrac::scene::detail {

/// The source name of a value given on the command line: "--set key=value". Such a value has no
/// line of its own (toml++ gives it line 1 of its one-line text), so problems name the option only.
inline constexpr std::string_view kOverrideOrigin = "--set ";

/// Collects problems; knows which file to blame when a node has no source of its own.
class Diagnostics {
 public:
  explicit Diagnostics(std::string fallback_file) : fallback_file_(std::move(fallback_file)) {}

  void report(const toml::source_region& where, std::string key, std::string message);
  bool empty() const { return problems_.empty(); }
  std::vector<Problem> take() { return std::move(problems_); }

 private:
  std::string fallback_file_;
  std::vector<Problem> problems_;
};

enum class Need { Required, Optional };

/// An admissible interval for a number, with its unit for messages. An unset bound is infinite.
struct NumberRule {
  std::optional<double> min;
  std::optional<double> max;
  bool min_open = false;
  bool max_open = false;
  std::string unit;  // e.g. "s", "Pa", "degrees"; empty for dimensionless

  bool admits(double v) const;
  std::string describe() const;  // "a number > 0 (s)"

  static NumberRule positive(std::string unit) { return {0.0, std::nullopt, true, false, std::move(unit)}; }
  static NumberRule non_negative(std::string unit) { return {0.0, std::nullopt, false, false, std::move(unit)}; }
  static NumberRule any(std::string unit) { return {std::nullopt, std::nullopt, false, false, std::move(unit)}; }
  static NumberRule open(double lo, double hi, std::string unit = "") { return {lo, hi, true, true, std::move(unit)}; }
  static NumberRule half_open(double lo, double hi, std::string unit = "") {
    return {lo, hi, false, true, std::move(unit)};
  }
  static NumberRule closed(double lo, double hi, std::string unit = "") {
    return {lo, hi, false, false, std::move(unit)};
  }
};

/// Why `name` cannot name an output, or "" if it can. Scene, body and gauge names become folder
/// names, CSV fields and JSON strings, so a name is valid UTF-8 and holds only letters (of any
/// script), digits, spaces and _ - . + ( ), not starting with a dot or a space: no path
/// separator, no "..", no comma, quote or control character.
std::string name_problem(std::string_view name);

/// Whether `text` is valid UTF-8 (TOML, JSON and the messages need it).
bool valid_utf8(std::string_view text);

/// The closest candidate within a small edit distance, or "" if none is close.
std::string closest_match(std::string_view word, const std::vector<std::string>& candidates);

class TableReader {
 public:
  /// `table` may be null (a missing optional table): every read then yields nothing.
  TableReader(const toml::table* table, std::string path, const toml::source_region& where, Diagnostics& diagnostics);

  std::optional<double> number(std::string_view key, const NumberRule& rule, Need need);
  std::optional<long long> integer(std::string_view key, long long min, long long max, Need need);
  std::optional<bool> boolean(std::string_view key, Need need);
  std::optional<std::string> text(std::string_view key, Need need);
  /// A string that names an output (see name_problem).
  std::optional<std::string> name(std::string_view key, Need need);
  /// `key` as a name; without it, the stem of `file`, which must then be a valid name itself.
  std::string name_or_file_stem(std::string_view key, const std::filesystem::path& file);
  /// A string that must be one of `options`.
  std::optional<std::string> choice(std::string_view key, const std::vector<std::string>& options, Need need);
  /// A reference by name to an entry of another table (e.g. a material).
  std::optional<std::size_t> reference(std::string_view key, const std::vector<std::string>& names,
                                       std::string_view what, Need need);
  std::optional<std::array<double, 2>> vec2(std::string_view key, const std::string& unit, Need need);
  std::optional<std::vector<double>> numbers(std::string_view key, const NumberRule& rule, Need need);
  /// An array of strings; `what` says what each string is, for messages.
  std::optional<std::vector<std::string>> strings(std::string_view key, const std::string& what, Need need);

  /// A sub-table; a missing optional one gives a reader over nothing.
  TableReader table(std::string_view key, Need need);
  /// The keys of a table of named entries ([materials.rock], [materials.steel], ...), in file order.
  std::vector<std::string> entry_names() const;
  /// An array of tables ([[gauges]]).
  std::vector<TableReader> table_array(std::string_view key, Need need);

  bool present() const { return table_ != nullptr; }
  bool has(std::string_view key) const;
  const toml::source_region& where() const { return where_; }
  const toml::source_region& where(std::string_view key) const;
  std::string path_of(std::string_view key) const;
  void problem(std::string_view key, std::string message);

  /// Reports every key of this table that no read asked for.
  void reject_unknown_keys();

 private:
  const toml::node* find(std::string_view key, Need need, const std::string& expected);
  /// The value at `key` as toml++ type T (a toml::value<...>, toml::array, ...), or null after
  /// reporting it missing (if required) or of the wrong type.
  template <class T>
  const auto* find_as(std::string_view key, Need need, const std::string& expected) {
    const toml::node* node = find(key, need, expected);
    if (!node) return static_cast<decltype(node->as<T>())>(nullptr);
    const auto* typed = node->as<T>();
    if (!typed) wrong_type(key, *node, expected);
    return typed;
  }
  void wrong_type(std::string_view key, const toml::node& node, const std::string& expected);

  const toml::table* table_;
  std::string path_;
  toml::source_region where_;
  Diagnostics* diagnostics_;
  std::set<std::string, std::less<>> asked_;
  bool silent_ = false;  // the table itself is missing and was reported: say nothing more
};

}  // namespace ddafrac::scene::detail
