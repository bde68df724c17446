#include <fmt/core.h>

#include <sstream>

#include "ddafrac/common/whole_file.hpp"
#include "static/static_report.hpp"

namespace ddafrac::coupling {

void write_static_csv(const std::filesystem::path& dir, const StaticComparison& c) {
  std::ostringstream prof;
  prof << "profile,s,x,y,dda_sxx,dda_syy,dda_txy,fem_sxx,fem_syy,fem_txy,ana_sxx,ana_syy,ana_txy\n";
  for (const auto& p : c.profiles)
    prof << fmt::format("{},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g}\n",
                        p.profile, p.s, p.x, p.y, p.dda.xx, p.dda.yy, p.dda.xy, p.fem.xx, p.fem.yy, p.fem.xy, p.ana.xx,
                        p.ana.yy, p.ana.xy);
  std::ostringstream blocks;
  blocks << "block,x,y,area,dda_sxx,dda_syy,dda_txy,fem_sxx,fem_syy,fem_txy,ana_sxx,ana_syy,ana_txy\n";
  for (std::size_t i = 0; i < c.blocks.size(); ++i) {
    const auto& b = c.blocks[i];
    blocks << fmt::format("{},{:.9g},{:.9g},{:.6g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g}\n", i,
                          b.x, b.y, b.area, b.dda.xx, b.dda.yy, b.dda.xy, b.fem.xx, b.fem.yy, b.fem.xy, b.ana.xx,
                          b.ana.yy, b.ana.xy);
  }
  std::filesystem::create_directories(dir);
  common::write_whole_text(dir / "profiles.csv", prof.str());
  common::write_whole_text(dir / "blocks.csv", blocks.str());
}

}  // namespace ddafrac::coupling
