#pragma once
// Parametric descriptions of every scene geometry of the study. All lengths in metres, all
// angles in radians. The disc centre is at the origin in every generator.

#include <filesystem>
#include <optional>
#include <variant>

namespace ddafrac::meshes {

/// Plain disc. If load_half_angle > 0 the rim is split so that the two loaded arcs
/// (half-angle α about the top and bottom points) are boundary groups of their own
/// ("load_top", "load_bottom"), as needed for Hondros loading.
struct PlainDisc {
  double diameter = 0.1;
  double load_half_angle = 0.0;
};

/// A straight slot of given length and width through the disc centre, at an inclination
/// measured counter-clockwise from the x axis (boundary group "slit").
struct Slit {
  double length = 0.025;
  double width = 0.0004;
  double inclination = 0.0;
};

/// Disc with flats of central angle flat_angle cut at top and bottom, between two rectangular
/// platens of the given thickness and width, touching the flats (bodies "disc", "top_platen",
/// "bottom_platen"; boundary groups "flat_top", "flat_bottom", "rim"). With a slit, this is
/// the pre-cracked Brazilian disc of the study, loaded through its platens.
struct FlattenedDisc {
  double diameter = 0.1;
  double flat_angle = 0.17453292519943295;  // 10 degrees
  double platen_thickness = 0.02;
  double platen_width = 0.1;
  bool with_platens = true;  // the FEM model loads the flats directly and needs no platens
  std::optional<Slit> slit;
};

/// Pre-cracked Brazilian disc: a disc with a central slit.
struct SlitDisc {
  double diameter = 0.1;
  Slit slit;
};

/// Rockfall impact: a disc holding a pre-existing joint (a slit of length γ·D through the
/// centre at joint-slope angle θ) resting on a fixed rectangular plate whose top edge touches
/// the lowest point of the disc (bodies "disc", "plate"; boundary groups "rim", "joint",
/// "impact_patch" = the rim arc of half-angle patch_half_angle about the lowest point).
struct ImpactDisc {
  double diameter = 0.1;
  double joint_angle = 0.0;    // θ
  double connectivity = 0.25;  // γ = joint length / diameter, in (0, 1)
  double joint_width = 0.0004;
  double plate_width = 0.1;
  double plate_height = 0.02;
  double patch_half_angle = 0.05;
};

/// A user-supplied gmsh file with named physical groups.
struct MshFile {
  std::filesystem::path path;
};

using Geometry = std::variant<PlainDisc, FlattenedDisc, SlitDisc, ImpactDisc, MshFile>;

/// gmsh's 2-D algorithm for the DDA mesh. Frontal-Delaunay lays near-equilateral triangles in
/// rows whose edges line up into straight lines across the disc, and a crack running along block
/// edges can follow such a line; Delaunay gives less regular triangles whose edges line up less.
enum class MeshAlgorithm { FrontalDelaunay, Delaunay };

/// How fine to mesh. The DDA mesh is controlled by the number of triangles ("blocks") in the
/// disc; the generator iterates the element size until the count is within the tolerance.
struct MeshControl {
  int target_blocks = 2000;
  MeshAlgorithm algorithm = MeshAlgorithm::FrontalDelaunay;
  // Element size at the ends of slots and slits, in slot widths; the size grows from there to the
  // far-field size. The tips, where cracks start, keep this size whatever the block count, so a
  // mesh study that refines the tips must scale it too.
  double slot_end_size_per_width = 1.0;
  double block_tolerance = 0.02;  // relative; the study's counts must be hit within ±5%
  int max_iterations = 12;
};

}  // namespace ddafrac::meshes
