// libFuzzer target: any bytes as a user's .msh file, through what the app does with one
// (read_msh: gmsh reads the file, then our checks of groups, elements, plane and orientation;
// then the quality report). A MeshError is the reader's answer to a bad file; anything else
// (another exception, a crash, UB, a leak, a hang) is a finding.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "ddafrac/meshes/generate.hpp"
#include "ddafrac/meshes/msh_io.hpp"

namespace {

/// gmsh reads files only: each input is written to a file of this process's own, then removed.
class InputFile {
 public:
  InputFile(const std::uint8_t* data, std::size_t size)
      : path_(std::filesystem::temp_directory_path() /
              ("ddafrac_fuzz_msh_" + std::to_string(::getpid()) + ".msh")) {
    std::ofstream(path_, std::ios::binary).write(reinterpret_cast<const char*>(data),
                                                 static_cast<std::streamsize>(size));
  }
  ~InputFile() {
    std::error_code ignored;  // a file left behind is not worth a crash of the fuzzer
    std::filesystem::remove(path_, ignored);
  }
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const InputFile input(data, size);
  try {
    const ddafrac::meshes::Mesh mesh = ddafrac::meshes::read_msh(input.path());
    ddafrac::meshes::measure_quality(mesh);
  } catch (const ddafrac::meshes::MeshError&) {
  }
  return 0;
}
