#include "disc_model.hpp"

#include <gmsh.h>

#include <cmath>
#include <map>
#include <optional>
#include <string>
#include <variant>

#include <fmt/format.h>

#include "ddafrac/common/angles.hpp"
#include "ddafrac/meshes/generate.hpp"

namespace ddafrac::meshes::detail {

namespace {

using common::kPi;
constexpr double kMaxArcAngle = kPi / 2;  // rad; gmsh circle arcs must stay below pi
constexpr double kSnapToAxis = 1e-15;     // relative; cos(pi/2) is not exactly zero
constexpr double kSlotClearance = 0.02;   // slot corners stay this fraction of R inside the rim
constexpr double kAngleRoundOff = 1e-9;   // rad; an arc of exactly k * kMaxArcAngle needs k pieces

enum class Segment { Arc, Chord };

/// One piece of the rim, from the end of the previous piece counter-clockwise to end_angle.
struct RimPiece {
  double end_angle;  // rad
  Segment kind;
  const char* group;
};

/// Adds gmsh entities for the disc outline, the slot and the physical groups.
class DiscBuilder {
 public:
  explicit DiscBuilder(double radius) : radius_(radius) { centre_ = gmsh::model::geo::addPoint(0.0, 0.0, 0.0); }

  /// The rim as pieces starting at start_angle and closing after a full turn.
  int rim_loop(double start_angle, const std::vector<RimPiece>& pieces) {
    std::vector<int> curves;
    const int first = rim_point(start_angle);
    int from = first;
    double from_angle = start_angle;
    for (std::size_t i = 0; i < pieces.size(); ++i) {
      const RimPiece& piece = pieces[i];
      const int to = i + 1 == pieces.size() ? first : rim_point(piece.end_angle);
      if (piece.kind == Segment::Chord) {
        add_curve(gmsh::model::geo::addLine(from, to), piece.group, curves);
      } else {
        add_arc(from, from_angle, to, piece.end_angle, piece.group, curves);
      }
      from = to;
      from_angle = piece.end_angle;
    }
    return gmsh::model::geo::addCurveLoop(curves);
  }

  /// A rectangular slot of length x width through the centre, at the given inclination.
  int slot_loop(const Slit& slot, const char* group, std::vector<int>& corners) {
    const double c = std::cos(slot.inclination), s = std::sin(slot.inclination);
    const double half_length = slot.length / 2, half_width = slot.width / 2;
    const double along[4] = {-half_length, half_length, half_length, -half_length};
    const double across[4] = {-half_width, -half_width, half_width, half_width};
    for (int k = 0; k < 4; ++k) {
      corners.push_back(gmsh::model::geo::addPoint(along[k] * c - across[k] * s, along[k] * s + across[k] * c, 0.0));
    }
    std::vector<int> curves;
    for (int k = 0; k < 4; ++k) {
      add_curve(gmsh::model::geo::addLine(corners[k], corners[(k + 1) % 4]), group, curves);
    }
    // The hole's loop runs clockwise as seen from the disc, opposite to the rim.
    std::vector<int> reversed(curves.rbegin(), curves.rend());
    for (int& curve : reversed) curve = -curve;
    return gmsh::model::geo::addCurveLoop(reversed);
  }

  int surface(const std::vector<int>& loops) {
    const int tag = gmsh::model::geo::addPlaneSurface(loops);
    gmsh::model::geo::synchronize();
    const int body = gmsh::model::addPhysicalGroup(2, {tag});
    gmsh::model::setPhysicalName(2, body, "disc");
    for (const auto& [name, tags] : groups_) {
      const int group = gmsh::model::addPhysicalGroup(1, tags);
      gmsh::model::setPhysicalName(1, group, name);
    }
    return tag;
  }

 private:
  int rim_point(double angle) const {
    return gmsh::model::geo::addPoint(snap(radius_ * std::cos(angle)), snap(radius_ * std::sin(angle)), 0.0);
  }

