#include "ddafrac/common/whole_file.hpp"

#include <fstream>
#include <stdexcept>
#include <system_error>

namespace ddafrac::common {

std::filesystem::path partial_name(const std::filesystem::path& target) {
  std::filesystem::path temporary = target;
  temporary.replace_filename("." + target.stem().string() + ".partial" + target.extension().string());
  return temporary;
}

std::size_t remove_files_matching(const std::filesystem::path& folder, const std::regex& pattern) {
  std::error_code error;
  if (!std::filesystem::is_directory(folder, error)) return 0;
  std::size_t removed = 0;
  for (const auto& entry : std::filesystem::directory_iterator(folder, error)) {
    if (!entry.is_regular_file(error) || !std::regex_match(entry.path().filename().string(), pattern)) continue;
    if (std::filesystem::remove(entry.path(), error)) ++removed;
  }
  return removed;
}

void write_whole_file(const std::filesystem::path& target,
                      const std::function<void(const std::filesystem::path&)>& write) {
  const std::filesystem::path temporary = partial_name(target);
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
