#include "ddafrac/scene/sweep.hpp"

#include <fmt/format.h>

#include "ddafrac/scene/parse.hpp"
#include "document.hpp"
#include "toml_reader.hpp"

namespace ddafrac::scene {

Sweep load_sweep(const std::filesystem::path& path) {
  using detail::Need;
  detail::Diagnostics diagnostics(path.string());
  const std::optional<std::string> text = detail::read_text(path, diagnostics);
  if (!text) throw SceneError(diagnostics.take());
  const toml::table document = detail::load_document(*text, path, diagnostics);
  if (!diagnostics.empty()) throw SceneError(diagnostics.take());

  toml::source_region region{};
  region.path = std::make_shared<const std::string>(path.string());
  detail::TableReader top(&document, "", region, diagnostics);
  Sweep sweep;
  sweep.source = path;
  sweep.name = top.name_or_file_stem("name", path);
  sweep.crack_time = top.number("crack_time", detail::NumberRule::positive("s"), Need::Required).value_or(0.0);
  sweep.parallel = static_cast<int>(top.integer("parallel", 0, kMaxParallelRuns, Need::Optional).value_or(0));
  sweep.threads = static_cast<int>(top.integer("threads", 1, kMaxThreadsPerRun, Need::Optional).value_or(1));

  const auto cases = top.strings("cases", "scene files, relative to the sweep file", Need::Required);
  for (const std::string& file : cases.value_or(std::vector<std::string>{})) {
    const std::filesystem::path scene_file = path.parent_path() / file;
    if (!std::filesystem::exists(scene_file))
      top.problem("cases", fmt::format("no scene file \"{}\"", scene_file.string()));
    sweep.cases.push_back(scene_file);
  }
  if (cases && cases->empty()) top.problem("cases", "expected at least one scene file");
  sweep.overrides = top.strings("set", "key=value overrides applied to every case", Need::Optional)
                        .value_or(std::vector<std::string>{});
  top.reject_unknown_keys();
  if (!diagnostics.empty()) throw SceneError(diagnostics.take());
  return sweep;
}

}  // namespace ddafrac::scene
