#include "ddafrac/dda/crack_metrics.hpp"

#include <algorithm>
#include <limits>
#include <numeric>
#include <utility>

namespace ddafrac::dda {

namespace {

constexpr double kNever = std::numeric_limits<double>::infinity();  // an intact joint's break time
constexpr double kFromStart = -kNever;                              // a joint broken with no crack event

/// Union–find over the blocks: a fragment is a root with the area of all its blocks. Joining two
/// fragments updates their body's tallies. The smaller block index stays the root, so the result
/// depends only on the order of the joins, which the callers fix.
class Fragments {
 public:
  Fragments(const BlockSystem& blocks, const std::vector<Index>& slot_of_block, std::vector<BodyCracks>& bodies)
      : slot_of_block_(slot_of_block), bodies_(bodies), parent_(blocks.block_count()), area_(blocks.block_count()) {
    std::iota(parent_.begin(), parent_.end(), Index{0});
    for (std::size_t b = 0; b < area_.size(); ++b)
      area_[b] = blocks.mass[b] / blocks.materials[static_cast<std::size_t>(blocks.material[b])].density;
  }

  double area(std::size_t block) const { return area_[block]; }

  void join(Index a, Index b) {
    Index ra = root(a), rb = root(b);
    if (ra == rb) return;
    if (rb < ra) std::swap(ra, rb);
    BodyCracks& body = bodies_[static_cast<std::size_t>(slot_of_block_[static_cast<std::size_t>(a)])];
    auto& area_a = area_[static_cast<std::size_t>(ra)];
    const double area_b = area_[static_cast<std::size_t>(rb)];
    body.through_fragments -= is_through(body, area_a) + is_through(body, area_b);
    area_a += area_b;
    body.through_fragments += is_through(body, area_a);
    body.largest_fragment_area = std::max(body.largest_fragment_area, area_a);
    --body.fragments;
    parent_[static_cast<std::size_t>(rb)] = ra;
  }

  static long is_through(const BodyCracks& body, double area) {
    return area >= kThroughCrackFragmentFraction * body.area ? 1 : 0;
  }

 private:
  Index root(Index b) {
    while (parent_[static_cast<std::size_t>(b)] != b) {
      auto& p = parent_[static_cast<std::size_t>(b)];
      p = parent_[static_cast<std::size_t>(p)];  // path halving
      b = p;
    }
    return b;
  }

  const std::vector<Index>& slot_of_block_;
  std::vector<BodyCracks>& bodies_;
  std::vector<Index> parent_;
  std::vector<double> area_;  // m², of the fragment rooted here
};

void add_crack(BodyCracks& body, CrackType type, double length) {
  if (type == CrackType::Tensile) {
    ++body.cracks_tensile;
    body.length_tensile += length;
  } else if (type == CrackType::Shear) {
    ++body.cracks_shear;
    body.length_shear += length;
  } else {
    ++body.cracks_untyped;
  }
}

void copy_crack_tallies(const std::vector<BodyCracks>& from, std::vector<BodyCracks>& to) {
  for (std::size_t k = 0; k < from.size(); ++k) {
    to[k].cracks_tensile = from[k].cracks_tensile;
    to[k].cracks_shear = from[k].cracks_shear;
    to[k].cracks_untyped = from[k].cracks_untyped;
    to[k].length_tensile = from[k].length_tensile;
    to[k].length_shear = from[k].length_shear;
  }
}

void copy_fragment_tallies(const std::vector<BodyCracks>& from, std::vector<BodyCracks>& to) {
  for (std::size_t k = 0; k < from.size(); ++k) {
    to[k].fragments = from[k].fragments;
    to[k].through_fragments = from[k].through_fragments;
    to[k].largest_fragment_area = from[k].largest_fragment_area;
  }
}

}  // namespace

CrackHistory crack_history(const BlockSystem& blocks, const std::vector<CrackEvent>& events,
                           const std::vector<double>& times) {
  const std::size_t nb = blocks.block_count();
  const auto body_of_joint = [&](const Joint& j) { return blocks.body[static_cast<std::size_t>(j.block_a)]; };

  // The bodies with virtual joints, in body order, and each block's entry among them.
  std::vector<Index> jointed;
  for (const Joint& j : blocks.joints) jointed.push_back(body_of_joint(j));
  std::sort(jointed.begin(), jointed.end());
  jointed.erase(std::unique(jointed.begin(), jointed.end()), jointed.end());
  const auto slot_of_body = [&](Index body) {
    const auto it = std::lower_bound(jointed.begin(), jointed.end(), body);
    return it != jointed.end() && *it == body ? static_cast<Index>(it - jointed.begin()) : Index{-1};
  };
  std::vector<Index> slot_of_block(nb);
  for (std::size_t b = 0; b < nb; ++b) slot_of_block[b] = slot_of_body(blocks.body[b]);

  // t = 0, before any joint breaks: every block its own fragment.
  CrackHistory h;
  std::vector<BodyCracks> start(jointed.size());
  for (std::size_t k = 0; k < jointed.size(); ++k) start[k].body = jointed[k];
  Fragments fragments(blocks, slot_of_block, start);
  for (std::size_t b = 0; b < nb; ++b)
    if (slot_of_block[b] >= 0) start[static_cast<std::size_t>(slot_of_block[b])].area += fragments.area(b);
  for (std::size_t b = 0; b < nb; ++b) {
    if (slot_of_block[b] < 0) continue;
    BodyCracks& body = start[static_cast<std::size_t>(slot_of_block[b])];
    ++body.fragments;
    body.through_fragments += Fragments::is_through(body, fragments.area(b));
    body.largest_fragment_area = std::max(body.largest_fragment_area, fragments.area(b));
  }

  // When each joint broke; the events in time order (ties in the order they happened).
  std::vector<double> broken_at(blocks.joints.size(), kNever);
  for (std::size_t k = 0; k < blocks.joints.size(); ++k)
    if (blocks.joints[k].broken) broken_at[k] = kFromStart;
  for (const CrackEvent& e : events) broken_at[static_cast<std::size_t>(e.joint)] = e.t;
  std::vector<std::size_t> order(events.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return events[a].t < events[b].t; });
  const auto event_joint = [&](std::size_t p) {
    return blocks.joints[static_cast<std::size_t>(events[order[p]].joint)];
  };

