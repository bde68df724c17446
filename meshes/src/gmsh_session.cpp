#include "gmsh_session.hpp"

#include <gmsh.h>

#include <exception>
#include <vector>

#include "ddafrac/meshes/generate.hpp"

namespace ddafrac::meshes::detail {

namespace {
constexpr double kRandomSeed = 20260;  // fixed seed: the same input gives the same mesh
}

GmshSession::GmshSession() {
  gmsh::initialize(0, nullptr, /*readConfigFiles=*/false);
  try {
    gmsh::option::setNumber("General.Terminal", 0);
    gmsh::option::setNumber("General.Verbosity", 2);  // errors and warnings only
    gmsh::option::setNumber("General.NumThreads", 1);
    gmsh::option::setNumber("Mesh.RandomSeed", kRandomSeed);
    gmsh::logger::start();
  } catch (...) {
    gmsh::finalize();
    rethrow_gmsh_error("initialising gmsh");
  }
}

GmshSession::~GmshSession() {
  try {
    gmsh::logger::stop();
    gmsh::finalize();
  } catch (...) {  // a destructor must not throw; gmsh's state is gone either way
  }
}

std::string gmsh_last_error() {
  std::string error;
  try {
    gmsh::logger::getLastError(error);
  } catch (...) {
    error.clear();
  }
  return error;
}

void rethrow_gmsh_error(const std::string& context) {
  std::string message;
  try {
    throw;
  } catch (const MeshError&) {
    throw;
  } catch (const std::string& gmsh_message) {
    message = gmsh_message;
  } catch (const std::exception& e) {
    message = e.what();
  } catch (...) {
    message = gmsh_last_error();
  }
  if (message.empty()) message = "unknown gmsh error";
  throw MeshError(context + ": " + message);
}

}  // namespace ddafrac::meshes::detail
