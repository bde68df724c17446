// Engine: construction, the time step (open-close iteration, step-size control, acceptance) and
// what an accepted step records (docs/design.md §7).
#include "ddafrac/dda/engine.hpp"

#include <fmt/core.h>
#include <omp.h>

#include <algorithm>
#include <cmath>

#include "contact_commit.hpp"
#include "ddafrac/dda/contact_mechanics.hpp"
#include "ddafrac/dda/geometry.hpp"
#include "deterministic_sum.hpp"

namespace ddafrac::dda {

namespace {
using detail::chunked_sum;
using detail::commit_and_store;

/// What committing the contacts of a step adds up: their step energy, the cohesive contacts that
/// failed, and whether any slides.
struct ContactCommit {
  StepEnergy energy;
  ResidualSources residual;
  long cohesion_lost = 0;
  bool sliding = false;
  ContactCommit& operator+=(const ContactCommit& o) {
    energy += o.energy;
    residual += o.residual;
    cohesion_lost += o.cohesion_lost;
    sliding = sliding || o.sliding;
    return *this;
  }
};

class Timer {
 public:
  explicit Timer(double& sink) : sink_(sink), start_(omp_get_wtime()) {}
  ~Timer() { sink_ += omp_get_wtime() - start_; }
  Timer(const Timer&) = delete;
  Timer& operator=(const Timer&) = delete;

