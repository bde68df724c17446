// libFuzzer target: any bytes as the text of a user's .msh file, through what the app does with
// one (parse_msh: ddafrac's MSH 4.1/2.2 parser, the checks of groups, elements, plane and
// orientation; then the quality report). A MeshError is the reader's answer to a bad file;
// anything else (another exception, a crash, UB, a leak, a hang) is a finding, and so is an
// accepted mesh that breaks what the DDA relies on.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <set>
#include <string_view>

#include "ddafrac/meshes/generate.hpp"
#include "ddafrac/meshes/msh_io.hpp"
#include "mesh_checks.hpp"

namespace {

using namespace ddafrac::meshes;

/// Stops the fuzzer (a finding) unless `holds`.
void require(bool holds, const char* what) {
  if (holds) return;
  std::fprintf(stderr, "parse_msh accepted an invalid mesh: %s\n", what);
  std::abort();
}

/// What every cell and boundary edge of a mesh the reader accepts must be.
void check_accepted_mesh(const Mesh& mesh) {
  require(!mesh.body_names.empty(), "no body");
  require(mesh.cell_offsets.size() == mesh.cell_count() + 1 && mesh.cell_offsets.back() == mesh.cell_nodes.size(),
          "cell lists of different lengths");
  for (const Point& p : mesh.nodes)
    require(std::isfinite(p.x) && std::isfinite(p.y), "a coordinate that is not finite");
  for (std::size_t c = 0; c < mesh.cell_count(); ++c) {
    const std::size_t n = mesh.cell_size(c);
    require(n == 3 || n == 4, "a cell of neither 3 nor 4 nodes");
    require(mesh.cell_body[c] < mesh.body_names.size(), "a cell of no body");
    const std::set<Index> corners(mesh.cell_begin(c), mesh.cell_begin(c) + n);
    require(corners.size() == n, "a cell that uses a node twice");
    require(*corners.rbegin() < mesh.nodes.size(), "a cell on a node that does not exist");
    const double area = testing::cell_area(mesh, c);
    require(std::isfinite(area) && area > 0.0, "a cell whose area is not finite and positive (counter-clockwise)");
  }
  for (const BoundaryEdge& edge : mesh.boundary_edges) {
    require(edge.group < mesh.boundary_names.size() && edge.a < mesh.nodes.size() && edge.b < mesh.nodes.size(),
            "a boundary edge of no group or on a node that does not exist");
  }
  require(testing::misoriented_boundary_edges(mesh) == 0, "a boundary edge that is no cell edge in its direction");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const Mesh mesh = parse_msh(text, "fuzz_input.msh");
    check_accepted_mesh(mesh);
    measure_quality(mesh);
  } catch (const MeshError&) {
  }
  return 0;
}
