#pragma once
// The 2D idealisation, one enum for the scene, the DDA, the FEM and the closed forms: plane
// stress (a thin slab, σzz = 0) or plane strain (a long body, εzz = 0).

namespace ddafrac::common {

enum class PlaneModel { Stress, Strain };

}  // namespace ddafrac::common
