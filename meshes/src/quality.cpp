#include <algorithm>
#include <string>

#include "cell_geometry.hpp"
#include "ddafrac/meshes/generate.hpp"
#include "quality_detail.hpp"

namespace ddafrac::meshes {

namespace detail {

QualityReport quality_of_cells(const Mesh& mesh, const std::function<bool(Index)>& include) {
  QualityReport report;
  double sum_of_min_angles = 0.0;
  double smallest = 180.0;  // degrees
  for (std::size_t c = 0; c < mesh.cell_count(); ++c) {
    if (!include(mesh.cell_body[c])) continue;
    const double angle = min_interior_angle_deg(mesh, c);
    smallest = std::min(smallest, angle);
    sum_of_min_angles += angle;
    ++report.blocks;
  }
  if (report.blocks > 0) {
    report.min_angle_deg = smallest;
    report.mean_min_angle_deg = sum_of_min_angles / static_cast<double>(report.blocks);
  }
  return report;
}

long body_index(const Mesh& mesh, const std::string& name) {
  const auto found = std::find(mesh.body_names.begin(), mesh.body_names.end(), name);
  return found == mesh.body_names.end() ? -1 : found - mesh.body_names.begin();
}

}  // namespace detail

QualityReport measure_quality(const Mesh& mesh, const std::string& body) {
  const long index = detail::body_index(mesh, body);
  if (index < 0) throw MeshError("measure_quality: the mesh has no body named \"" + body + "\"");
  return detail::quality_of_cells(mesh, [index](Index b) { return b == index; });
}

}  // namespace ddafrac::meshes
