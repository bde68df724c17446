#pragma once
// The defaults of the contact keys a scene may leave out, in one place. The parser fills them in
// (and scene.hpp's member initialisers use them, for scenes built in code); nothing downstream
// falls back to a value of its own. README, "Scene files", lists them.
//
// The contact penalty kn itself has no default: analysis.penalty is required, and a joint set
// that gives no normal_stiffness takes it.

namespace ddafrac::scene {

/// joints.*.shear_stiffness of a joint set that gives none: ks = this × its normal stiffness
/// (ks = kn / 2.5, the usual choice in Shi's DDA codes).
inline constexpr double kDefaultShearToNormalStiffness = 0.4;

/// analysis.search_distance_factor: contact search distance / allowed step displacement.
inline constexpr double kDefaultSearchDistanceFactor = 2.5;

/// analysis.pair_list_skin_factor: skin of the contact pair list / search distance.
inline constexpr double kDefaultPairListSkinFactor = 1.0;

/// analysis.solver_tolerance: PCG stops once its residual |b − K·x| is this fraction of |b|.
inline constexpr double kDefaultSolverTolerance = 1e-10;

/// The range analysis.solver_tolerance may take: below the smallest, round-off keeps PCG from
/// ever getting there (every step would fail); above the largest, a solve is not a solution.
inline constexpr double kSmallestSolverTolerance = 1e-14;
inline constexpr double kLargestSolverTolerance = 1e-3;

}  // namespace ddafrac::scene
