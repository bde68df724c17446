#include "ddafrac/common/whole_file.hpp"

#include <fmt/core.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <optional>
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

namespace {

constexpr double kBytesPerMegabyte = 1e6;

/// Free bytes on the file system `target` would be written to (nothing if that cannot be told).
std::optional<std::uintmax_t> free_bytes_for(const std::filesystem::path& target) {
  std::error_code error;
  const std::filesystem::path folder = target.has_parent_path() ? target.parent_path() : std::filesystem::path(".");
  const std::filesystem::space_info space = std::filesystem::space(folder, error);
  if (error) return std::nullopt;
  return space.available;
}

/// Why `bytes` could not be written to `target`, which had `free_before` bytes free: a full
/// disk (also when the system reported something else but the space was short), else the
/// system's reason.
std::string write_failure(const std::filesystem::path& target, std::size_t bytes,
                          std::optional<std::uintmax_t> free_before, int error_number) {
  if (error_number == ENOSPC || (free_before && *free_before < bytes))
    return fmt::format("cannot write {}: the disk is full ({} MB free, the file needs {:.1f} MB)", target.string(),
                       free_before ? fmt::format("{:.1f}", static_cast<double>(*free_before) / kBytesPerMegabyte) : "?",
                       static_cast<double>(bytes) / kBytesPerMegabyte);
  return fmt::format("cannot write {}: {}", target.string(),
                     error_number != 0 ? std::strerror(error_number) : "write failed");
}

}  // namespace

void write_whole_text(const std::filesystem::path& target, std::string_view text) {
  write_whole_file(target, [&](const std::filesystem::path& temporary) {
    const std::optional<std::uintmax_t> free_before = free_bytes_for(temporary);
    errno = 0;
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    out.close();
    if (!out) throw WriteError(write_failure(target, text.size(), free_before, errno));
  });
}

}  // namespace ddafrac::common
