// .msh files: ASCII 4.1 round trip of generated meshes, reorientation of clockwise cells, and
// a clear error (file name + reason) for every kind of file we cannot use.
#define BOOST_TEST_MODULE meshes_msh_io
#include <boost/test/unit_test.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <unistd.h>

#include "ddafrac/meshes/generate.hpp"
#include "ddafrac/meshes/msh_io.hpp"
#include "mesh_checks.hpp"

using namespace ddafrac::meshes;
using namespace ddafrac::meshes::testing;
namespace fs = std::filesystem;

namespace {

constexpr double kRoundTripTolerance = 1e-12;  // m

struct TempDir {
  fs::path path = fs::temp_directory_path() / ("ddafrac_msh_" + std::to_string(::getpid()));
  TempDir() { fs::create_directories(path); }
  ~TempDir() { fs::remove_all(path); }
  fs::path file(const std::string& name, const std::string& text) const {
    std::ofstream(path / name) << text;
    return path / name;
  }
};

std::string read_text(const fs::path& path) {
  std::ostringstream text;
  text << std::ifstream(path).rdbuf();
  return text.str();
}

// A unit square of two triangles in msh 2.2, the pieces varied by the error cases.
const std::string kFormat = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n";
const std::string kNames = "$PhysicalNames\n2\n1 1 \"rim\"\n2 2 \"disc\"\n$EndPhysicalNames\n";
std::string nodes(double z3 = 0.0) {
  return "$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 1 1 " + std::to_string(z3) + "\n4 0 1 0\n$EndNodes\n";
}
// elm-number elm-type number-of-tags physical elementary node-list
const std::string kTriangles = "1 2 2 2 1 1 2 3\n2 2 2 2 1 1 3 4\n";
std::string elements(const std::string& lines) {
  std::istringstream in(lines);
  std::string line;
  int count = 0;
  while (std::getline(in, line)) ++count;
  return "$Elements\n" + std::to_string(count) + "\n" + lines + "$EndElements\n";
}

void check_error(const fs::path& file, const std::string& reason) {
  BOOST_TEST_CONTEXT(file.filename().string()) {
    try {
      read_msh(file);
      BOOST_ERROR("no MeshError for " << file);
    } catch (const MeshError& e) {
      const std::string message = e.what();
      BOOST_TEST_MESSAGE(message);
      BOOST_TEST(message.find(file.string()) != std::string::npos);
      BOOST_TEST(message.find(reason) != std::string::npos, "'" << message << "' lacks '" << reason << "'");
    }
  }
}

}  // namespace

BOOST_AUTO_TEST_CASE(round_trip_of_generated_meshes) {
  TempDir dir;
  MeshControl control;
  control.target_blocks = 2000;
  FlattenedDisc precracked;
  precracked.slit = Slit{};
  const Mesh quads = generate_fem_mesh(SlitDisc{}, 0.004, FemCells::Quadrilaterals);
  for (const Mesh& mesh : {generate_dda_mesh(ImpactDisc{}, control), generate_dda_mesh(precracked, control), quads}) {
    const fs::path path = dir.path / "mesh.msh";
    write_msh(mesh, path);
    BOOST_TEST(read_text(path).rfind("$MeshFormat\n4.1 0 8\n", 0) == 0u);  // ASCII 4.1
    BOOST_TEST(!fs::exists(dir.path / ".mesh.partial.msh"));
    const Mesh back = read_msh(path);
    BOOST_TEST(same_mesh(mesh, back, kRoundTripTolerance));
    BOOST_TEST(back.boundary_names.size() == mesh.boundary_names.size());
  }
}

