#include "whole_file.hpp"

#include <system_error>

#include "ddafrac/meshes/generate.hpp"

namespace ddafrac::meshes::detail {

void write_whole_file(const std::filesystem::path& target,
                      const std::function<void(const std::filesystem::path&)>& write) {
  std::filesystem::path temporary = target;
  temporary.replace_filename("." + target.stem().string() + ".partial" +
                             target.extension().string());
  try {
    write(temporary);
    std::filesystem::rename(temporary, target);
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw;
  }
}

}  // namespace ddafrac::meshes::detail
