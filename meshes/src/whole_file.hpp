#pragma once
// Files are written whole: to a temporary name beside the target, then renamed over it.

#include <filesystem>
#include <functional>

namespace ddafrac::meshes::detail {

/// Calls write(temporary) and renames the temporary file to `target`. The temporary name keeps
/// the target's extension (gmsh and others pick the format from it). On failure the temporary
/// file is removed and the exception passes on.
void write_whole_file(const std::filesystem::path& target,
                      const std::function<void(const std::filesystem::path&)>& write);

}  // namespace ddafrac::meshes::detail
