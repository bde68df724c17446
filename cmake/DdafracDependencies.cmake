# Every dependency comes from a Debian 12 package (see .ci/install-deps).
find_package(OpenMP REQUIRED COMPONENTS CXX)
find_package(Eigen3 3.3 REQUIRED NO_MODULE)
find_package(tomlplusplus REQUIRED)
find_package(CLI11 REQUIRED)
find_package(nlohmann_json 3.10 REQUIRED)
find_package(fmt REQUIRED)
find_package(Boost 1.74 REQUIRED COMPONENTS unit_test_framework serialization)
find_package(PkgConfig REQUIRED)
pkg_check_modules(CAIRO REQUIRED IMPORTED_TARGET cairo)

# gmsh ships no CMake config in Debian: find the C++ API header and library by hand.
find_path(GMSH_INCLUDE_DIR gmsh.h REQUIRED)
find_library(GMSH_LIBRARY NAMES gmsh REQUIRED)
add_library(gmsh::gmsh UNKNOWN IMPORTED)
set_target_properties(gmsh::gmsh PROPERTIES
  IMPORTED_LOCATION "${GMSH_LIBRARY}"
  INTERFACE_INCLUDE_DIRECTORIES "${GMSH_INCLUDE_DIR}")

if(DDAFRAC_WITH_FEM)
  find_package(deal.II 9.4 REQUIRED HINTS ${DEAL_II_DIR} /usr/share/cmake/deal.II)
  if(NOT DEAL_II_WITH_TRILINOS)
    message(FATAL_ERROR "deal.II was built without Trilinos; the FEM reference needs it")
  endif()
  # SuiteSparse (a dependency of Debian's deal.II) ships no CMake config in Debian 12.
  find_path(CHOLMOD_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse REQUIRED)
  find_library(CHOLMOD_LIBRARY NAMES cholmod REQUIRED)
  add_library(SuiteSparse::cholmod UNKNOWN IMPORTED)
  set_target_properties(SuiteSparse::cholmod PROPERTIES
    IMPORTED_LOCATION "${CHOLMOD_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${CHOLMOD_INCLUDE_DIR}")
endif()
