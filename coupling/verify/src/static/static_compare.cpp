#include "static/static_compare.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

#include "ddafrac/common/angles.hpp"
#include "ddafrac/reference/compare.hpp"

namespace ddafrac::coupling {

using common::kPi;

namespace {

using reference::Stress2;

/// The FEM and the series at every block centroid; counts the centroids outside the FEM mesh.
std::vector<BlockSample> sample_references(const StaticSetup& st, const StaticDdaRun& dda, const StaticFemRun& fem,
                                           std::size_t& outside) {
  const reference::Disc disc{st.diameter, 1.0};
  const reference::HondrosLoad hondros{st.load, st.half_angle};
  std::vector<BlockSample> out;
  outside = 0;
  for (const auto& block : dda.blocks) {
    BlockSample b;
    b.x = block.x;
    b.y = block.y;
    b.area = block.area;
    b.dda = block.stress;
    if (const auto f = fem_stress_at(*fem.solution, b.x, b.y)) {
      b.fem = *f;
      b.has_fem = true;
    } else {
      ++outside;
    }
    if (st.analytic) b.ana = reference::hondros_series(disc, hondros, b.x, b.y);
    out.push_back(b);
  }
  return out;
}

/// Blocks with centroid radius above `max_radius` are left out.
FieldError field_error(const std::vector<BlockSample>& blocks, Stress2 BlockSample::*approx, Stress2 BlockSample::*ref,
                       double max_radius = std::numeric_limits<double>::infinity()) {
  std::vector<double> a, r, axx, rxx, ayy, ryy, axy, rxy;
  for (const auto& b : blocks) {
    if (!b.has_fem || std::hypot(b.x, b.y) > max_radius) continue;
    const double w = std::sqrt(b.area);
    const Stress2& p = b.*approx;
    const Stress2& q = b.*ref;
    // τxy counts twice in the Frobenius norm of the tensor.
    for (const auto& [va, vr] :
         {std::pair{p.xx, q.xx}, std::pair{p.yy, q.yy}, std::pair{std::sqrt(2.0) * p.xy, std::sqrt(2.0) * q.xy}}) {
      a.push_back(w * va);
      r.push_back(w * vr);
    }
    axx.push_back(w * p.xx);
    rxx.push_back(w * q.xx);
    ayy.push_back(w * p.yy);
    ryy.push_back(w * q.yy);
    axy.push_back(w * p.xy);
    rxy.push_back(w * q.xy);
  }
  using reference::relative_l2_error;
  return {relative_l2_error(a, r), relative_l2_error(axx, rxx), relative_l2_error(ayy, ryy),
          relative_l2_error(axy, rxy)};
}

/// Area-weighted mean over the blocks whose centroid lies within `radius` of the centre.
Stress2 centre_mean(const std::vector<BlockSample>& blocks, Stress2 BlockSample::*which, double radius) {
  Stress2 s;
  double w = 0.0;
  for (const auto& b : blocks) {
    if (std::hypot(b.x, b.y) > radius || !b.has_fem) continue;
    const Stress2& t = b.*which;
    s.xx += b.area * t.xx;
    s.yy += b.area * t.yy;
    s.xy += b.area * t.xy;
    w += b.area;
  }
  if (w > 0.0) {
    s.xx /= w;
    s.yy /= w;
    s.xy /= w;
  }
  return s;
}

double relative_difference(double a, double r) { return std::abs(a - r) / std::abs(r); }

CentreError centre_error(const Stress2& a, const Stress2& r) {
  return {relative_difference(a.xx, r.xx), relative_difference(a.yy, r.yy)};
}

void compare_centre(const StaticSetup& st, StaticComparison& c) {
  c.centre_radius = kCentreRegionShare * st.radius;
  c.centre_dda = centre_mean(c.blocks, &BlockSample::dda, c.centre_radius);
  c.centre_fem = centre_mean(c.blocks, &BlockSample::fem, c.centre_radius);
  c.centre_ana = centre_mean(c.blocks, &BlockSample::ana, c.centre_radius);
  c.has_centre = !st.slit;
  c.centre_point_ana = reference::hondros_centre({st.diameter, 1.0}, {st.load, st.half_angle});
  c.centre_dda_fem = centre_error(c.centre_dda, c.centre_fem);
  c.centre_dda_ana = centre_error(c.centre_dda, c.centre_ana);
  c.centre_fem_ana = centre_error(c.centre_fem, c.centre_ana);
}

/// Where a block lies, for the list of the worst ones: the feature within reach that explains
/// an error, or "interior".
std::string where_is(const BlockSample& b, const StaticSetup& st, double h) {
  const double r = std::hypot(b.x, b.y);
  const double theta = std::atan2(b.y, b.x);
  if (st.slit) {
    const double c = std::cos(st.slit->inclination), s = std::sin(st.slit->inclination);
    for (const double sign : {1.0, -1.0})
      if (std::hypot(b.x - sign * 0.5 * st.slit->length * c, b.y - sign * 0.5 * st.slit->length * s) <
          kNearBlockSizes * h)
        return "near a slit tip";
  }
  if (st.flattened && std::abs(b.y) > st.radius * std::cos(st.half_angle) - kNearBlockSizes * h &&
      std::abs(b.x) < st.radius * std::sin(st.half_angle) + kNearBlockSizes * h)
    return b.y > 0 ? "near the top flat" : "near the bottom flat (supports differ)";
  const double from_axis = std::min(std::abs(theta - kPi / 2), std::abs(theta + kPi / 2));
  if (!st.flattened && r > st.radius - kNearBlockSizes * h &&
      from_axis < st.half_angle + kNearBlockSizes * h / st.radius)
    return "near a loaded arc";
  if (r > st.radius - kFreeRimBlockSizes * h) return "at the free rim";
  return "interior";
}

/// The worst kWorstPercent of the blocks against the FEM (at least one), worst first.
void find_worst_blocks(const StaticSetup& st, double h, StaticComparison& c) {
  double ref_rms = 0.0, wsum = 0.0;
  for (const auto& b : c.blocks)
    if (b.has_fem) {
      ref_rms += b.area * (b.fem.xx * b.fem.xx + b.fem.yy * b.fem.yy + 2 * b.fem.xy * b.fem.xy);
      wsum += b.area;
    }
  c.fem_rms = std::sqrt(ref_rms / wsum);
  for (std::size_t i = 0; i < c.blocks.size(); ++i) {
    const auto& b = c.blocks[i];
    if (!b.has_fem) continue;
    const double dxx = b.dda.xx - b.fem.xx, dyy = b.dda.yy - b.fem.yy, dxy = b.dda.xy - b.fem.xy;
    c.worst.push_back({i, std::sqrt(dxx * dxx + dyy * dyy + 2 * dxy * dxy) / c.fem_rms, ""});
  }
  std::sort(c.worst.begin(), c.worst.end(), [](const WorstBlock& a, const WorstBlock& b) {
    return a.error > b.error || (a.error == b.error && a.block < b.block);
  });
  if (!c.worst.empty()) c.worst.resize(std::max<std::size_t>(1, c.worst.size() * kWorstPercent / 100));
  c.near_distance = kNearBlockSizes * h;
  for (auto& w : c.worst) {
    w.where = where_is(c.blocks[w.block], st, h);
    ++c.worst_where[w.where];
  }
}

/// The loaded (x = 0) and the horizontal (y = 0) diameter, at points inside a block of the
/// deformed twin and inside the FEM mesh.
std::vector<ProfileSample> sample_profiles(const StaticSetup& st, const StaticDdaRun& dda, const StaticFemRun& fem) {
  const reference::Disc disc{st.diameter, 1.0};
  const reference::HondrosLoad hondros{st.load, st.half_angle};
  const auto& blocks = dda.engine->blocks();
  std::vector<ProfileSample> out;
  const double rr = st.radius * (1.0 - kProfileRimClearance);
  const double ry = st.flattened ? rr * std::cos(st.half_angle) : rr;
  for (const auto& [name, x0, y0, x1, y1] :
       {std::tuple{"loaded", 0.0, -ry, 0.0, ry}, std::tuple{"horizontal", -rr, 0.0, rr, 0.0}}) {
    for (int k = 0; k < kProfilePoints; ++k) {
      const double t = static_cast<double>(k) / (kProfilePoints - 1);
      const double x = x0 + t * (x1 - x0), y = y0 + t * (y1 - y0);
      const auto blk = dda::find_block(blocks, x, y);
      const auto f = fem_stress_at(*fem.solution, x, y);
      if (blk < 0 || !f) continue;  // inside a slit or just outside a polygonal rim
      const auto& s = blocks.stress[static_cast<std::size_t>(blk)];
      ProfileSample p;
      p.profile = name;
      p.s = x0 == x1 ? y : x;
      p.x = x;
      p.y = y;
      p.dda = {s[0], s[1], s[2]};
      p.fem = *f;
      p.ana = {std::nan(""), std::nan(""), std::nan("")};
      if (st.analytic) p.ana = reference::hondros_series(disc, hondros, x, y);
      out.push_back(p);
    }
  }
  return out;
}

}  // namespace

StaticComparison compare_static(const StaticSetup& st, const StaticDdaRun& dda, const StaticFemRun& fem) {
  StaticComparison c;
  c.blocks = sample_references(st, dda, fem, c.outside_fem);
  compare_centre(st, c);
  c.dda_fem = field_error(c.blocks, &BlockSample::dda, &BlockSample::fem);
  c.dda_fem_inner = field_error(c.blocks, &BlockSample::dda, &BlockSample::fem, kInnerDiscShare * st.radius);
  if (st.analytic) {
    c.dda_ana = field_error(c.blocks, &BlockSample::dda, &BlockSample::ana);
    c.fem_ana = field_error(c.blocks, &BlockSample::fem, &BlockSample::ana);
  }
  find_worst_blocks(st, dda.mean_block_size, c);
  c.profiles = sample_profiles(st, dda, fem);
  return c;
}

}  // namespace ddafrac::coupling