 private:
  double& sink_;
  double start_;
};
}  // namespace

std::vector<std::string> ActiveTerms::names() const {
  std::vector<std::string> n;
  n.push_back(dynamic ? "inertia (dynamic, velocities carried)" : "inertia (static, velocities reset)");
  if (elasticity) n.push_back("elastic stiffness");
  if (initial_stress) n.push_back("initial stress");
  if (gravity) n.push_back("gravity");
  if (point_loads) n.push_back("point loads");
  if (anchors) n.push_back("fixed/prescribed points");
  if (contacts) n.push_back("contact springs");
  if (friction) n.push_back("friction (sliding contacts)");
  if (cohesion) n.push_back("cohesion and tension of real joints closed at t = 0");
  if (bonded_joints) n.push_back("bonded virtual joints");
  if (fracture) n.push_back("fracture check");
  if (damping) n.push_back("mass damping");
  return n;
}

Engine::Engine(scene::Scene scene, const meshes::Mesh& mesh, EngineOptions options)
    : scene_(std::move(scene)), options_(std::move(options)) {
  if (scene_.real_joints >= scene_.joint_sets.size())
    throw std::invalid_argument("the scene names no joint set for real joints (contacts.real_joints)");
  for (const auto& js : scene_.joint_sets)
    if (!(js.normal_stiffness > 0.0 && js.shear_stiffness > 0.0))
      throw std::invalid_argument(fmt::format("joint set '{}' has no positive normal and shear stiffness", js.name));
  blocks_ = build_block_system(scene_, mesh, options_.bond_virtual_joints, options_.point_loads, options_.anchors);
  for (const auto& gauge : scene_.gauges) {
    const Index b = find_block(blocks_, gauge.position[0], gauge.position[1]);
    if (b < 0)
      throw std::invalid_argument(
          fmt::format("gauge '{}' at ({:.6g}, {:.6g}) m lies in no block at t = 0 (outside "
                      "the bodies or in a slot)",
                      gauge.name, gauge.position[0], gauge.position[1]));
    gauge_blocks_.push_back(b);
  }
  const auto& an = scene_.analysis;
  if (!(an.dt_max > 0.0)) throw std::invalid_argument("analysis.dt_max must be positive");
  dt_ = an.dt_max;
  dt_prev_ = dt_;
  allowed_ = options_.allowed_displacement > 0.0 ? options_.allowed_displacement
                                                 : an.max_displacement_ratio * blocks_.model_half_height;
  if (!(allowed_ > 0.0))
    throw std::invalid_argument("allowed step displacement must be positive (max_displacement_ratio)");
  options_.detection.search_distance = an.search_distance_factor * allowed_;
  options_.detection.skin = an.pair_list_skin_factor * options_.detection.search_distance;
  options_.solver.tolerance = an.solver_tolerance;
  if (!(an.penalty > 0.0)) throw std::invalid_argument("analysis.penalty must be positive");
  anchor_penalty_ = options_.anchor_penalty_factor * an.penalty;
  const std::size_t n = blocks_.block_count();
  d_.assign(n, Vec6::Zero());
  active_.dynamic = an.mode == scene::Mode::Dynamic;
  active_.gravity = an.gravity[0] != 0.0 || an.gravity[1] != 0.0;
  active_.point_loads = !blocks_.loads.empty();
  active_.anchors = !blocks_.anchors.empty();
  active_.bonded_joints = !blocks_.joints.empty();
  active_.fracture = !blocks_.joints.empty();
  active_.damping = an.mass_damping > 0.0;
  if (!active_.dynamic) std::fill(blocks_.velocity.begin(), blocks_.velocity.end(), Vec6::Zero());
  if (an.fracture_stress_radius > 0.0)
    stress_neighbourhoods_ = stress_neighbourhoods(blocks_, an.fracture_stress_radius);
}

std::string Engine::describe_block(Index b) const {
  if (b < 0) return "no block";
  const auto& g = blocks_.geometry[b];
  const Index body = blocks_.body[b];
  return fmt::format("block {} (body '{}', centroid ({:.6g}, {:.6g}) m)", b,
                     body >= 0 ? scene_.bodies[static_cast<std::size_t>(body)].name : std::string("?"), g.cx, g.cy);
}

std::string Engine::describe_contact(Index k) const {
  if (k < 0) return "no contact";
  const Contact& c = set_.contacts[k];
  return fmt::format(
      "contact {} (vertex of block {} at ({:.6g}, {:.6g}) m against an edge of block {}, gap {:.3g} m, {} -> {})", k,
      c.vblock, blocks_.vx[c.vertex], blocks_.vy[c.vertex], c.eblock, c.d_iter, to_string(c.state), to_string(c.trial));
}

void Engine::trouble(const std::string& what) const {
  throw NumericalTrouble(
      fmt::format("numerical trouble at step {}, t = {:.9g} s, dt = {:.3g} s: {}", step_ + 1, time_, dt_, what));
}

Energies Engine::accept(double dt) {
  const auto n = static_cast<std::int64_t>(blocks_.block_count());
  const auto nc = static_cast<std::int64_t>(set_.contacts.size());
  const BlockStepEnergy blocks_energy = block_step_energy(dt);
  ledger_.total += blocks_energy.step;
  // One pass over the contacts: each term books a contact's step energy and then commits it
  // (the term touches its own contact only, so the chunked sum stays thread-count independent).
  const ContactCommit committed = chunked_sum<ContactCommit>(nc, [&](std::int64_t k) {
    Contact& c = set_.contacts[k];
    ContactCommit one;
    const bool held = c.held(blocks_.joints);
    one.energy = contact_step_energy(c, held);
    double& source = !c.same_line                    ? one.residual.contacts_new
                     : c.state == ContactState::Open ? one.residual.contacts_reclosed
                                                     : one.residual.contacts_kept;
    source += contact_start_mismatch(c, held);
    one.cohesion_lost = c.cohesion_lost ? 1 : 0;
    commit_and_store(c);
    c.was_bonded = c.held(blocks_.joints);
    one.sliding = c.state == ContactState::Sliding;
    return one;
  });
  ledger_.total += committed.energy;
  ledger_.residual_sources += committed.residual;
  if (committed.sliding) active_.friction = true;
  stats_.cohesion_failures += committed.cohesion_lost;
  const bool dynamic = active_.dynamic;
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) {
    const Vec6& d = d_[i];
    const PolygonIntegrals& g = blocks_.geometry[i];
    for (Index v = blocks_.begin(i); v < blocks_.end(i); ++v)
      displace_point(g.cx, g.cy, d, blocks_.vx[v], blocks_.vy[v]);
    for (Index l = blocks_.load_offsets[i]; l < blocks_.load_offsets[i + 1]; ++l) {
      PointLoad& p = blocks_.loads[static_cast<std::size_t>(l)];
      displace_point(g.cx, g.cy, d, p.x, p.y);
    }
    for (Index a = blocks_.anchor_offsets[i]; a < blocks_.anchor_offsets[i + 1]; ++a) {
      Anchor& p = blocks_.anchors[static_cast<std::size_t>(a)];
      displace_point(g.cx, g.cy, d, p.x, p.y);
    }
    const MaterialData& mat = blocks_.materials[static_cast<std::size_t>(blocks_.material[i])];
    const Vec3 de = d.segment<3>(3);
    blocks_.strain[i] += de;
    blocks_.stress[i] += mat.elastic * de;
    if (dynamic)
      blocks_.velocity[i] = 2.0 / dt * d - blocks_.velocity[i];
    else
      blocks_.velocity[i].setZero();
  }
  update_block_geometry(blocks_);
  return blocks_energy.linearised_end;
}

