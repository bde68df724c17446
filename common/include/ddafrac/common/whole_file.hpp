#pragma once
// Output files are written whole: to a temporary name beside the target, then renamed over it,
// so that an interrupted run never leaves a half-written file under the real name.

#include <filesystem>
#include <functional>
#include <regex>
#include <stdexcept>
#include <string_view>

namespace ddafrac::common {

/// A file that could not be written: the message names it and says why (a full disk says so,
/// with the free space). The previous version of the file, if any, is left as it was.
class WriteError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Calls write(temporary) and renames the temporary file to `target`. The temporary name keeps
/// the target's extension (gmsh and others pick the format from it). On failure the temporary
/// file is removed and the exception passes on.
void write_whole_file(const std::filesystem::path& target,
                      const std::function<void(const std::filesystem::path&)>& write);

/// Writes `text` as the whole content of `target`. Throws WriteError naming the file.
void write_whole_text(const std::filesystem::path& target, std::string_view text);

/// The temporary name write_whole_file writes `target` under: ".<stem>.partial<extension>".
std::filesystem::path partial_name(const std::filesystem::path& target);

/// Removes the regular files directly in `folder` whose names match `pattern` (nothing else, no
/// sub-folder); returns how many. A missing folder holds nothing.
std::size_t remove_files_matching(const std::filesystem::path& folder, const std::regex& pattern);

}  // namespace ddafrac::common
