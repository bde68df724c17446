#pragma once
// Synthetic scenes built in code (no gmsh): a disc triangulated in concentric rings, resting on a
// plate, as in the rockfall-impact scene of the study. Used by the benchmark and the thread-count
// determinism test; does not replace the meshes module.

#include "ddafrac/meshes/mesh.hpp"
#include "ddafrac/scene/scene.hpp"

namespace ddafrac::dda {

/// Disc of the given diameter centred at the origin, 6n² triangles for n = round(sqrt(target/6))
/// rings (body "disc"), and if plate_height > 0 a rectangular plate (body "plate") whose top edge
/// touches the lowest disc node.
meshes::Mesh make_ring_disc_mesh(double diameter, int target_blocks, double plate_width = 0.1,
                                 double plate_height = 0.02);

/// The rockfall-impact parameters of the source study (rock, virtual and real joints, kn = 0.35 GPa,
/// dt_max = 1e-7 s, ratio 1e-4, gravity) with the disc glued by virtual joints, moving down at v0
/// onto the fixed plate.
scene::Scene make_impact_scene(double v0, double end_time);

}  // namespace ddafrac::dda