std::vector<Engine::BodyLoad> Engine::body_loads() const {
  std::vector<BodyLoad> out;
  std::vector<long> count;
  for (const Anchor& p : blocks_.anchors) {
    const Index body = blocks_.body[static_cast<std::size_t>(p.block)];
    std::size_t k = 0;
    while (k < out.size() && out[k].body != body) ++k;
    if (k == out.size()) {
      out.push_back({body, 0.0, 0.0, 0.0, 0.0});
      count.push_back(0);
    }
    // Spring force on the body: penalty · (target − position), target at the current time.
    out[k].fx += anchor_penalty_ * (p.x_start + p.vx * time_ - p.x);
    out[k].fy += anchor_penalty_ * (p.y_start + p.vy * time_ - p.y);
    out[k].ux += p.x - p.x_start;
    out[k].uy += p.y - p.y_start;
    ++count[k];
  }
  for (std::size_t k = 0; k < out.size(); ++k) {
    out[k].ux /= static_cast<double>(count[k]);
    out[k].uy /= static_cast<double>(count[k]);
  }
  std::sort(out.begin(), out.end(), [](const BodyLoad& p, const BodyLoad& q) { return p.body < q.body; });
  return out;
}

Engine::OpenClose Engine::iterate_open_close(StepReport& rep) {
  const int cap = std::max(1, scene_.analysis.open_close_max);
  const auto n = static_cast<std::int64_t>(blocks_.block_count());
  OpenClose oc;
  while (oc.iterations < cap) {
    ++oc.iterations;
    {
      Timer t(stats_.times.assembly);
      assemble(oc.iterations == 1);
    }
    SolveReport sr;
    {
      Timer t(stats_.times.solve);
      sr = solve(matrix_, set_, rhs_, d_, options_.solver, solver_work_);
    }
    ++stats_.solves;
    stats_.cg_total += sr.iterations;
    stats_.cg_max = std::max(stats_.cg_max, sr.iterations);
    rep.cg_iterations += sr.iterations;
    for (std::int64_t i = 0; i < n; ++i)
      if (!d_[i].allFinite()) trouble("NaN in the solution at " + describe_block(static_cast<Index>(i)));
    if (!sr.converged) {
      oc.solver_ok = false;
      return oc;
    }
    Timer t(stats_.times.judgement);
    if (judge(oc.worst_contact)) {
      oc.converged = true;
      return oc;
    }
  }
  return oc;
}

double Engine::largest_step_displacement(Index& worst) const {
  const auto n = static_cast<std::int64_t>(blocks_.block_count());
  std::vector<double> block_disp(static_cast<std::size_t>(n));
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) {
    const PolygonIntegrals& g = blocks_.geometry[i];
    double m = 0.0;
    for (Index v = blocks_.begin(i); v < blocks_.end(i); ++v)
      m = std::max(m, (displacement_matrix(g.cx, g.cy, blocks_.vx[v], blocks_.vy[v]) * d_[i]).norm());
    block_disp[static_cast<std::size_t>(i)] = m;
  }
  worst = -1;
  double dmax = 0.0;
  for (std::int64_t i = 0; i < n; ++i)
    if (block_disp[static_cast<std::size_t>(i)] > dmax) {
      dmax = block_disp[static_cast<std::size_t>(i)];
      worst = static_cast<Index>(i);
    }
  return dmax;
}

