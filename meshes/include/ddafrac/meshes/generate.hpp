#pragma once
// gmsh-based meshing of the scene geometries. Deterministic: the same input gives the same mesh.
// gmsh keeps global state: call these functions (and write_msh) from one thread at a
// time; each call initialises and finalises gmsh itself.

#include <stdexcept>
#include <string>

#include "ddafrac/meshes/geometry.hpp"
#include "ddafrac/meshes/mesh.hpp"

namespace ddafrac::meshes {

/// Thrown for geometry that cannot be built or meshed, and for .msh files that cannot be read
/// (the message says which file/entity and what was expected).
class MeshError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct QualityReport {
  std::size_t blocks = 0;           // cells of the meshed (triangulated) bodies
  double min_angle_deg = 0.0;       // smallest interior angle over those cells
  double mean_min_angle_deg = 0.0;  // mean over cells of each cell's smallest angle
  double element_size = 0.0;        // m, the gmsh size that hit the target
  int iterations = 0;               // sizing iterations used
};

/// Triangles for the DDA: the disc is triangulated (every triangle a block); platens and the
/// plate are single polygon cells (rigid-ish blocks of their own).
Mesh generate_dda_mesh(const Geometry& geometry, const MeshControl& control, QualityReport* report = nullptr);

enum class FemCells { Triangles, Quadrilaterals };

/// The same geometry for the FEM: the disc only (no platens/plate), with the boundary groups,
/// meshed with the given element size (m) as triangles or gmsh-recombined quadrilaterals.
Mesh generate_fem_mesh(const Geometry& geometry, double element_size, FemCells cells, QualityReport* report = nullptr);

QualityReport measure_quality(const Mesh& mesh, const std::string& body = "disc");

}  // namespace ddafrac::meshes
