#pragma once
// Cell quality over a chosen set of bodies (the public measure_quality takes one body).

#include <functional>

#include "ddafrac/meshes/generate.hpp"

namespace ddafrac::meshes::detail {

/// Count, smallest angle and mean smallest angle over the cells whose body passes `include`.
QualityReport quality_of_cells(const Mesh& mesh, const std::function<bool(Index)>& include);

/// The index of the body called `name` in mesh.body_names, or -1.
long body_index(const Mesh& mesh, const std::string& name);

}  // namespace ddafrac::meshes::detail
