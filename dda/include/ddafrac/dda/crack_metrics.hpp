#pragma once
// Crack measures that may converge with the mesh when crack counts do not: the length of the
// broken joints, the fragments (groups of blocks still joined by intact virtual joints), the
// largest fragment's area, the time of the first crack and of the first through-going crack
// (docs/design.md §5).
//
// They read only the block system's joints and blocks and the crack events. Joints only ever
// break, so the joints broken at time t are those whose crack event is at or before t: the
// whole history follows from the events, the same for any thread count and for a resumed run.
// Areas are the blocks' areas at t = 0 (mass / density), so deformation does not move them.
//
// Through-going crack: the first time a body with virtual joints falls into at least two
// fragments each of at least kThroughCrackFragmentFraction of the body's area.

#include <optional>
#include <vector>

#include "ddafrac/dda/block_system.hpp"
#include "ddafrac/dda/engine.hpp"

namespace ddafrac::dda {

/// A fragment of at least this fraction of its body's area counts towards a through-going
/// crack: a split into two such pieces is a crack across the body, not a chipped corner.
inline constexpr double kThroughCrackFragmentFraction = 0.1;

/// The cracks and fragments of one body that has virtual joints, at one time.
struct BodyCracks {
  Index body = -1;                                  // Scene::bodies index
  double area = 0.0;                                // m², at t = 0
  long cracks_tensile = 0, cracks_shear = 0;        // joints broken in tension / in shear
  long cracks_untyped = 0;                          // joints broken with no failure type (set by hand)
  double length_tensile = 0.0, length_shear = 0.0;  // m, summed lengths of those joints
  long fragments = 0;                               // groups of blocks joined by intact joints
  long through_fragments = 0;                       // of them, those of ≥ kThroughCrackFragmentFraction · area
  double largest_fragment_area = 0.0;               // m²
};

struct CrackHistory {
  /// One entry per body with virtual joints, in body order: as the joints are now.
  std::vector<BodyCracks> now;
  /// For each requested time, the same entries as they were then.
  std::vector<std::vector<BodyCracks>> at_times;
  /// Per entry of `now`: the time of its first crack and of its first through-going crack (s).
  std::vector<std::optional<double>> first_crack, first_through_crack;
};

/// Fragments and cracks of every body with virtual joints now and at each of `times` (s). A joint
/// broken without a crack event (tests break joints by hand) counts as broken from t = 0.
CrackHistory crack_history(const BlockSystem& blocks, const std::vector<CrackEvent>& events,
                           const std::vector<double>& times = {});

}  // namespace ddafrac::dda
