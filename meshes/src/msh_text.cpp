#include "msh_text.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <limits>
#include <set>
#include <vector>

#include <fmt/format.h>

#include "ddafrac/meshes/generate.hpp"

namespace ddafrac::meshes::detail {

namespace {

/// The longest piece of a bad word quoted in a message (a binary file has very long "words").
constexpr std::size_t kMaxQuotedBytes = 40;
/// How to save a mesh that ddafrac can read, for the messages that refuse a file.
constexpr std::string_view kHowToSave =
    "save the mesh as ASCII MSH 4.1 (gmsh options Mesh.MshFileVersion = 4.1, Mesh.Binary = 0)";

enum class Version { Msh2, Msh41 };

/// gmsh's element types up to the second order, by number, as gmsh names them.
ElementKind element_kind(int type) {
  struct Known {
    int type;
    const char* name;
    int dim;
    int order;
  };
  static constexpr std::array<Known, 19> kKnown{{
      {1, "Line 2", 1, 1},           {2, "Triangle 3", 2, 1},      {3, "Quadrilateral 4", 2, 1},
      {4, "Tetrahedron 4", 3, 1},    {5, "Hexahedron 8", 3, 1},    {6, "Prism 6", 3, 1},
      {7, "Pyramid 5", 3, 1},        {8, "Line 3", 1, 2},          {9, "Triangle 6", 2, 2},
      {10, "Quadrilateral 9", 2, 2}, {11, "Tetrahedron 10", 3, 2}, {12, "Hexahedron 27", 3, 2},
      {13, "Prism 18", 3, 2},        {14, "Pyramid 14", 3, 2},     {15, "Point", 0, 0},
      {16, "Quadrilateral 8", 2, 2}, {17, "Hexahedron 20", 3, 2},  {18, "Prism 15", 3, 2},
      {19, "Pyramid 13", 3, 2},
  }};
  for (const Known& known : kKnown) {
    if (known.type == type) return {known.name, known.dim, known.order};
  }
  return {fmt::format("element type {}", type), -1, 0};
}

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f'; }

/// The text of a .msh file as words, with the line of each for messages.
class MshText {
 public:
  MshText(std::string_view text, const std::string& source) : text_(text), source_(source) {}

  /// Whether nothing but white space is left.
  bool at_end() {
    skip_space();
    return pos_ == text_.size();
  }

  /// The next word; `expected` says what it should be, for the message if the text ends first.
  std::string_view word(std::string_view expected) {
    if (at_end()) fail(fmt::format("the file ends where {} was expected", expected));
    word_line_ = line_;
    const std::size_t begin = pos_;
    while (pos_ < text_.size() && !is_space(text_[pos_])) ++pos_;
    return text_.substr(begin, pos_ - begin);
  }

  void expect(std::string_view keyword) {
    const std::string_view got = word(keyword);
    if (got != keyword) fail(fmt::format("expected {}, got {}", keyword, quoted(got)));
  }

  /// An integer in [min, max]; `what` names it in messages.
  template <class T>
  T integer(std::string_view what, T min = std::numeric_limits<T>::min(), T max = std::numeric_limits<T>::max()) {
    const std::string_view got = word(what);
    T value{};
    const auto [end, error] = std::from_chars(got.data(), got.data() + got.size(), value);
    if (error != std::errc() || end != got.data() + got.size() || value < min || value > max) {
      fail(fmt::format("expected {} ({}), got {}", what, integer_range(min, max), quoted(got)));
    }
    return value;
  }

  /// A finite number; `what` names it in messages.
  double number(std::string_view what) {
    const std::string_view got = word(what);
    double value = 0.0;
    const auto [end, error] = std::from_chars(got.data(), got.data() + got.size(), value);
    if (error != std::errc() || end != got.data() + got.size() || !std::isfinite(value)) {
      fail(fmt::format("expected {} (a finite number), got {}", what, quoted(got)));
    }
    return value;
  }

  /// A name in double quotes, on one line.
  std::string quoted_name(std::string_view what) {
    const std::string_view first = word(what);
    if (first.front() != '"') fail(fmt::format("expected {} in double quotes, got {}", what, quoted(first)));
    const std::size_t open = pos_ - first.size();
    const std::size_t close = text_.find_first_of("\"\n", open + 1);
    if (close == std::string_view::npos || text_[close] != '"') {
      fail(fmt::format("expected {} in double quotes, closed on the same line", what));
    }
    pos_ = close + 1;
    return std::string(text_.substr(open + 1, close - open - 1));
  }

