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

}  // namespace ddafrac::scene
