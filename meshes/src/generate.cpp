#include "ddafrac/meshes/generate.hpp"

#include <gmsh.h>

#include <algorithm>
#include <cmath>
#include <variant>

#include <fmt/format.h>

#include "ddafrac/meshes/msh_io.hpp"
#include "disc_model.hpp"
#include "gmsh_model_mesh.hpp"
#include "gmsh_session.hpp"
#include "quality_detail.hpp"

namespace ddafrac::meshes {

namespace {

constexpr int kGmshFrontalDelaunay = 6;       // Mesh.Algorithm; 8 (Frontal-Delaunay quads) crashes 4.8
constexpr int kGmshDelaunay = 5;
constexpr int kBlossomFullQuad = 3;           // Mesh.RecombinationAlgorithm
constexpr double kSizeGrowthRate = 0.4;       // m of size per m of distance from the slot ends
constexpr double kMinSizeExponent = 1.0;      // bounds of the fitted N ~ h^-p law
constexpr double kMaxSizeExponent = 3.0;
constexpr double kAreaExponent = 2.0;  // N ~ h^-2 for a uniform 2D mesh
/// Largest element size tried, as a fraction of the side of a square of the disc's area: larger
/// elements no longer resolve the disc, and the cell count stops falling well before (a slot's
/// graded ends keep hundreds of cells whatever the size far from them).
constexpr double kLargestSizePerModelSide = 1.0;

/// Edge length (m) of equilateral triangles that tile `area` (m^2) in `count` pieces.
double equilateral_size(double area, double count) { return std::sqrt(4.0 * area / (std::sqrt(3.0) * count)); }

/// Sizing: h everywhere, graded down to about the slot width near the slot ends so that the
/// short end faces do not make needle triangles.
class DiscSizing {
 public:
  DiscSizing(const detail::DiscModel& model, const MeshControl& control)
      : model_(model), slot_end_size_(control.slot_end_size_per_width * model.slot_width) {
    gmsh::option::setNumber("Mesh.Algorithm",
                            control.algorithm == MeshAlgorithm::Delaunay ? kGmshDelaunay : kGmshFrontalDelaunay);
    gmsh::option::setNumber("Mesh.MeshSizeFromPoints", 0);
    gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
    gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 0);
    if (model.slot_corners.empty()) return;
    const int distance = gmsh::model::mesh::field::add("Distance");
    gmsh::model::mesh::field::setNumbers(distance, "PointsList",
                                         std::vector<double>(model.slot_corners.begin(), model.slot_corners.end()));
    threshold_ = gmsh::model::mesh::field::add("Threshold");
    gmsh::model::mesh::field::setNumber(threshold_, "InField", distance);
    gmsh::model::mesh::field::setNumber(threshold_, "DistMin", 0.0);
    gmsh::model::mesh::field::setAsBackgroundMesh(threshold_);
  }

  void set(double size) const {
    gmsh::option::setNumber("Mesh.MeshSizeMax", size);
    if (threshold_ == 0) return;
    const double end_size = std::min(size, slot_end_size_);
    gmsh::model::mesh::field::setNumber(threshold_, "SizeMin", end_size);
    gmsh::model::mesh::field::setNumber(threshold_, "SizeMax", size);
    gmsh::model::mesh::field::setNumber(threshold_, "DistMax", (size - end_size) / kSizeGrowthRate);
  }

 private:
  const detail::DiscModel& model_;
  double slot_end_size_;  // m
  int threshold_ = 0;
};

/// Meshes the model with element size `size` and returns the number of cells in the disc.
std::size_t mesh_disc(const detail::DiscModel& model, const DiscSizing& sizing, double size) {
  gmsh::model::mesh::clear();
  sizing.set(size);
  gmsh::model::mesh::generate(2);
  std::vector<int> types;
  std::vector<std::vector<std::size_t>> element_tags, node_tags;
  gmsh::model::mesh::getElements(types, element_tags, node_tags, 2, model.surface);
  std::size_t count = 0;
  for (const auto& tags : element_tags) count += tags.size();
  if (count == 0) throw MeshError(fmt::format("gmsh made no cells at element size {} m", size));
  return count;
}

/// Secant step on log N = c - p log h, with p bounded; plain N ~ h^-2 until two samples exist.
class SizeSearch {
 public:
  SizeSearch(double first_size, double target, double largest_size)
      : size_(std::min(first_size, largest_size)), target_(target), largest_size_(largest_size) {}

  double size() const { return size_; }

  void record(std::size_t count) {
    double exponent = kAreaExponent;
    const double n = static_cast<double>(count);
    if (previous_count_ > 0.0 && previous_count_ != n) {
      exponent = -std::log(n / previous_count_) / std::log(size_ / previous_size_);
      exponent = std::clamp(exponent, kMinSizeExponent, kMaxSizeExponent);
    }
    previous_size_ = size_;
    previous_count_ = n;
    size_ = std::min(largest_size_, size_ * std::pow(n / target_, 1.0 / exponent));
  }

