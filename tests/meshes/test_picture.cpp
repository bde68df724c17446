// PNG pictures: requested width, aspect ratio kept, disc centre in the disc's colour.
#define BOOST_TEST_MODULE meshes_picture
#include <boost/test/unit_test.hpp>

#include <cairo.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string>

#include <unistd.h>

#include "ddafrac/common/angles.hpp"
#include "ddafrac/meshes/generate.hpp"
#include "ddafrac/meshes/picture.hpp"

using namespace ddafrac::meshes;
namespace fs = std::filesystem;

namespace {

using Surface = std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)>;

Surface read_png(const fs::path& path) {
  Surface surface(cairo_image_surface_create_from_png(path.c_str()), &cairo_surface_destroy);
  BOOST_REQUIRE(cairo_surface_status(surface.get()) == CAIRO_STATUS_SUCCESS);
  return surface;
}

Rgb pixel(cairo_surface_t* surface, int x, int y) {
  const unsigned char* row = cairo_image_surface_get_data(surface) + y * cairo_image_surface_get_stride(surface);
  std::uint32_t argb = 0;
  std::memcpy(&argb, row + 4 * x, sizeof argb);  // native-endian 0xAARRGGBB
  return {static_cast<unsigned char>(argb >> 16), static_cast<unsigned char>(argb >> 8),
          static_cast<unsigned char>(argb)};
}

struct TempDir {
  fs::path path = fs::temp_directory_path() / ("ddafrac_picture_" + std::to_string(::getpid()));
  TempDir() { fs::create_directories(path); }
  ~TempDir() { fs::remove_all(path); }
};

}  // namespace

BOOST_AUTO_TEST_CASE(plain_disc_picture_width_aspect_and_centre_colour) {
  TempDir dir;
  MeshControl control;
  control.target_blocks = 500;
  const Mesh mesh = generate_dda_mesh(PlainDisc{}, control);
  const fs::path png = dir.path / "disc.png";
  PictureOptions options;
  options.width_px = 640;
  options.draw_cell_edges = false;  // the centre pixel then shows the fill colour only
  write_mesh_png(mesh, png, options);

  const Surface surface = read_png(png);
  const int width = cairo_image_surface_get_width(surface.get());
  const int height = cairo_image_surface_get_height(surface.get());
  BOOST_TEST(width == 640);
  BOOST_TEST(std::abs(height - width) <= 1);  // a disc: square picture
  const Rgb centre = pixel(surface.get(), width / 2, height / 2);
  const Rgb disc = body_colour(0);
  BOOST_TEST(centre.r == disc.r);
  BOOST_TEST(centre.g == disc.g);
  BOOST_TEST(centre.b == disc.b);
  const Rgb corner = pixel(surface.get(), 0, 0);
  BOOST_TEST((corner.r == 255 && corner.g == 255 && corner.b == 255));  // white background
  BOOST_TEST(!fs::exists(dir.path / ".disc.partial.png"));
}

BOOST_AUTO_TEST_CASE(flattened_disc_with_platens_keeps_its_aspect_ratio) {
  TempDir dir;
  MeshControl control;
  control.target_blocks = 1500;  // a slit's graded ends alone take ~600 blocks
  FlattenedDisc disc;
  disc.slit = Slit{};
  const Mesh mesh = generate_dda_mesh(disc, control);
  const fs::path png = dir.path / "flattened.png";
  write_mesh_png(mesh, png, PictureOptions{800, true});
  const Surface surface = read_png(png);
  const int width = cairo_image_surface_get_width(surface.get());
  const int height = cairo_image_surface_get_height(surface.get());
  BOOST_TEST(width == 800);
  // 0.1 m wide; 2 (R cos 5 deg + 0.02) m tall; the margin adds 2 * 3% of the width to both.
  const double model_height = 2 * (0.05 * std::cos(5.0 * ddafrac::common::kPi / 180) + 0.02);
  const double margin = 2 * std::round(0.03 * width);
  const double expected = (width - margin) * model_height / 0.1 + margin;
  BOOST_TEST(std::abs(height - expected) <= 1.0);
  const double scale = (width - margin) / 0.1;                             // px per m
  const int mid_platen_row = static_cast<int>(margin / 2 + 0.01 * scale);  // 10 mm below its top
  const Rgb top_platen = pixel(surface.get(), width / 2, mid_platen_row);
  BOOST_TEST(top_platen.r == body_colour(1).r);
  BOOST_TEST(top_platen.b == body_colour(1).b);
}
