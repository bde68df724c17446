#include "ddafrac/dda/checkpoint.hpp"

#include <fmt/core.h>
#include <boost/archive/archive_exception.hpp>
#include <boost/archive/binary_iarchive.hpp>
#include <boost/archive/binary_oarchive.hpp>
#include <boost/serialization/string.hpp>

#include <fstream>
#include <sstream>

#include "ddafrac/common/whole_file.hpp"

namespace ddafrac::dda {

namespace {

/// First bytes of the archive, so that any other file is refused by name.
constexpr std::string_view kMagic = "ddafrac checkpoint";
/// Raised whenever the layout of a checkpoint (or of the engine's carried state) changes.
// 2: the contacts without their linearisation; 3: the residual's sources; 4: the contacts' rest gap;
// 5: the ledger's mass damping; 6: node ties; 7: ties lost; 8: the joints' damage (softening);
// 9: the friction of a softening joint's damaged part.
constexpr int kFormat = 9;

constexpr std::uint64_t kFnvOffset = 14695981039346656037ull;
constexpr std::uint64_t kFnvPrime = 1099511628211ull;

}  // namespace

std::uint64_t fingerprint(std::string_view bytes) {
  std::uint64_t h = kFnvOffset;
  for (const char c : bytes) {
    h ^= static_cast<unsigned char>(c);
    h *= kFnvPrime;
  }
  return h;
}

void write_checkpoint(const std::filesystem::path& run_dir, const Checkpoint& c) {
  std::ostringstream bytes(std::ios::binary);
  {
    boost::archive::binary_oarchive archive(bytes);
    std::string magic(kMagic);
    int format = kFormat;
    archive << magic << format << c.invocation << c.initial_state << c.step << c.time << c.engine << c.run_log;
  }
  common::write_whole_text(run_dir / kCheckpointFile, std::move(bytes).str());
}

Checkpoint read_checkpoint(const std::filesystem::path& run_dir) {
  const std::filesystem::path file = run_dir / kCheckpointFile;
  std::ifstream in(file, std::ios::binary);
  if (!in)
    throw CheckpointError(
        fmt::format("{}: no checkpoint to resume from (a run writes one every --checkpoint-every "
                    "seconds and when it is interrupted)",
                    file.string()));
  Checkpoint c;
  std::string magic;
  int format = 0;
  try {
    boost::archive::binary_iarchive archive(in);
    archive >> magic;
    if (magic != kMagic) throw CheckpointError(fmt::format("{}: not a ddafrac checkpoint", file.string()));
    archive >> format;
    if (format != kFormat)
      throw CheckpointError(fmt::format("{}: checkpoint format {}, this ddafrac reads format {}; run the scene anew",
                                        file.string(), format, kFormat));
    archive >> c.invocation >> c.initial_state >> c.step >> c.time >> c.engine >> c.run_log;
  } catch (const boost::archive::archive_exception& e) {
    throw CheckpointError(fmt::format("{}: damaged or not a ddafrac checkpoint ({})", file.string(), e.what()));
  }
  return c;
}

}  // namespace ddafrac::dda
