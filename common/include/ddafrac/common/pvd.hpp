#pragma once
// ParaView's collection file (.pvd): a time series of VTK files, one DataSet a snapshot; the one
// writer of the DDA run's and the FEM's run.pvd.

#include <string>
#include <vector>

namespace ddafrac::common {

struct PvdEntry {
  double time = 0.0;  // s
  std::string file;   // relative to the .pvd file
};

std::string pvd_document(const std::vector<PvdEntry>& entries);

}  // namespace ddafrac::common
