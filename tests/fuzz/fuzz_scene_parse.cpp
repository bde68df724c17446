// libFuzzer target: any bytes as the text of a scene file, through the parser the app uses
// (TOML syntax, `base` chains, every key's type, range and cross-checks). A SceneError is the
// parser's answer to a bad scene; anything else (another exception, a crash, UB, a leak, a hang)
// is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "ddafrac/scene/parse.hpp"

namespace {
// The input is named as a file beside the shipped scenes (it is never written), so a seed's
// `base = "impact/case04.toml"` extends a real scene and the base chain is fuzzed too.
constexpr const char* kInputName = DDAFRAC_SOURCE_DIR "/scenes/fuzz_input.toml";
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    ddafrac::scene::parse_scene(text, kInputName);
  } catch (const ddafrac::scene::SceneError&) {
  }
  return 0;
}
