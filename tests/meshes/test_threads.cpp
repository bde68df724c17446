// gmsh sets the process-wide OpenMP thread count; meshing must leave the caller's count as it
// was, or a DDA run after meshing silently runs on one thread.
#define BOOST_TEST_MODULE meshes_threads
#include <boost/test/unit_test.hpp>

#include <omp.h>

#include "ddafrac/meshes/generate.hpp"

BOOST_AUTO_TEST_CASE(meshing_keeps_the_callers_openmp_thread_count) {
  constexpr int kThreads = 3;  // any count other than gmsh's own 1
  omp_set_num_threads(kThreads);
  ddafrac::meshes::MeshControl control;
  control.target_blocks = 300;
  control.block_tolerance = 0.05;
  const auto mesh = ddafrac::meshes::generate_dda_mesh(ddafrac::meshes::PlainDisc{}, control);
  BOOST_TEST(mesh.cell_count() > 0u);
  BOOST_TEST(omp_get_max_threads() == kThreads);
}
