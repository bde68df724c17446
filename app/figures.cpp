#include "figures.hpp"

#include "ddafrac/common/whole_file.hpp"

#include <fmt/core.h>

#include <cstdlib>
#include <filesystem>

#include "subprocess.hpp"

namespace ddafrac::app {

namespace {
/// Debian's interpreter, which python3-matplotlib installs into (another python3 on PATH, such
/// as a pyenv one, may lack it). DDAFRAC_PYTHON overrides it.
constexpr const char* kDefaultPython = "/usr/bin/python3";
}  // namespace

std::size_t remove_previous_figures(const std::filesystem::path& run_dir) {
  // The names plots/ddafrac_plots.py gives them; it saves each as ".<name>.partial.png" first.
  static const std::regex kRunFigure(
      R"(\.?(energy|crack_counts|gauges_sigma1|(crack_pattern|utilisation)_\d+us)\.png(\.partial\.png)?)");
  return common::remove_files_matching(run_dir / "figures", kRunFigure);
}

bool draw_figures(const std::vector<std::string>& arguments) {
  const char* override_python = std::getenv("DDAFRAC_PYTHON");
  const std::string python = override_python ? override_python : kDefaultPython;
  const std::filesystem::path script = std::filesystem::path(DDAFRAC_SOURCE_DIR) / "plots" / "ddafrac_plots.py";
  if (!std::filesystem::exists(python)) {
    fmt::print(stderr, "ddafrac: figures skipped: no {} (install python3-matplotlib, or set DDAFRAC_PYTHON)\n", python);
    return false;
  }
  std::vector<std::string> argv{python, script.string()};
  argv.insert(argv.end(), arguments.begin(), arguments.end());
  const int code = run_process(argv);
  if (code != 0) {
    fmt::print(stderr, "ddafrac: figures not drawn: {} exited with status {}\n", script.string(), code);
    return false;
  }
  return true;
}

}  // namespace ddafrac::app
