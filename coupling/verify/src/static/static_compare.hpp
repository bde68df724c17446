#pragma once
// The static comparison proper: the FEM and (plain disc) the Hondros series sampled at the DDA
// twin's block centroids, and from those samples the centre stresses, the field errors, the
// worst blocks with where they are, and the profiles along both diameters.

#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "ddafrac/reference/analytic.hpp"
#include "static/static_dda.hpp"
#include "static/static_fem.hpp"
#include "static/static_setup.hpp"

namespace ddafrac::coupling {

/// Centre stresses: area-weighted means over the blocks whose centroid lies within this × R of
/// the centre (a slit disc has no material there: not compared).
inline constexpr double kCentreRegionShare = 0.1;
/// The inner disc r < this × R, away from the loaded arcs and flats.
inline constexpr double kInnerDiscShare = 0.8;
/// The worst this-many percent of the blocks (against the FEM) are listed with where they are.
inline constexpr std::size_t kWorstPercent = 1;
/// "Near" a slit tip, a flat or a loaded arc: within this many mean block sizes.
inline constexpr double kNearBlockSizes = 3.0;
/// "At the free rim": within this many mean block sizes of the rim.
inline constexpr double kFreeRimBlockSizes = 1.5;
/// Samples along each profile (the loaded and the horizontal diameter), ends included.
inline constexpr int kProfilePoints = 201;
/// The profiles end this share of R inside the rim (the series converges slowly on it).
inline constexpr double kProfileRimClearance = 1e-6;

/// One DDA block with every source at its undeformed centroid.
struct BlockSample {
  double x = 0.0, y = 0.0, area = 0.0;  // m; m²
  reference::Stress2 dda, fem, ana;     // Pa; ana zero unless the Hondros series applies
  bool has_fem = false;                 // the centroid lies in the FEM mesh
};

/// Area-weighted relative L2 error of the three components together (τxy counted twice, as in
/// the tensor norm) and of each one alone.
struct FieldError {
  double all = 0.0, xx = 0.0, yy = 0.0, xy = 0.0;
};

/// Relative errors |a − r| / |r| of the centre σxx and σyy.
struct CentreError {
  double xx = 0.0, yy = 0.0;
};

struct WorstBlock {
  std::size_t block = 0;
  double error = 0.0;  // |σ_DDA − σ_FEM| (tensor norm) / RMS FEM stress
  std::string where;   // "interior", "near a loaded arc", ...
};

/// One point of a profile: the DDA block stress there (deformed blocks), the FEM, the series.
struct ProfileSample {
  const char* profile = "";          // "loaded" or "horizontal"
  double s = 0.0, x = 0.0, y = 0.0;  // m: position along the diameter, and the point
  reference::Stress2 dda, fem, ana;  // Pa; ana NaN unless the Hondros series applies
};

struct StaticComparison {
  std::vector<BlockSample> blocks;
  std::size_t outside_fem = 0;  // centroids outside the FEM mesh, left out
  bool has_centre = false;
  double centre_radius = 0.0;                             // m
  reference::Stress2 centre_dda, centre_fem, centre_ana;  // Pa, area-weighted means
  reference::Stress2 centre_point_ana;                    // Pa, the series at the centre point
  CentreError centre_dda_fem, centre_dda_ana, centre_fem_ana;
  FieldError dda_fem, dda_fem_inner, dda_ana, fem_ana;  // the last two only with the series
  double fem_rms = 0.0;                                 // Pa, area-weighted RMS of the FEM stress tensor norm
  double near_distance = 0.0;                           // m, kNearBlockSizes mean block sizes
  std::vector<WorstBlock> worst;
  std::map<std::string, int> worst_where;  // how many of the worst blocks are where
  std::vector<ProfileSample> profiles;
};

StaticComparison compare_static(const StaticSetup& setup, const StaticDdaRun& dda, const StaticFemRun& fem);

}  // namespace ddafrac::coupling
