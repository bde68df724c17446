// Engine: energies stored by the blocks and contacts, and the block terms of a step's energy ledger.
#include "ddafrac/dda/engine.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "ddafrac/dda/contact_mechanics.hpp"
#include "ddafrac/dda/geometry.hpp"
#include "deterministic_sum.hpp"

namespace ddafrac::dda {

using detail::chunked_sum;

namespace {
/// ½·(m/A)·Vᵀ·(∫ Tᵀ·T dA)·V: the kinetic energy of a block moving with V, J/m.
double kinetic_energy(double mass_per_area, const Mat6& unit_mass, const Vec6& v) {
  return 0.5 * mass_per_area * v.dot(unit_mass * v);
}
/// ½·A·σᵀ·C·σ: the strain energy of a block of area A under stress σ, J/m.
double strain_energy(double area, const MaterialData& mat, const Vec3& stress) {
  return 0.5 * area * stress.dot(mat.compliance * stress);
}
}  // namespace

Engine::BlockStepEnergy Engine::block_step_energy(double dt) const {
  // Terms of the linear system of the step (block_terms): ½·Δεᵀ·A·E·Δε of the elasticity,
  // ½·p·|T·D|² of the anchors, the work of the damping force −η·M·V1 (booked apart), and in static mode the kinetic
  // energy ½·V1ᵀ·M·V1 thrown away with the velocities; the work of gravity, point loads and moving anchor targets.
  // Beside them, what block and anchors store at the end of the linearised step (ResidualSources: record_step sets it
  // against the moved geometry's).
  const auto& an = scene_.analysis;
  const double t0 = time_, t1 = time_ + dt;
  const bool dynamic = active_.dynamic;
  const double eta = an.mass_damping;
  return chunked_sum<BlockStepEnergy>(static_cast<std::int64_t>(blocks_.block_count()), [&](std::int64_t i) {
    BlockStepEnergy b;
    StepEnergy& e = b.step;
    Energies& end = b.linearised_end;
    const Vec6& d = d_[i];
    const PolygonIntegrals& g = blocks_.geometry[i];
    const MaterialData& mat = blocks_.materials[static_cast<std::size_t>(blocks_.material[i])];
    const Vec3 de = d.segment<3>(3);
    e.numerical += 0.5 * g.area * de.dot(mat.elastic * de);
    const Vec3 stress_end = blocks_.stress[i] + mat.elastic * de;
    end.strain = strain_energy(g.area, mat, stress_end);
    const Mat6 unit_mass = mass_integral(g);
    const Mat6 m = (blocks_.mass[i] / g.area) * unit_mass;
    const Vec6 v1 = dynamic ? Vec6(2.0 / dt * d - blocks_.velocity[i]) : Vec6(2.0 / dt * d);
    e.damping += eta * v1.dot(m * d);
    if (dynamic)
      end.kinetic = kinetic_energy(blocks_.mass[i] / g.area, unit_mass, v1);
    else
      e.numerical += 0.5 * v1.dot(m * v1);
    e.work_gravity += blocks_.mass[i] * (an.gravity[0] * d[kU] + an.gravity[1] * d[kV]);
    for (Index l = blocks_.load_offsets[i]; l < blocks_.load_offsets[i + 1]; ++l) {
      const PointLoad& p = blocks_.loads[static_cast<std::size_t>(l)];
      e.work_loads += Eigen::Vector2d(p.fx, p.fy).dot(displacement_matrix(g.cx, g.cy, p.x, p.y) * d);
    }
    for (Index a = blocks_.anchor_offsets[i]; a < blocks_.anchor_offsets[i + 1]; ++a) {
      const Anchor& p = blocks_.anchors[static_cast<std::size_t>(a)];
      const Eigen::Vector2d step = displacement_matrix(g.cx, g.cy, p.x, p.y) * d;
      e.numerical += 0.5 * anchor_penalty_ * step.squaredNorm();
      const Eigen::Vector2d r0 = anchor_stretch(p, p.x, p.y, t0), r1 = anchor_stretch(p, p.x, p.y, t1);
      e.work_supports += 0.5 * anchor_penalty_ * (r1.squaredNorm() - r0.squaredNorm());
      const Eigen::Vector2d linear = Eigen::Vector2d(p.x, p.y) + step;
      end.support += 0.5 * anchor_penalty_ * anchor_stretch(p, linear.x(), linear.y(), t1).squaredNorm();
    }
    return b;
  });
}

double Engine::block_kinetic_energy(Index i) const {
  const PolygonIntegrals& g = blocks_.geometry[i];
  return kinetic_energy(blocks_.mass[i] / g.area, mass_integral(g), blocks_.velocity[i]);
}

double Engine::block_strain_energy(Index i) const {
  const MaterialData& mat = blocks_.materials[static_cast<std::size_t>(blocks_.material[i])];
  return strain_energy(blocks_.geometry[i].area, mat, blocks_.stress[i]);
}

Eigen::Vector2d Engine::anchor_stretch(const Anchor& p, double x, double y, double t) {
  return {x - p.x_start - p.vx * t, y - p.y_start - p.vy * t};
}

Energies Engine::energies() const {
  Energies e;
  const auto n = static_cast<std::int64_t>(blocks_.block_count());
  e.kinetic = chunked_sum(n, [&](std::int64_t i) { return block_kinetic_energy(i); });
  e.kinetic_free = chunked_sum(n, [&](std::int64_t i) {
    return blocks_.anchor_offsets[i] != blocks_.anchor_offsets[i + 1] ? 0.0 : block_kinetic_energy(i);
  });
  e.strain = chunked_sum(n, [&](std::int64_t i) { return block_strain_energy(i); });
  e.contact = chunked_sum(static_cast<std::int64_t>(set_.contacts.size()),
                          [&](std::int64_t k) { return contact_energy(set_.contacts[k]).total(); });
  e.support = chunked_sum(static_cast<std::int64_t>(blocks_.anchors.size()), [&](std::int64_t a) {
    const Anchor& p = blocks_.anchors[static_cast<std::size_t>(a)];
    return 0.5 * anchor_penalty_ * anchor_stretch(p, p.x, p.y, time_).squaredNorm();
  });
  return e;
}

}  // namespace ddafrac::dda
