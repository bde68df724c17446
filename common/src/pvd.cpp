#include "ddafrac/common/pvd.hpp"

#include <fmt/core.h>

namespace ddafrac::common {

std::string pvd_document(const std::vector<PvdEntry>& entries) {
  std::string s =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      "  <Collection>\n";
  for (const PvdEntry& e : entries)
    s += fmt::format("    <DataSet timestep=\"{:.17g}\" group=\"\" part=\"0\" file=\"{}\"/>\n", e.time, e.file);
  return s + "  </Collection>\n</VTKFile>\n";
}

}  // namespace ddafrac::common
