#include "ddafrac/meshes/picture.hpp"

#include <cairo.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <string>

#include <fmt/format.h>

#include "ddafrac/common/whole_file.hpp"
#include "ddafrac/meshes/generate.hpp"

namespace ddafrac::meshes {

namespace {

constexpr double kMarginPerWidth = 0.03;  // blank border, fraction of the picture width
constexpr double kCellEdgePx = 0.5;       // line width of cell edges, pixels
constexpr double kThickGroupPx = 3.0;     // line width of slit/joint faces, pixels
constexpr double kChannelMax = 255.0;
constexpr std::array<Rgb, 6> kBodyPalette{{{222, 184, 135},    // disc: burlywood
                                           {112, 128, 144},    // slate grey
                                           {70, 130, 180},     // steel blue
                                           {143, 188, 143},    // sea green
                                           {218, 165, 32},     // goldenrod
                                           {188, 143, 143}}};  // rosy brown
constexpr Rgb kCellEdgeColour{60, 60, 60};
constexpr Rgb kThickGroupColour{220, 20, 60};  // crimson
constexpr std::array<const char*, 2> kThickGroups{"slit", "joint"};

struct Bounds {
  double xmin = HUGE_VAL, ymin = HUGE_VAL, xmax = -HUGE_VAL, ymax = -HUGE_VAL;
};

Bounds bounds_of(const Mesh& mesh) {
  Bounds b;
  for (const Point& p : mesh.nodes) {
    b.xmin = std::min(b.xmin, p.x);
    b.xmax = std::max(b.xmax, p.x);
    b.ymin = std::min(b.ymin, p.y);
    b.ymax = std::max(b.ymax, p.y);
  }
  return b;
}

/// Maps model coordinates (m, y up) to pixels (y down), preserving the aspect ratio.
struct View {
  double scale = 1.0;   // px per m
  double margin = 0.0;  // px
  Bounds bounds;
  int width = 0, height = 0;

  View(const Mesh& mesh, int width_px) : bounds(bounds_of(mesh)), width(width_px) {
    margin = std::round(kMarginPerWidth * width_px);
    scale = (width_px - 2 * margin) / (bounds.xmax - bounds.xmin);
    height = static_cast<int>(std::ceil((bounds.ymax - bounds.ymin) * scale + 2 * margin));
  }
  double px(double x) const { return margin + (x - bounds.xmin) * scale; }
  double py(double y) const { return margin + (bounds.ymax - y) * scale; }
};

void set_colour(cairo_t* cr, Rgb c) {
  cairo_set_source_rgb(cr, c.r / kChannelMax, c.g / kChannelMax, c.b / kChannelMax);
}

void cell_path(cairo_t* cr, const Mesh& mesh, const View& view, std::size_t c) {
  for (std::size_t k = 0; k < mesh.cell_size(c); ++k) {
    const Point& p = mesh.nodes[mesh.cell_begin(c)[k]];
    if (k == 0) {
      cairo_move_to(cr, view.px(p.x), view.py(p.y));
    } else {
      cairo_line_to(cr, view.px(p.x), view.py(p.y));
    }
  }
  cairo_close_path(cr);
}

/// Each body is filled as one path (nonzero winding over counter-clockwise cells gives the
/// union), so no seams show between neighbouring cells.
void fill_bodies(cairo_t* cr, const Mesh& mesh, const View& view) {
  cairo_set_fill_rule(cr, CAIRO_FILL_RULE_WINDING);
  for (std::size_t b = 0; b < mesh.body_names.size(); ++b) {
    for (std::size_t c = 0; c < mesh.cell_count(); ++c) {
      if (mesh.cell_body[c] == b) cell_path(cr, mesh, view, c);
    }
    set_colour(cr, body_colour(b));
    cairo_fill(cr);
  }
}

void stroke_cell_edges(cairo_t* cr, const Mesh& mesh, const View& view) {
  for (std::size_t c = 0; c < mesh.cell_count(); ++c) cell_path(cr, mesh, view, c);
  set_colour(cr, kCellEdgeColour);
  cairo_set_line_width(cr, kCellEdgePx);
  cairo_stroke(cr);
}

bool is_thick(const std::string& group) {
  return std::find(kThickGroups.begin(), kThickGroups.end(), group) != kThickGroups.end();
}

void stroke_thick_groups(cairo_t* cr, const Mesh& mesh, const View& view) {
  for (const BoundaryEdge& edge : mesh.boundary_edges) {
    if (!is_thick(mesh.boundary_names[edge.group])) continue;
    const Point& a = mesh.nodes[edge.a];
    const Point& b = mesh.nodes[edge.b];
    cairo_move_to(cr, view.px(a.x), view.py(a.y));
    cairo_line_to(cr, view.px(b.x), view.py(b.y));
  }
  set_colour(cr, kThickGroupColour);
  cairo_set_line_width(cr, kThickGroupPx);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  cairo_stroke(cr);
}

using Surface = std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)>;
using Context = std::unique_ptr<cairo_t, decltype(&cairo_destroy)>;

}  // namespace

Rgb body_colour(std::size_t body) { return kBodyPalette[body % kBodyPalette.size()]; }

void write_mesh_png(const Mesh& mesh, const std::filesystem::path& path, const PictureOptions& options) {
  const View view(mesh, options.width_px);
  if (!(view.bounds.xmax > view.bounds.xmin) || view.width <= 2 * view.margin) {
    throw MeshError(
        fmt::format("{}: nothing to draw ({} nodes, {} px wide)", path.string(), mesh.nodes.size(), options.width_px));
  }
  Surface surface(cairo_image_surface_create(CAIRO_FORMAT_RGB24, view.width, view.height), &cairo_surface_destroy);
  Context cr(cairo_create(surface.get()), &cairo_destroy);
  cairo_set_source_rgb(cr.get(), 1.0, 1.0, 1.0);
  cairo_paint(cr.get());
  fill_bodies(cr.get(), mesh, view);
  if (options.draw_cell_edges) stroke_cell_edges(cr.get(), mesh, view);
  stroke_thick_groups(cr.get(), mesh, view);
  cairo_surface_flush(surface.get());
  common::write_whole_file(path, [&](const std::filesystem::path& temporary) {
    const cairo_status_t status = cairo_surface_write_to_png(surface.get(), temporary.c_str());
    if (status != CAIRO_STATUS_SUCCESS) {
      throw MeshError(fmt::format("{}: cannot write PNG: {}", path.string(), cairo_status_to_string(status)));
    }
  });
}

}  // namespace ddafrac::meshes
