#include "ddafrac/dda/stress_average.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ddafrac::dda {

namespace {

/// Fewest grid cells along the longer side of the centroids' box: a radius much smaller than the
/// body still gets a grid of bounded size (each query then scans a few more cells).
constexpr double kMostCellsPerSide = 1024.0;

/// Block centroids binned in a uniform grid (CSR by cell), for the radius queries.
struct CentroidGrid {
  double x0 = 0.0, y0 = 0.0, cell = 1.0;
  long nx = 1, ny = 1;
  std::vector<Index> offsets, blocks;

  CentroidGrid(const BlockSystem& s, double radius) {
    double x1 = -std::numeric_limits<double>::infinity(), y1 = x1;
    x0 = y0 = std::numeric_limits<double>::infinity();
    for (const PolygonIntegrals& g : s.geometry) {
      x0 = std::min(x0, g.cx);
      y0 = std::min(y0, g.cy);
      x1 = std::max(x1, g.cx);
      y1 = std::max(y1, g.cy);
    }
    cell = std::max(radius, std::max(x1 - x0, y1 - y0) / kMostCellsPerSide);
    nx = static_cast<long>((x1 - x0) / cell) + 1;
    ny = static_cast<long>((y1 - y0) / cell) + 1;
    offsets.assign(static_cast<std::size_t>(nx * ny + 1), 0);
    for (const PolygonIntegrals& g : s.geometry) ++offsets[static_cast<std::size_t>(index_of(g.cx, g.cy)) + 1];
    for (std::size_t c = 1; c < offsets.size(); ++c) offsets[c] += offsets[c - 1];
    blocks.resize(s.block_count());
    std::vector<Index> fill(offsets.begin(), offsets.end() - 1);
    for (std::size_t b = 0; b < s.block_count(); ++b)
      blocks[static_cast<std::size_t>(fill[static_cast<std::size_t>(index_of(s.geometry[b].cx, s.geometry[b].cy))]++)] =
          static_cast<Index>(b);
  }
  long column(double x) const { return std::clamp(static_cast<long>((x - x0) / cell), 0L, nx - 1); }
  long row(double y) const { return std::clamp(static_cast<long>((y - y0) / cell), 0L, ny - 1); }
  long index_of(double x, double y) const { return row(y) * nx + column(x); }
};

/// Joint j's neighbourhood, sorted by block.
std::vector<Index> neighbourhood(const BlockSystem& s, const CentroidGrid& grid, const Joint& j, double radius) {
  const meshes::Point mid = s.joint_midpoint(j);
  const Index body = s.body[static_cast<std::size_t>(j.block_a)];
  std::vector<Index> out{j.block_a, j.block_b};
  for (long r = grid.row(mid.y - radius); r <= grid.row(mid.y + radius); ++r)
    for (long c = grid.column(mid.x - radius); c <= grid.column(mid.x + radius); ++c) {
      const auto cell = static_cast<std::size_t>(r * grid.nx + c);
      for (Index k = grid.offsets[cell]; k < grid.offsets[cell + 1]; ++k) {
        const auto b = static_cast<std::size_t>(grid.blocks[static_cast<std::size_t>(k)]);
        if (s.body[b] == body && std::hypot(s.geometry[b].cx - mid.x, s.geometry[b].cy - mid.y) <= radius)
          out.push_back(static_cast<Index>(b));
      }
    }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace

StressNeighbourhoods stress_neighbourhoods(const BlockSystem& s, double radius) {
  const CentroidGrid grid(s, radius);
  const auto nj = static_cast<std::int64_t>(s.joints.size());
  std::vector<std::vector<Index>> lists(s.joints.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t j = 0; j < nj; ++j) lists[j] = neighbourhood(s, grid, s.joints[j], radius);
  StressNeighbourhoods n;
  for (const std::vector<Index>& list : lists) {
    double area = 0.0;
    for (const Index b : list) area += s.geometry[static_cast<std::size_t>(b)].area;
    for (const Index b : list) {
      n.blocks.push_back(b);
      n.weights.push_back(s.geometry[static_cast<std::size_t>(b)].area / area);
    }
    n.offsets.push_back(static_cast<Index>(n.blocks.size()));
  }
  return n;
}

Vec3 neighbourhood_stress(const BlockSystem& s, const StressNeighbourhoods& n, std::size_t j) {
  Vec3 mean = Vec3::Zero();
  for (Index k = n.offsets[j]; k < n.offsets[j + 1]; ++k)
    mean += n.weights[static_cast<std::size_t>(k)] *
            s.stress[static_cast<std::size_t>(n.blocks[static_cast<std::size_t>(k)])];
  return mean;
}

}  // namespace ddafrac::dda
