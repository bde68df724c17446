// Issue 5, test 5 (and issue 15 part 3): the same small static Hondros discs (triangles and
// quads, p = 2) and the same short impact response solved serially and with `mpirun -np 2`
// (each rank holding only its METIS part of the mesh, everything distributed; static: CG + AMG;
// dynamic: CHOLMOD serially, MUMPS distributed on 2 ranks; gauges and profile points evaluated
// by the rank that owns their cell) give the same stresses to the solver tolerance, and the two
// ranks' VTU pieces hold every cell once. Only rank 0 meshes, and its meshing error stops both.

#define BOOST_TEST_MODULE fem_mpi
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace {

// Static: CG stops at |r| <= 1e-10 |b| (SolverSettings default). The iterates of the two runs
// differ (another AMG hierarchy), so stresses agree to a small multiple of the tolerance
// (measured: 1.7e-11 triangles, 2.4e-11 quadrilaterals, of each case's stress scale).
// Dynamic: two direct solvers, so the histories agree to round-off grown over 60 steps
// (measured: 5.0e-13 gauges, 1.6e-13 energy).
constexpr double solver_tolerance = 1e-10;
constexpr double static_agreement = 10.0 * solver_tolerance;
constexpr double direct_agreement = 1e-11;

double agreement(const std::string& kind) { return kind.rfind("static", 0) == 0 ? static_agreement : direct_agreement; }

using Values = std::map<std::string, double>;  // "case,point,quantity" -> value

Values read_values(const std::filesystem::path& path) {
  std::ifstream in(path);
  BOOST_REQUIRE_MESSAGE(in, "cannot read " << path);
  Values out;
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    const auto last = line.rfind(',');
    out[line.substr(0, last)] = std::stod(line.substr(last + 1));
  }
  return out;
}

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  BOOST_REQUIRE_MESSAGE(in, path << " cannot be read");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

/// Values of `attribute="..."` in a text, in order.
std::vector<std::string> attributes(const std::string& text, const std::string& attribute) {
  std::vector<std::string> out;
  const std::string key = attribute + "=\"";
  for (auto at = text.find(key); at != std::string::npos; at = text.find(key, at + 1)) {
    const auto begin = at + key.size();
    out.push_back(text.substr(begin, text.find('"', begin) - begin));
  }
  return out;
}

/// Snapshot records (.pvtu) listed in DIR/run.pvd, and the cell count of each: the sum over
/// the pieces (one per rank) that the record lists.
std::vector<std::size_t> snapshot_cells(const std::filesystem::path& dir, std::size_t expected_pieces) {
  std::vector<std::size_t> out;
  for (const auto& file : attributes(read_text(dir / "run.pvd"), "file")) {
    const auto record = dir / file;
    BOOST_REQUIRE(record.extension() == ".pvtu");
    const auto pieces = attributes(read_text(record), "Source");
    BOOST_TEST(pieces.size() == expected_pieces);
    std::size_t cells = 0;
    for (const auto& piece : pieces)
      for (const auto& count : attributes(read_text(record.parent_path() / piece), "NumberOfCells"))
        cells += std::stoul(count);
    out.push_back(cells);
  }
  return out;
}

/// The first line of a text file.
std::string first_line(const std::filesystem::path& path) {
  const auto text = read_text(path);
  return text.substr(0, text.find('\n'));
}

const std::string two_ranks = std::string(MPIEXEC) + " -np 2 --oversubscribe";

/// The file fem_mpi_case's rank writes beside BASE: BASE.rankK.SUFFIX.
std::filesystem::path rank_file(const std::filesystem::path& base, int rank, const std::string& suffix) {
  return base.string() + ".rank" + std::to_string(rank) + "." + suffix;
}

Values run(const std::string& launcher, const std::filesystem::path& csv) {
  std::filesystem::remove(csv);
  for (const int rank : {0, 1}) std::filesystem::remove(rank_file(csv, rank, "mesh"));
  const std::string command = launcher + " \"" + FEM_MPI_CASE + "\" \"" + csv.string() + "\"";
  BOOST_TEST_MESSAGE("running " << command);
  const int status = std::system(command.c_str());
  BOOST_REQUIRE_MESSAGE(status == 0, command << " failed with status " << status);
  return read_values(csv);
}

}  // namespace

BOOST_AUTO_TEST_CASE(serial_and_two_ranks_agree) {
  const auto dir = std::filesystem::current_path() / "fem_mpi.out";
  std::filesystem::create_directories(dir);
  const Values serial = run("", dir / "serial.csv");
  const Values parallel = run(two_ranks, dir / "np2.csv");
  BOOST_REQUIRE_EQUAL(serial.size(), parallel.size());
  BOOST_REQUIRE_GT(serial.size(), 100u);

  // Stress scale per case: the largest magnitude in the serial run.
  std::map<std::string, double> scale, worst;
  for (const auto& [key, value] : serial) {
    const std::string kind = key.substr(0, key.find(','));
    scale[kind] = std::max(scale[kind], std::abs(value));
  }
  for (const auto& [key, value] : serial) {
    const auto it = parallel.find(key);
    BOOST_REQUIRE_MESSAGE(it != parallel.end(), "np 2 lacks " << key);
    const std::string kind = key.substr(0, key.find(','));
    const double difference = std::abs(it->second - value) / scale[kind];
    worst[kind] = std::max(worst[kind], difference);
    BOOST_TEST(difference < agreement(kind), key << ": serial " << value << ", np 2 " << it->second);
  }
  BOOST_REQUIRE_EQUAL(scale.size(), 4u);  // static_tri, static_quad, dynamic, energy

  // Snapshots at 0, 2, 4, 6 us; under MPI each rank writes its own cells, and together the
  // pieces hold every cell once.
  const auto cells_serial = snapshot_cells(dir / "serial_vtk", 1);
  const auto cells_np2 = snapshot_cells(dir / "np2_vtk", 2);
  BOOST_TEST(cells_serial.size() == 4u);
  BOOST_TEST(cells_np2 == cells_serial, boost::test_tools::per_element());
  for (const auto& [kind, w] : worst)
    BOOST_TEST_MESSAGE(kind << ": largest |serial - np 2| / scale = " << w << " (scale " << scale[kind] << ")");

  // Only rank 0 meshed: rank 1 got its part of the triangulation, never the whole mesh.
  const auto serial_nodes = std::stoul(first_line(rank_file(dir / "serial.csv", 0, "mesh")));
  BOOST_TEST(serial_nodes > 100u);
  BOOST_TEST(std::stoul(first_line(rank_file(dir / "np2.csv", 0, "mesh"))) == serial_nodes);
  BOOST_TEST(std::stoul(first_line(rank_file(dir / "np2.csv", 1, "mesh"))) == 0u);
}

// A mesh that cannot be made on rank 0 is an error on every rank, not a rank left waiting in
// a collective call for a mesh that never comes (the test's TIMEOUT would catch a hang).
BOOST_AUTO_TEST_CASE(a_meshing_error_on_the_first_rank_stops_every_rank) {
  const auto dir = std::filesystem::current_path() / "fem_mpi.out";
  std::filesystem::create_directories(dir);
  const auto out = dir / "mesh_error";
  for (const int rank : {0, 1}) std::filesystem::remove(rank_file(out, rank, "error"));
  const std::string command = two_ranks + " \"" + FEM_MPI_CASE + "\" --mesh-error \"" + out.string() + "\"";
  BOOST_TEST(std::system(command.c_str()) != 0);
  for (const int rank : {0, 1}) BOOST_TEST(first_line(rank_file(out, rank, "error")) == "the test's generator fails");
}
