#include "ddafrac/common/whole_file.hpp"

#include <fstream>
#include <stdexcept>
#include <system_error>

namespace ddafrac::common {

void write_whole_file(const std::filesystem::path& target,
                      const std::function<void(const std::filesystem::path&)>& write) {
  std::filesystem::path temporary = target;
  temporary.replace_filename("." + target.stem().string() + ".partial" + target.extension().string());
  try {
    write(temporary);
    std::filesystem::rename(temporary, target);
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw;
  }
}

void write_whole_text(const std::filesystem::path& target, std::string_view text) {
  write_whole_file(target, [&](const std::filesystem::path& temporary) {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    out.close();
    if (!out) throw std::runtime_error("cannot write " + target.string());
  });
}

}  // namespace ddafrac::common
