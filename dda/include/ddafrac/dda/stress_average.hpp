#pragma once
// The stress the fracture criterion judges a virtual joint on when it averages over a radius
// (scene analysis.fracture_stress_radius; docs/design.md §5).

#include <vector>

#include "ddafrac/dda/block_system.hpp"

namespace ddafrac::dda {

/// Per virtual joint, the blocks whose stress the criterion averages and their weights: the
/// blocks of the joint's body whose centroids lie within the radius of its midpoint at t = 0,
/// and its own two blocks; weighted by their areas at t = 0, the weights summing to 1. Joint j's
/// blocks are blocks[offsets[j]] .. blocks[offsets[j + 1] - 1], in increasing order (so the mean
/// is summed in a fixed order, whatever the thread count).
struct StressNeighbourhoods {
  std::vector<Index> offsets{0};
  std::vector<Index> blocks;
  std::vector<double> weights;
};

/// The neighbourhoods of every joint of `blocks` (its current geometry taken as t = 0).
StressNeighbourhoods stress_neighbourhoods(const BlockSystem& blocks, double radius);

/// The weighted mean stress (σxx, σyy, τxy) of joint j's neighbourhood, Pa.
Vec3 neighbourhood_stress(const BlockSystem& blocks, const StressNeighbourhoods& n, std::size_t j);

}  // namespace ddafrac::dda