void Engine::record_step(StepReport& rep, const Energies& linearised_end) {
  ++stats_.steps;
  stats_.dt_min = stats_.steps == 1 ? rep.dt : std::min(stats_.dt_min, rep.dt);
  stats_.dt_max = std::max(stats_.dt_max, rep.dt);
  stats_.dt_sum += rep.dt;
  stats_.open_close_total += rep.open_close;
  stats_.open_close_max = std::max(stats_.open_close_max, rep.open_close);
  rep.contacts = set_.contacts.size();
  const auto nc = static_cast<std::int64_t>(set_.contacts.size());
  std::size_t closed = 0, sliding = 0;
  double deepest = 0.0;
#pragma omp parallel for schedule(static) reduction(+ : closed, sliding) reduction(max : deepest)
  for (std::int64_t k = 0; k < nc; ++k) {
    const Contact& c = set_.contacts[k];
    if (c.state == ContactState::Open) continue;
    ++closed;
    if (c.state == ContactState::Sliding) ++sliding;
    deepest = std::max(deepest, -c.d_iter);
  }
  rep.closed = closed;
  rep.sliding = sliding;
  rep.max_penetration = deepest;
  stats_.max_penetration = std::max(stats_.max_penetration, rep.max_penetration);
  {
    Timer t(stats_.times.update);
    rep.energy = energies();
  }
  ledger_.stored = rep.energy;
  ledger_.residual_sources.blocks +=
      (rep.energy.strain + rep.energy.kinetic) - (linearised_end.strain + linearised_end.kinetic);
  ledger_.residual_sources.supports += rep.energy.support - linearised_end.support;
  ledger_.largest_balance_error = std::max(ledger_.largest_balance_error, std::abs(ledger_.balance_error()));
  rep.ledger = ledger_;
}

StepReport Engine::step(double max_dt) {
  StepReport rep;
  if (step_ == 0) ledger_.initial = energies().stored();
  {
    Timer t(stats_.times.detection);
    detect();
  }
  const auto& an = scene_.analysis;
  const double dt_floor = an.dt_max * options_.dt_floor_fraction;
  const auto n = static_cast<std::int64_t>(blocks_.block_count());
  const BlockVector d_prev = d_;
  int cuts = 0;
  Energies linearised_end;
  // A failed trial step of length dt cuts dt and starts again from the step's start; true: dt is
  // below its floor.
  const auto cut_below_floor = [&](double dt, long& why) {
    ++why;
    ++cuts;
    dt_ = dt * options_.dt_cut_factor;
    reset_trials();
    return dt_ < dt_floor;
  };
  // Solve, judge and check the step; cut dt and start again until the step is acceptable.
  for (;;) {
    const double dt = std::min(dt_, max_dt);
    // Warm start: the previous step's displacement, scaled to the new step length.
    const double scale = dt / dt_prev_;
#pragma omp parallel for schedule(static)
    for (std::int64_t i = 0; i < n; ++i) d_[i] = scale * d_prev[i];
    {
      Timer t(stats_.times.assembly);
      block_terms(dt);
    }
    const OpenClose oc = iterate_open_close(rep);
    if (!oc.converged) {
      if (cut_below_floor(dt, oc.solver_ok ? stats_.cuts_open_close : stats_.cuts_solver)) {
        if (!oc.solver_ok) trouble("the linear solver did not converge and dt fell below its floor");
        trouble(
            fmt::format("open-close iteration did not converge in {} iterations and dt fell below its floor; worst: {}",
                        oc.iterations, describe_contact(oc.worst_contact)));
      }
      continue;
    }
    Index worst = -1;
    const double dmax = largest_step_displacement(worst);
    if (dmax > allowed_) {
      if (cut_below_floor(dt, stats_.cuts_displacement))
        trouble(
            fmt::format("step displacement {:.3g} m exceeds the allowed {:.3g} m even with dt at its floor; worst: {}",
                        dmax, allowed_, describe_block(worst)));
      continue;
    }
    {
      Timer t(stats_.times.update);
      linearised_end = accept(dt);
    }
    time_ += dt;
    // Fracture check on the converged, accepted step. Breaks take effect from the next step
    // (the joint's contacts become real joints at the next detection); the step is not re-solved,
    // so a joint carries at most one step's load increment beyond its strength.
    {
      Timer t(stats_.times.fracture);
      rep.new_cracks = fracture_check();
    }
    rep.cracks = crack_counts_;
    ++step_;
    dt_prev_ = dt;
    if (cuts == 0 && oc.iterations <= options_.easy_open_close && dt_ < an.dt_max)
      dt_ = std::min(an.dt_max, dt_ * options_.dt_grow_factor);
    rep.step = step_;
    rep.time = time_;
    rep.dt = dt;
    rep.open_close = oc.iterations;
    rep.cuts = cuts;
    rep.max_displacement = dmax;
    break;
  }
  record_step(rep, linearised_end);
  return rep;
}

}  // namespace ddafrac::dda