  /// At the largest size and still too many cells: no size gives fewer.
  bool at_floor(std::size_t count) const { return size_ >= largest_size_ && static_cast<double>(count) > target_; }

 private:
  double size_;
  double target_;
  double largest_size_;
  double previous_size_ = 0.0;
  double previous_count_ = 0.0;
};

bool within(std::size_t count, const MeshControl& control) {
  const double target = control.target_blocks;
  return std::abs(static_cast<double>(count) - target) <= control.block_tolerance * target;
}

void check_control(const MeshControl& control) {
  if (control.target_blocks < 1 || control.block_tolerance <= 0.0 || control.max_iterations < 1) {
    throw MeshError(
        fmt::format("invalid mesh control: target_blocks {} tolerance {} "
                    "max_iterations {}",
                    control.target_blocks, control.block_tolerance, control.max_iterations));
  }
}

/// The quality of the disc cells (or of every cell, for a file without a "disc" body).
QualityReport disc_quality(const Mesh& mesh) {
  const long disc = detail::body_index(mesh, "disc");
  return detail::quality_of_cells(mesh, [disc](Index b) { return disc < 0 || b == disc; });
}

void fill(QualityReport* report, const Mesh& mesh, double size, int iterations) {
  if (report == nullptr) return;
  *report = disc_quality(mesh);
  report->element_size = size;
  report->iterations = iterations;
}

/// A finite-element space of quadrilaterals cannot take a leftover triangle.
void require_all_quadrilaterals(const Mesh& mesh, double element_size) {
  constexpr std::size_t kQuadCorners = 4;
  for (std::size_t c = 0; c < mesh.cell_count(); ++c) {
    if (mesh.cell_size(c) != kQuadCorners) {
      throw MeshError(
          fmt::format("gmsh recombination left triangles at element size {} m; try "
                      "another size or triangles",
                      element_size));
    }
  }
}

Mesh read_user_file(const MshFile& file, QualityReport* report) {
  Mesh mesh = read_msh(file.path);
  fill(report, mesh, 0.0, 0);
  return mesh;
}

}  // namespace

Mesh generate_dda_mesh(const Geometry& geometry, const MeshControl& control, QualityReport* report) {
  if (const auto* file = std::get_if<MshFile>(&geometry)) return read_user_file(*file, report);
  check_control(control);
  detail::GmshSession session;
  return detail::gmsh_call("meshing the DDA disc", [&] {
    const detail::DiscModel model = detail::build_disc_model(geometry);
    const DiscSizing sizing(model, control);
    const double largest_size = kLargestSizePerModelSide * std::sqrt(model.area);
    SizeSearch search(equilateral_size(model.area, control.target_blocks), control.target_blocks, largest_size);
    std::size_t count = 0;
    double size = search.size();
    for (int iteration = 1; iteration <= control.max_iterations; ++iteration) {
      size = search.size();
      count = mesh_disc(model, sizing, size);
      if (within(count, control)) {
        Mesh mesh = detail::mesh_from_gmsh_model("generated disc mesh");
        fill(report, mesh, size, iteration);
        detail::append_rigid_bodies(geometry, mesh);
        return mesh;
      }
      if (search.at_floor(count))
        throw MeshError(fmt::format(
            "this geometry meshes into no fewer than about {} disc blocks (at element size "
            "{:.3g} m, the largest for a disc of {:.3g} m^2{}); mesh.blocks = {} asks for fewer",
            count, size, model.area, model.slot_corners.empty() ? "" : ": the slot's graded ends alone take hundreds",
            control.target_blocks));
      search.record(count);
    }
    throw MeshError(
        fmt::format("no element size gave {} +- {:.1f}% disc blocks in {} iterations "
                    "(last: {} blocks at {:.3g} m)",
                    control.target_blocks, 100.0 * control.block_tolerance, control.max_iterations, count, size));
  });
}

Mesh generate_fem_mesh(const Geometry& geometry, double element_size, FemCells cells, QualityReport* report) {
  if (const auto* file = std::get_if<MshFile>(&geometry)) return read_user_file(*file, report);
  if (!(element_size > 0.0)) {
    throw MeshError(fmt::format("invalid FEM element size {} m", element_size));
  }
  detail::GmshSession session;
  return detail::gmsh_call("meshing the FEM disc", [&] {
    const detail::DiscModel model = detail::build_disc_model(geometry);
    const DiscSizing sizing(model, MeshControl{});  // the default sizing: Frontal-Delaunay, tips at one slot width
    if (cells == FemCells::Quadrilaterals) {
      gmsh::option::setNumber("Mesh.RecombineAll", 1);
      gmsh::option::setNumber("Mesh.RecombinationAlgorithm", kBlossomFullQuad);
    }
    mesh_disc(model, sizing, element_size);
    Mesh mesh = detail::mesh_from_gmsh_model("generated FEM mesh");
    if (cells == FemCells::Quadrilaterals) require_all_quadrilaterals(mesh, element_size);
    fill(report, mesh, element_size, 1);
    return mesh;
  });
}

}  // namespace ddafrac::meshes
