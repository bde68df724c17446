#pragma once
// The disc of each scene as a gmsh model (built-in kernel): rim segments, optional flats and a
// central slot, with named physical groups. Platens and the impact plate are not meshed by
// gmsh: each is one rectangular cell, appended by append_rigid_bodies().

#include <vector>

#include "ddafrac/meshes/geometry.hpp"
#include "ddafrac/meshes/mesh.hpp"

namespace ddafrac::meshes::detail {

/// What the mesh sizing needs to know about the model that was built.
struct DiscModel {
  int surface = 0;                // gmsh tag of the disc surface
  std::vector<int> slot_corners;  // gmsh point tags of the slot corners (empty: no slot)
  double slot_width = 0.0;        // m
  double area = 0.0;              // m^2, analytic area of the meshed disc
};

/// Builds the disc of `geometry` into the current (empty) gmsh model and synchronises it.
/// Throws MeshError for invalid dimensions. MshFile is not a parametric geometry: not accepted.
DiscModel build_disc_model(const Geometry& geometry);

/// Appends the single-cell rigid bodies (platens, plate) that the DDA scene has beside the disc.
void append_rigid_bodies(const Geometry& geometry, Mesh& mesh);

}  // namespace ddafrac::meshes::detail
