#pragma once
// ddafrac's own reader of .msh text: ASCII MSH 4.1 (what gmsh writes by default) and MSH 2.2
// (what it writes for other programs). A user's file is not handed to gmsh's reader, which
// frees memory twice and dereferences null on malformed files (found by fuzzing, issue 13).

#include <string>
#include <string_view>

#include "msh_model.hpp"

namespace ddafrac::meshes::detail {

/// Parses the text of a .msh file. Throws MeshError "source:line: what was expected" for
/// anything but a well-formed file of linear points, lines, triangles and quadrangles; the
/// model's groups and geometry are checked by mesh_from_model.
MshModel parse_msh_text(std::string_view text, const std::string& source);

}  // namespace ddafrac::meshes::detail