  h.first_crack.assign(jointed.size(), std::nullopt);
  h.first_through_crack.assign(jointed.size(), std::nullopt);
  for (std::size_t k = 0; k < blocks.joints.size(); ++k) {
    if (broken_at[k] != kFromStart) continue;
    const auto slot = static_cast<std::size_t>(slot_of_body(body_of_joint(blocks.joints[k])));
    add_crack(start[slot], blocks.joints[k].failure, blocks.joints[k].length);
    h.first_crack[slot] = 0.0;
  }
  for (std::size_t p = 0; p < order.size(); ++p) {
    auto& first = h.first_crack[static_cast<std::size_t>(slot_of_body(body_of_joint(event_joint(p))))];
    if (!first) first = events[order[p]].t;
  }

  // Requested times in ascending order.
  std::vector<std::size_t> by_time(times.size());
  std::iota(by_time.begin(), by_time.end(), std::size_t{0});
  std::stable_sort(by_time.begin(), by_time.end(), [&](std::size_t a, std::size_t b) { return times[a] < times[b]; });
  h.at_times.assign(times.size(), start);

  // Crack counts and lengths: forward in time, adding each event's joint.
  {
    std::vector<BodyCracks> tally = start;
    std::size_t p = 0;
    const auto add_until = [&](double t) {
      for (; p < order.size() && events[order[p]].t <= t; ++p) {
        const Joint& j = event_joint(p);
        add_crack(tally[static_cast<std::size_t>(slot_of_body(body_of_joint(j)))], events[order[p]].type, j.length);
      }
    };
    for (const std::size_t s : by_time) {
      add_until(times[s]);
      copy_crack_tallies(tally, h.at_times[s]);
    }
    add_until(kNever);
    h.now = tally;
  }

  // Fragments: a union–find can join but not split, so walk backwards in time from now, when
  // every intact joint is joined, re-joining each event's joint.
  {
    std::vector<BodyCracks>& state = start;  // `fragments` updates it
    for (std::size_t k = 0; k < blocks.joints.size(); ++k)
      if (broken_at[k] == kNever) fragments.join(blocks.joints[k].block_a, blocks.joints[k].block_b);
    copy_fragment_tallies(state, h.now);
    std::size_t s = by_time.size();           // requested times not yet recorded: by_time[0 .. s)
    const auto record_from = [&](double t) {  // the state holds for the requested times ≥ t
      for (; s > 0 && times[by_time[s - 1]] >= t; --s) copy_fragment_tallies(state, h.at_times[by_time[s - 1]]);
    };
    std::size_t p = order.size();
    while (p > 0) {
      const double t = events[order[p - 1]].t;  // the state is that just after the step at t
      record_from(t);
      for (std::size_t k = 0; k < state.size(); ++k)
        if (state[k].through_fragments >= 2) h.first_through_crack[k] = t;
      for (; p > 0 && events[order[p - 1]].t == t; --p)
        fragments.join(event_joint(p - 1).block_a, event_joint(p - 1).block_b);
    }
    record_from(-kNever);
    for (std::size_t k = 0; k < state.size(); ++k)
      if (state[k].through_fragments >= 2) h.first_through_crack[k] = 0.0;  // apart from t = 0
  }
  return h;
}

}  // namespace ddafrac::dda