BOOST_AUTO_TEST_CASE(a_valid_hand_written_file_with_clockwise_cells) {
  TempDir dir;
  const std::string clockwise = "1 2 2 2 1 1 3 2\n2 2 2 2 1 1 4 3\n3 1 2 1 2 1 2\n";
  const Mesh mesh = read_msh(dir.file("clockwise.msh", kFormat + kNames + nodes() + elements(clockwise)));
  BOOST_TEST(mesh.cell_count() == 2u);
  BOOST_TEST(smallest_relative_area(mesh) > 0.0);  // reoriented
  BOOST_TEST(body_area(mesh, "disc") == 1.0, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(mesh.boundary_names == std::vector<std::string>{"rim"}, boost::test_tools::per_element());
  BOOST_TEST(misoriented_boundary_edges(mesh) == 0u);
}

BOOST_AUTO_TEST_CASE(missing_file) { check_error("/nonexistent/ddafrac/none.msh", "no such file"); }

BOOST_AUTO_TEST_CASE(three_dimensional_elements) {
  TempDir dir;
  const std::string nodes_3d = "$Nodes\n5\n1 0 0 0\n2 1 0 0\n3 1 1 0\n4 0 1 0\n5 0 0 1\n$EndNodes\n";
  check_error(dir.file("tet.msh", kFormat + kNames + nodes_3d + elements(kTriangles + "3 4 2 2 2 1 2 3 5\n")),
              "3D elements");
}

BOOST_AUTO_TEST_CASE(second_order_elements) {
  TempDir dir;
  const std::string nodes_p2 =
      "$Nodes\n7\n1 0 0 0\n2 1 0 0\n3 1 1 0\n4 0 1 0\n5 0.5 0 0\n6 1 0.5 0\n7 0.5 0.5 0\n"
      "$EndNodes\n";
  check_error(dir.file("p2.msh", kFormat + kNames + nodes_p2 + elements("1 9 2 2 1 1 2 3 5 6 7\n")),
              "second-order (curved) elements");
}

BOOST_AUTO_TEST_CASE(no_physical_surface_groups) {
  TempDir dir;
  const std::string no_groups = "1 2 2 0 1 1 2 3\n2 2 2 0 1 1 3 4\n";
  check_error(dir.file("nogroups.msh", kFormat + nodes() + elements(no_groups)), "no physical surface groups");
}

BOOST_AUTO_TEST_CASE(unnamed_physical_group) {
  TempDir dir;
  check_error(dir.file("unnamed.msh", kFormat + nodes() + elements(kTriangles)), "has no name");
}

BOOST_AUTO_TEST_CASE(nodes_off_the_plane) {
  TempDir dir;
  check_error(dir.file("offplane.msh", kFormat + kNames + nodes(0.01) + elements(kTriangles)), "off the plane z = 0");
}

BOOST_AUTO_TEST_CASE(not_a_mesh_file) {
  TempDir dir;
  check_error(dir.file("garbage.msh", "this is not a gmsh file\n"), "garbage.msh:1: expected $MeshFormat");
  check_error(dir.file("empty.msh", ""), "the file ends where $MeshFormat was expected");
}

// ddafrac reads .msh files itself (gmsh's reader crashes on malformed ones): every error names
// the line and what was expected there.
BOOST_AUTO_TEST_CASE(versions_and_encodings_it_does_not_read) {
  TempDir dir;
  check_error(dir.file("v40.msh", "$MeshFormat\n4 0 8\n$EndMeshFormat\n"), "v40.msh:2: MSH version \"4\" is not read");
  check_error(dir.file("binary.msh", "$MeshFormat\n4.1 1 8\n"), "binary.msh:2: a binary .msh file is not read");
  check_error(dir.file("v1.msh", "$NOD\n1\n1 0 0 0\n$ENDNOD\n"), "v1.msh:1: MSH version 1 is not read");
}

BOOST_AUTO_TEST_CASE(malformed_sections_are_refused_with_their_line) {
  TempDir dir;
  const std::string undefined_node = "1 2 2 2 1 1 2 9\n";
  check_error(dir.file("undefined.msh", kFormat + kNames + nodes() + elements(undefined_node)),
              "undefined.msh:18: element 1 uses node 9, which $Nodes does not define");
  check_error(dir.file("short.msh", kFormat + kNames + "$Nodes\n4\n1 0 0 0\n$EndNodes\n"),
              "short.msh:12: expected a node tag (an integer >= 1), got \"$EndNodes\"");
  check_error(dir.file("nan.msh", kFormat + kNames + "$Nodes\n1\n1 nan 0 0\n$EndNodes\n"),
              "nan.msh:11: expected a coordinate of node 1 (a finite number), got \"nan\"");
  check_error(dir.file("twice.msh", kFormat + kNames + nodes() + nodes() + elements(kTriangles)),
              "twice.msh:16: a second $Nodes section");
  check_error(dir.file("order.msh", kFormat + kNames + elements(kTriangles) + nodes()),
              "order.msh:9: $Elements comes before $Nodes");
  check_error(dir.file("unclosed.msh", kFormat + "$Comments\nno end\n"),
              "no $EndComments closes the $Comments section");
  check_error(dir.file("noelements.msh", kFormat + kNames + nodes()), "has no $Elements section");
  check_error(dir.file("repeated.msh", kFormat + kNames + nodes() + elements("1 3 2 2 1 1 2 3 3\n")),
              "repeated.msh:18: element 1 uses node 3 twice; expected 4 distinct nodes");
  check_error(dir.file("type.msh", kFormat + kNames + nodes() + elements("1 99 2 2 1 1 2 3\n")),
              "type.msh:18: element type 99 is not one ddafrac reads");
}

// MSH 4.1 names the entity of every block: a block of lines in a surface (which gmsh would
// have taken as cells of four nodes) is refused.
BOOST_AUTO_TEST_CASE(msh41_blocks_of_the_wrong_dimension_or_entity) {
  TempDir dir;
  const std::string head =
      "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"
      "$PhysicalNames\n1\n2 1 \"disc\"\n$EndPhysicalNames\n"
      "$Entities\n0 0 1 0\n1 0 0 0 1 1 0 1 1 0\n$EndEntities\n"
      "$Nodes\n1 3 1 3\n2 1 0 3\n1\n2\n3\n0 0 0\n1 0 0\n0 1 0\n$EndNodes\n";
  const Mesh mesh = read_msh(dir.file("good.msh", head + "$Elements\n1 1 1 1\n2 1 2 1\n1 1 2 3\n$EndElements\n"));
  BOOST_TEST(mesh.cell_count() == 1u);
  check_error(dir.file("lines.msh", head + "$Elements\n1 1 1 1\n2 1 1 1\n1 1 2\n$EndElements\n"),
              "lines.msh:24: Line 2 elements in surface 1; expected elements of dimension 2 there");
  check_error(dir.file("entity.msh", head + "$Elements\n1 1 1 1\n2 7 2 1\n1 1 2 3\n$EndElements\n"),
              "entity.msh:24: elements of surface 7, which $Entities does not list");
  check_error(dir.file("count.msh", head + "$Elements\n1 2 1 2\n2 1 2 1\n1 1 2 3\n$EndElements\n"),
              "count.msh:25: the section announces 2 elements, its blocks hold 1");
}

BOOST_AUTO_TEST_CASE(msh_file_geometry_is_read_and_written_files_are_reproducible) {
  TempDir dir;
  MeshControl control;
  control.target_blocks = 1000;
  const fs::path first = dir.path / "first.msh", second = dir.path / "second.msh";
  write_msh(generate_dda_mesh(SlitDisc{}, control), first);
  write_msh(generate_dda_mesh(SlitDisc{}, control), second);
  BOOST_TEST(read_text(first) == read_text(second));  // same input, byte-identical file

  QualityReport report;
  const Mesh mesh = generate_dda_mesh(MshFile{first}, control, &report);
  BOOST_TEST(same_mesh(mesh, read_msh(first), 0.0));
  BOOST_TEST(report.blocks == body_cells(mesh, "disc"));
  BOOST_TEST(report.min_angle_deg > 0.0);
}
