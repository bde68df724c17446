// `ddafrac mesh SCENE [--out DIR]`: the scene's DDA mesh and FEM mesh as gmsh files, a picture,
// and a quality report.

#include <fmt/core.h>
#include <CLI/CLI.hpp>

#include <chrono>
#include <filesystem>
#include <memory>

#include "commands.hpp"
#include "ddafrac/meshes/edge_lines.hpp"
#include "ddafrac/meshes/generate.hpp"
#include "ddafrac/meshes/msh_io.hpp"
#include "ddafrac/meshes/picture.hpp"
#include "scene_source.hpp"

namespace ddafrac::app {

namespace {

struct MeshArguments {
  SceneArguments scene;
  std::string out;
  bool fem_quads = false;
};

void print_quality(const char* what, const char* cells, const meshes::QualityReport& q, double seconds) {
  fmt::print(
      "{:<9} {:>7} {:<6}  min angle {:5.1f}°  mean min angle {:5.1f}°  element size {:.3g} m  "
      "({} sizing iterations, {:.2f} s)\n",
      what, q.blocks, cells, q.min_angle_deg, q.mean_min_angle_deg, q.element_size, q.iterations, seconds);
}

void run_mesh(const MeshArguments& args) {
  const scene::Scene scene = args.scene.load();
  const std::filesystem::path out = output_directory(args.out, scene, "mesh");
  std::filesystem::create_directories(out);

  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  meshes::QualityReport quality;
  const meshes::Mesh dda = dda_mesh(scene, &quality);
  const double dda_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  meshes::write_msh(dda, out / "dda.msh");
  meshes::write_mesh_png(dda, out / "dda.png");
  print_quality("DDA mesh", "blocks", quality, dda_seconds);
  fmt::print("          longest straight line of block edges {:.1f} mm (turning {}° at most per node)\n",
             1e3 * meshes::longest_straight_edge_line(dda), meshes::kStraightLineTurnDeg);

  const bool generated = !std::holds_alternative<meshes::MshFile>(scene.geometry);
  if (generated) {
    const double off = static_cast<double>(quality.blocks) / scene.mesh.target_blocks - 1.0;
    fmt::print("          target {} blocks, hit within {:+.1f}%\n", scene.mesh.target_blocks, 100.0 * off);
    try {
      const auto fem_start = Clock::now();
      meshes::QualityReport fem_quality;
      const auto cells = args.fem_quads ? meshes::FemCells::Quadrilaterals : meshes::FemCells::Triangles;
      const meshes::Mesh fem = meshes::generate_fem_mesh(scene.geometry, quality.element_size, cells, &fem_quality);
      meshes::write_msh(fem, out / "fem.msh");
      meshes::write_mesh_png(fem, out / "fem.png");
      print_quality("FEM mesh", "cells", fem_quality, std::chrono::duration<double>(Clock::now() - fem_start).count());
    } catch (const meshes::MeshError& e) {
      throw CommandFailed(fmt::format("{}: cannot mesh the scene for the FEM: {}", scene.source.string(), e.what()));
    }
  }
  fmt::print("wrote {}/{{dda.msh, dda.png{}}}\n", out.string(), generated ? ", fem.msh, fem.png" : "");
}

}  // namespace

void register_mesh_command(CLI::App& app) {
  auto args = std::make_shared<MeshArguments>();
  CLI::App* command = app.add_subcommand("mesh", "mesh a scene: DDA blocks and FEM cells as .msh files, with pictures");
  args->scene.add_to(*command);
  command->add_option("--out", args->out, "output directory (default runs/<scene name>/mesh)");
  command->add_flag("--fem-quads", args->fem_quads, "mesh the FEM model with quadrilaterals instead of triangles");
  command->callback([args] { run_mesh(*args); });
}

}  // namespace ddafrac::app