  double snap(double coordinate) const { return std::abs(coordinate) < kSnapToAxis * radius_ ? 0.0 : coordinate; }

  /// An arc split into pieces short enough for gmsh's three-point circle arcs.
  void add_arc(int from, double from_angle, int to, double to_angle, const char* group, std::vector<int>& curves) {
    const int pieces = static_cast<int>(std::ceil((to_angle - from_angle - kAngleRoundOff) / kMaxArcAngle));
    const double step = (to_angle - from_angle) / pieces;
    for (int k = 1; k <= pieces; ++k) {
      const int next = k == pieces ? to : rim_point(from_angle + k * step);
      add_curve(gmsh::model::geo::addCircleArc(from, centre_, next), group, curves);
      from = next;
    }
  }

  void add_curve(int tag, const char* group, std::vector<int>& curves) {
    curves.push_back(tag);
    groups_[group].push_back(tag);
  }

  double radius_;
  int centre_ = 0;
  std::map<std::string, std::vector<int>> groups_;
};

void require(bool condition, const std::string& what) {
  if (!condition) throw MeshError("invalid geometry: " + what);
}

void check_slot(double radius, const Slit& slot, const char* name) {
  require(slot.length > 0.0 && slot.width > 0.0, fmt::format("{} length and width must be positive", name));
  const double corner_radius = std::hypot(slot.length / 2, slot.width / 2);
  require(
      corner_radius < (1.0 - kSlotClearance) * radius,
      fmt::format("{} ({} m x {} m) must lie inside the disc of radius {} m", name, slot.length, slot.width, radius));
}

/// A disc outline: the rim from start_angle round in pieces, an optional central slot, and the
/// analytic area of the full disc minus whatever the rim pieces cut off (flats).
struct Outline {
  double diameter = 0.0;
  double start_angle = 0.0;
  std::vector<RimPiece> rim;
  double area_without_slot = 0.0;  // m^2
  std::optional<Slit> slot;
  const char* slot_group = "slit";
};

double disc_area(double diameter) { return kPi * diameter * diameter / 4; }

DiscModel build_outline(const Outline& outline) {
  require(outline.diameter > 0.0, "disc diameter must be positive");
  DiscBuilder builder(outline.diameter / 2);
  std::vector<int> loops{builder.rim_loop(outline.start_angle, outline.rim)};
  DiscModel model;
  model.area = outline.area_without_slot;
  if (outline.slot) {
    check_slot(outline.diameter / 2, *outline.slot, outline.slot_group);
    loops.push_back(builder.slot_loop(*outline.slot, outline.slot_group, model.slot_corners));
    model.slot_width = outline.slot->width;
    model.area -= outline.slot->length * outline.slot->width;
  }
  model.surface = builder.surface(loops);
  return model;
}

Outline full_rim(double diameter) {
  return {diameter, -kPi / 2, {{3 * kPi / 2, Segment::Arc, "rim"}}, disc_area(diameter), {}};
}

DiscModel build(const PlainDisc& disc) {
  require(disc.load_half_angle >= 0.0 && disc.load_half_angle < kPi / 4, "load half-angle must lie in [0, pi/4)");
  Outline outline = full_rim(disc.diameter);
  if (const double a = disc.load_half_angle; a > 0.0) {
    outline.start_angle = -kPi / 2 + a;
    outline.rim = {{kPi / 2 - a, Segment::Arc, "rim"},
                   {kPi / 2 + a, Segment::Arc, "load_top"},
                   {3 * kPi / 2 - a, Segment::Arc, "rim"},
                   {3 * kPi / 2 + a, Segment::Arc, "load_bottom"}};
  }
  return build_outline(outline);
}

/// Flats of central angle phi cut off two circular segments of area R^2/2 (phi - sin phi).
DiscModel build(const FlattenedDisc& disc) {
  require(disc.flat_angle > 0.0 && disc.flat_angle < kPi / 2, "flat angle must lie in (0, pi/2)");
  const double r = disc.diameter / 2, b = disc.flat_angle / 2;
  const double segment_area = r * r / 2 * (disc.flat_angle - std::sin(disc.flat_angle));
  return build_outline({disc.diameter,
                        -kPi / 2 + b,
                        {{kPi / 2 - b, Segment::Arc, "rim"},
                         {kPi / 2 + b, Segment::Chord, "flat_top"},
                         {3 * kPi / 2 - b, Segment::Arc, "rim"},
                         {3 * kPi / 2 + b, Segment::Chord, "flat_bottom"}},
                        disc_area(disc.diameter) - 2 * segment_area,
                        disc.slit,
                        "slit"});
}

DiscModel build(const SlitDisc& disc) {
  Outline outline = full_rim(disc.diameter);
  outline.slot = disc.slit;
  return build_outline(outline);
}

DiscModel build(const ImpactDisc& disc) {
  require(disc.connectivity > 0.0 && disc.connectivity < 1.0, "connectivity must lie in (0, 1)");
  require(disc.patch_half_angle > 0.0 && disc.patch_half_angle < kPi / 4,
          "impact patch half-angle must lie in (0, pi/4)");
  require(disc.plate_width > 0.0 && disc.plate_height > 0.0, "plate size must be positive");
  const double p = disc.patch_half_angle;
  // The patch is split at the lowest point so that (0, -R) is a node of the mesh.
  return build_outline({disc.diameter,
                        -kPi / 2 + p,
                        {{3 * kPi / 2 - p, Segment::Arc, "rim"},
                         {3 * kPi / 2, Segment::Arc, "impact_patch"},
                         {3 * kPi / 2 + p, Segment::Arc, "impact_patch"}},
                        disc_area(disc.diameter),
                        Slit{disc.connectivity * disc.diameter, disc.joint_width, disc.joint_angle},
                        "joint"});
}

DiscModel build(const MshFile& file) {
  throw MeshError("a .msh file (" + file.path.string() + ") is read, not generated");
}

/// One rectangular cell with four nodes of its own, counter-clockwise.
void append_rectangle(Mesh& mesh, const std::string& body, double x0, double y0, double x1, double y1) {
  const auto first = static_cast<Index>(mesh.nodes.size());
  mesh.nodes.insert(mesh.nodes.end(), {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}});
  for (Index k = 0; k < 4; ++k) mesh.cell_nodes.push_back(first + k);
  mesh.cell_offsets.push_back(mesh.cell_offsets.back() + 4);
  mesh.cell_body.push_back(static_cast<Index>(mesh.body_names.size()));
  mesh.body_names.push_back(body);
}

}  // namespace

DiscModel build_disc_model(const Geometry& geometry) {
  return std::visit([](const auto& g) { return build(g); }, geometry);
}

void append_rigid_bodies(const Geometry& geometry, Mesh& mesh) {
  if (const auto* disc = std::get_if<FlattenedDisc>(&geometry); disc && disc->with_platens) {
    require(disc->platen_thickness > 0.0 && disc->platen_width > 0.0, "platen size must be positive");
    const double flat_y = disc->diameter / 2 * std::cos(disc->flat_angle / 2);
    const double half_width = disc->platen_width / 2;
    append_rectangle(mesh, "top_platen", -half_width, flat_y, half_width, flat_y + disc->platen_thickness);
    append_rectangle(mesh, "bottom_platen", -half_width, -flat_y - disc->platen_thickness, half_width, -flat_y);
  } else if (const auto* impact = std::get_if<ImpactDisc>(&geometry)) {
    const double bottom = -impact->diameter / 2;
    append_rectangle(mesh, "plate", -impact->plate_width / 2, bottom - impact->plate_height, impact->plate_width / 2,
                     bottom);
  }
}

}  // namespace ddafrac::meshes::detail