  /// "source:line" of the last word read.
  std::string where() const { return fmt::format("{}:{}", source_, word_line_); }
  std::size_t line() const { return word_line_; }

  [[noreturn]] void fail(const std::string& message) const { throw MeshError(where() + ": " + message); }

 private:
  void skip_space() {
    while (pos_ < text_.size() && is_space(text_[pos_])) {
      if (text_[pos_] == '\n') ++line_;
      ++pos_;
    }
  }

  /// "an integer >= 1", "an integer in [0, 3]": a bound at the type's limit goes unsaid.
  template <class T>
  static std::string integer_range(T min, T max) {
    const bool no_min = min == std::numeric_limits<T>::min(), no_max = max == std::numeric_limits<T>::max();
    if (no_min && no_max) return "an integer";
    if (no_max) return fmt::format("an integer >= {}", min);
    if (no_min) return fmt::format("an integer <= {}", max);
    return fmt::format("an integer in [{}, {}]", min, max);
  }

  static std::string quoted(std::string_view word) {
    return word.size() <= kMaxQuotedBytes ? fmt::format("{:?}", word)
                                          : fmt::format("{:?}...", word.substr(0, kMaxQuotedBytes));
  }

  std::string_view text_;
  const std::string& source_;
  std::size_t pos_ = 0;
  std::size_t line_ = 1;
  std::size_t word_line_ = 1;
};

const char* entity_name(int dim) {
  constexpr std::array<const char*, 4> kNames{"point", "curve", "surface", "volume"};
  return kNames[static_cast<std::size_t>(dim)];
}

int dimension(MshText& in) { return in.integer<int>("an entity dimension", kPointDim, kVolumeDim); }

Version read_format(MshText& in) {
  const std::string_view first = in.word("$MeshFormat");
  if (first == "$NOD") in.fail(fmt::format("MSH version 1 is not read; {}", kHowToSave));
  if (first != "$MeshFormat") in.fail("expected $MeshFormat: this is not a gmsh .msh file");
  const std::string_view version = in.word("the MSH version");
  Version out = Version::Msh41;
  if (version == "2" || version == "2.0" || version == "2.1" || version == "2.2") {
    out = Version::Msh2;
  } else if (version != "4.1") {
    in.fail(fmt::format("MSH version {:?} is not read; {}", version.substr(0, kMaxQuotedBytes), kHowToSave));
  }
  constexpr int kAscii = 0, kBinary = 1;
  if (in.integer<int>("the file type (0 for ASCII)", kAscii, kBinary) == kBinary) {
    in.fail(fmt::format("a binary .msh file is not read; {}", kHowToSave));
  }
  in.integer<int>("the size of a floating-point number", 1);
  in.expect("$EndMeshFormat");
  return out;
}

void read_physical_names(MshText& in, MshModel& model) {
  const auto count = in.integer<std::size_t>("the number of physical names");
  for (std::size_t i = 0; i < count; ++i) {
    const int dim = dimension(in);
    const int tag = in.integer<int>("a physical tag");
    const auto [name, added] = model.group_names.try_emplace({dim, tag}, in.quoted_name("a physical name"));
    if (!added) in.fail(fmt::format("physical {} group {} is named twice", entity_name(dim), tag));
  }
}

/// MSH 4.1 $Entities: points, curves, surfaces and volumes, each with its physical groups.
void read_entities(MshText& in, MshModel& model) {
  std::array<std::size_t, 4> counts{};
  for (int dim = kPointDim; dim <= kVolumeDim; ++dim) {
    counts[dim] = in.integer<std::size_t>(fmt::format("the number of {}s", entity_name(dim)));
  }
  constexpr int kPointCoordinates = 3, kBoxCoordinates = 6;
  for (int dim = kPointDim; dim <= kVolumeDim; ++dim) {
    for (std::size_t i = 0; i < counts[dim]; ++i) {
      const int tag = in.integer<int>(fmt::format("a {} tag", entity_name(dim)));
      const auto [entity, added] = model.entities.try_emplace({dim, tag});
      if (!added) in.fail(fmt::format("{} {} is listed twice", entity_name(dim), tag));
      const int coordinates = dim == kPointDim ? kPointCoordinates : kBoxCoordinates;
      for (int k = 0; k < coordinates; ++k) in.number(fmt::format("a coordinate of {} {}", entity_name(dim), tag));
      const auto groups = in.integer<std::size_t>("the number of physical tags");
      for (std::size_t g = 0; g < groups; ++g) entity->second.groups.insert(in.integer<int>("a physical tag"));
      if (dim == kPointDim) continue;
      const auto bounding = in.integer<std::size_t>("the number of bounding entities");
      for (std::size_t b = 0; b < bounding; ++b) in.integer<int>("a bounding entity tag");
    }
  }
}

/// A node's x, y, z, added under `tag`.
void read_node(MshText& in, std::size_t tag, MshModel& model) {
  std::array<double, 3> xyz{};
  for (double& coordinate : xyz) coordinate = in.number(fmt::format("a coordinate of node {}", tag));
  if (!model.nodes.emplace(tag, xyz).second) in.fail(fmt::format("node {} is defined twice", tag));
}

std::size_t node_tag(MshText& in) { return in.integer<std::size_t>("a node tag", 1); }

void check_total(MshText& in, std::string_view what, std::size_t announced, std::size_t read) {
  if (announced != read) in.fail(fmt::format("the section announces {} {}, its blocks hold {}", announced, what, read));
}

/// The head of an MSH 4.1 $Nodes or $Elements section of `item`s: the numbers of blocks and of
/// items (the smallest and largest tags that follow are not needed).
std::pair<std::size_t, std::size_t> read_blocks_head(MshText& in, std::string_view item) {
  const auto blocks = in.integer<std::size_t>(fmt::format("the number of {} blocks", item));
  const auto total = in.integer<std::size_t>(fmt::format("the number of {}s", item));
  in.integer<std::size_t>(fmt::format("the smallest {} tag", item));
  in.integer<std::size_t>(fmt::format("the largest {} tag", item));
  return {blocks, total};
}

void read_nodes_41(MshText& in, MshModel& model) {
  const auto [blocks, total] = read_blocks_head(in, "node");
  std::size_t read = 0;
  for (std::size_t b = 0; b < blocks; ++b) {
    const int dim = dimension(in);
    in.integer<int>("an entity tag");
    const bool parametric = in.integer<int>("0 or 1 (parametric)", 0, 1) == 1;
    const auto count = in.integer<std::size_t>("the number of nodes in the block");
    std::vector<std::size_t> tags;
    for (std::size_t i = 0; i < count; ++i) tags.push_back(node_tag(in));
    for (std::size_t tag : tags) {
      read_node(in, tag, model);
      for (int k = 0; parametric && k < dim; ++k) in.number(fmt::format("a parametric coordinate of node {}", tag));
    }
    read += count;
  }
  check_total(in, "nodes", total, read);
}

void read_nodes_2(MshText& in, MshModel& model) {
  const auto count = in.integer<std::size_t>("the number of nodes");
  for (std::size_t i = 0; i < count; ++i) read_node(in, node_tag(in), model);
}

/// The element type at hand, checked to be one ddafrac reads; returns its dimension.
int checked_element_type(MshText& in, int type) {
  const ElementKind kind = element_kind(type);
  if (kind.dim < 0) {
    in.fail(
        fmt::format("element type {} is not one ddafrac reads; expected triangles ({}) and quadrangles ({}), "
                    "lines ({}) and points ({})",
                    type, kTriangle3, kQuadrangle4, kLine2, kPoint1));
  }
  check_element_kind(type, kind, in.where());
  return kind.dim;
}

/// The nodes of one element of `type`, each checked to be defined and to be used once by the
/// element (a repeated corner makes a cell with an edge of length zero), appended to `nodes`.
void read_element_nodes(MshText& in, int type, std::size_t element, const MshModel& model,
                        std::vector<std::size_t>& nodes) {
  const std::size_t count = linear_node_count(type);
  const std::size_t first = nodes.size();
  for (std::size_t k = 0; k < count; ++k) {
    const std::size_t tag = node_tag(in);
    if (model.nodes.count(tag) == 0) {
      in.fail(fmt::format("element {} uses node {}, which $Nodes does not define", element, tag));
    }
    if (std::find(nodes.begin() + first, nodes.end(), tag) != nodes.end()) {
      in.fail(fmt::format("element {} uses node {} twice; expected {} distinct nodes", element, tag, count));
    }
    nodes.push_back(tag);
  }
}

void read_elements_41(MshText& in, MshModel& model) {
  const auto [blocks, total] = read_blocks_head(in, "element");
  std::size_t read = 0;
  for (std::size_t b = 0; b < blocks; ++b) {
    const int dim = dimension(in);
    const int tag = in.integer<int>("an entity tag");
    const int type = in.integer<int>("an element type");
    const int element_dim = checked_element_type(in, type);
    if (element_dim != dim) {
      in.fail(fmt::format("{} elements in {} {}; expected elements of dimension {} there", element_kind(type).name,
                          entity_name(dim), tag, dim));
    }
    const auto entity = model.entities.find({dim, tag});
    if (entity == model.entities.end()) {
      in.fail(fmt::format("elements of {} {}, which $Entities does not list", entity_name(dim), tag));
    }
    const auto count = in.integer<std::size_t>("the number of elements in the block");
    std::vector<std::size_t>& nodes = entity->second.elements[type];
    for (std::size_t e = 0; e < count; ++e) {
      read_element_nodes(in, type, in.integer<std::size_t>("an element tag"), model, nodes);
    }
    read += count;
  }
  check_total(in, "elements", total, read);
}

/// MSH 2.2 elements: "tag type number-of-tags physical-tag entity-tag ... nodes"; an entity
/// is in the physical groups its elements name (0 for none).
void read_elements_2(MshText& in, MshModel& model) {
  const auto count = in.integer<std::size_t>("the number of elements");
  for (std::size_t e = 0; e < count; ++e) {
    const auto element = in.integer<std::size_t>("an element tag");
    const int type = in.integer<int>("an element type");
    const int dim = checked_element_type(in, type);
    const auto tags = in.integer<std::size_t>("the number of element tags");
    std::array<int, 2> physical_and_entity{};
    for (std::size_t t = 0; t < tags; ++t) {
      const int value = in.integer<int>("an element tag (physical, entity, ...)");
      if (t < physical_and_entity.size()) physical_and_entity[t] = value;
    }
    const auto [physical, entity_tag] = physical_and_entity;
    MshEntity& entity = model.entities[{dim, entity_tag}];
    if (physical != 0) entity.groups.insert(physical);
    read_element_nodes(in, type, element, model, entity.elements[type]);
  }
}

/// Skips a section ddafrac does not use ($Periodic, $NodeData, $Comments, ...).
void skip_section(MshText& in, const std::string& name) {
  const std::size_t first_line = in.line();
  const std::string end = "$End" + name;
  while (!in.at_end()) {
    if (in.word(end) == end) return;
  }
  in.fail(fmt::format("no {} closes the ${} section of line {}", end, name, first_line));
}

}  // namespace

MshModel parse_msh_text(std::string_view text, const std::string& source) {
  MshText in(text, source);
  const Version version = read_format(in);
  MshModel model;
  std::set<std::string> seen{"MeshFormat"};
  while (!in.at_end()) {
    const std::string_view header = in.word("a section such as $Nodes");
    if (header.size() < 2 || header.front() != '$' || header.rfind("$End", 0) == 0) {
      in.fail(
          fmt::format("expected a section such as $Nodes or $Elements, got {:?}", header.substr(0, kMaxQuotedBytes)));
    }
    const std::string name(header.substr(1));
    if (!seen.insert(name).second) in.fail(fmt::format("a second ${} section", name));
    if (name == "PhysicalNames") {
      read_physical_names(in, model);
    } else if (name == "Entities" && version == Version::Msh41) {
      read_entities(in, model);
    } else if (name == "PartitionedEntities") {
      in.fail("a partitioned mesh is not read; save the mesh without partitions");
    } else if (name == "Nodes") {
      version == Version::Msh41 ? read_nodes_41(in, model) : read_nodes_2(in, model);
    } else if (name == "Elements") {
      if (seen.count("Nodes") == 0) in.fail("$Elements comes before $Nodes; expected the nodes first");
      version == Version::Msh41 ? read_elements_41(in, model) : read_elements_2(in, model);
    } else {
      skip_section(in, name);
      continue;
    }
    in.expect("$End" + name);
  }
  if (seen.count("Elements") == 0) throw MeshError(source + ": has no $Elements section");
  return model;
}

}  // namespace ddafrac::meshes::detail
