#include "ddafrac/dda/contact.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace ddafrac::dda {

const char* to_string(ContactState s) {
  switch (s) {
    case ContactState::Open: return "open";
    case ContactState::Sliding: return "sliding";
    case ContactState::Locked: return "locked";
  }
  return "?";
}

namespace {

constexpr double kTwoPi = 6.283185307179586;
/// Upper bound on broad-phase grid cells per block (keeps the grid O(N) in memory).
constexpr double kMaxCellsPerBlock = 4.0;
/// Vertex-vertex capture radius relative to the shorter block edge (keeps VV local on fine meshes).
constexpr double kVertexVertexEdgeFraction = 0.1;

struct View {
  const BlockSystem& s;
  double x(Index v) const { return s.vx[static_cast<std::size_t>(v)]; }
  double y(Index v) const { return s.vy[static_cast<std::size_t>(v)]; }
  Index prev(Index block, Index v) const { return v == s.begin(block) ? s.end(block) - 1 : v - 1; }
  Index next(Index block, Index v) const { return v + 1 == s.end(block) ? s.begin(block) : v + 1; }
};

/// Angle rule: the wedge of block `block` at vertex v lies on the outer side of an edge with
/// outward unit normal (nx, ny), within the tolerance, and the vertex is convex.
bool wedge_faces_edge(const View& w, Index block, Index v, double nx, double ny, double sin_tol) {
  const Index p = w.prev(block, v), q = w.next(block, v);
  const double ax = w.x(p) - w.x(v), ay = w.y(p) - w.y(v);
  const double bx = w.x(q) - w.x(v), by = w.y(q) - w.y(v);
  if (bx * ay - by * ax <= 0.0) return false;  // reflex vertex: its edges make the contact
  const double la = std::hypot(ax, ay), lb = std::hypot(bx, by);
  return ax * nx + ay * ny >= -sin_tol * la && bx * nx + by * ny >= -sin_tol * lb;
}

/// Interior wedge of a vertex as [start angle, start + opening) (CCW from the next edge).
void wedge(const View& w, Index block, Index v, double& start, double& opening) {
  const Index p = w.prev(block, v), q = w.next(block, v);
  start = std::atan2(w.y(q) - w.y(v), w.x(q) - w.x(v));
  double end = std::atan2(w.y(p) - w.y(v), w.x(p) - w.x(v));
  opening = std::fmod(end - start + 2.0 * kTwoPi, kTwoPi);
}

double angle_mod(double a) { return std::fmod(std::fmod(a, kTwoPi) + kTwoPi, kTwoPi); }

/// Smallest angular gap between the wedges of two coincident vertices (0 if they overlap).
double wedge_gap(const View& w, Index ba, Index va, Index bb, Index vb) {
  double sa, oa, sb, ob;
  wedge(w, ba, va, sa, oa);
  wedge(w, bb, vb, sb, ob);
  const double g1 = angle_mod(sb - (sa + oa));
  const double g2 = angle_mod(sa - (sb + ob));
  if (oa + ob + g1 + g2 > kTwoPi + 1e-9) return 0.0;
  return std::min(g1, g2);
}

struct Candidate {
  bool valid = false;
  double abs_d = 0.0;
  Contact c;
};

Index find_joint(const BlockSystem& s, Index p, Index q, meshes::Index nv, meshes::Index n2,
                 meshes::Index n3) {
  if (s.joints.empty()) return -1;
  if (nv != n2 && nv != n3) return -1;
  const Index lo = std::min(p, q), hi = std::max(p, q);
  const meshes::Index a = std::min(n2, n3), b = std::max(n2, n3);
  for (Index k = s.joint_offsets[lo]; k < s.joint_offsets[lo + 1]; ++k) {
    const Joint& j = s.joints[static_cast<std::size_t>(s.joint_of_block[k])];
    if (j.block_a == lo && j.block_b == hi && j.node_a == a && j.node_b == b) return s.joint_of_block[k];
  }
  return -1;
}

/// Vertex v of block p against edge e0->e1 of block q: a contact record with gap and parameter.
Contact make_contact(const View& w, Index p, Index v, Index q, Index e0, Index e1, bool vv) {
  Contact c;
  c.vblock = p;
  c.eblock = q;
  c.vertex = v;
  c.edge0 = e0;
  c.edge1 = e1;
  c.vertex_vertex = vv;
  const double dx = w.x(e1) - w.x(e0), dy = w.y(e1) - w.y(e0);
  const double l2 = dx * dx + dy * dy;
  const double l = std::sqrt(l2);
  c.d0 = ((w.x(v) - w.x(e0)) * dy - (w.y(v) - w.y(e0)) * dx) / l;
  c.ref_t = ((w.x(v) - w.x(e0)) * dx + (w.y(v) - w.y(e0)) * dy) / l2;
  c.edge_length = l;
  c.joint = find_joint(w.s, p, q, w.s.vertex_node[static_cast<std::size_t>(v)],
                       w.s.vertex_node[static_cast<std::size_t>(e0)], w.s.vertex_node[static_cast<std::size_t>(e1)]);
  return c;
}

void offer(Candidate& slot, const Contact& c) {
  const double ad = std::abs(c.d0);
  if (!slot.valid || ad < slot.abs_d) {
    slot.valid = true;
    slot.abs_d = ad;
    slot.c = c;
  }
}

/// Narrow phase of one block pair a < b; appends at most one contact per vertex.
void narrow_phase(const View& w, Index a, Index b, const DetectionParams& prm,
                  std::vector<Candidate>& best, std::vector<Contact>& out) {
  const BlockSystem& s = w.s;
  const Index na = s.end(a) - s.begin(a);
  const Index nb = s.end(b) - s.begin(b);
  best.assign(static_cast<std::size_t>(na + nb), Candidate{});
  const double search = prm.search_distance;
  const double vv = std::min(search, kVertexVertexEdgeFraction * std::min(s.min_edge[a], s.min_edge[b]));
  const double sin_tol = std::sin(prm.angle_tolerance);
  auto slot_of = [&](Index block, Index v) -> Candidate& {
    return block == a ? best[static_cast<std::size_t>(v - s.begin(a))]
                      : best[static_cast<std::size_t>(na + v - s.begin(b))];
  };
  // Vertex-edge.
  for (int side = 0; side < 2; ++side) {
    const Index p = side == 0 ? a : b;  // vertex block
    const Index q = side == 0 ? b : a;  // edge block
    for (Index v = s.begin(p); v < s.end(p); ++v) {
      for (Index e0 = s.begin(q); e0 < s.end(q); ++e0) {
        const Index e1 = w.next(q, e0);
        const double dx = w.x(e1) - w.x(e0), dy = w.y(e1) - w.y(e0);
        const double l2 = dx * dx + dy * dy;
        const double l = std::sqrt(l2);
        const double rx = w.x(v) - w.x(e0), ry = w.y(v) - w.y(e0);
        const double d = (rx * dy - ry * dx) / l;
        if (std::abs(d) > search) continue;
        const double t = (rx * dx + ry * dy) / l2;
        if (t < 0.0 || t > 1.0) continue;
        if (std::hypot(rx, ry) <= vv || std::hypot(w.x(v) - w.x(e1), w.y(v) - w.y(e1)) <= vv) continue;
        if (!wedge_faces_edge(w, p, v, dy / l, -dx / l, sin_tol)) continue;
        offer(slot_of(p, v), make_contact(w, p, v, q, e0, e1, false));
      }
    }
  }
  // Vertex-vertex: reduce to the reference line with the largest gap (the entrance line).
  for (Index v = s.begin(a); v < s.end(a); ++v) {
    for (Index u = s.begin(b); u < s.end(b); ++u) {
      if (std::hypot(w.x(v) - w.x(u), w.y(v) - w.y(u)) > vv) continue;
      if (wedge_gap(w, a, v, b, u) > prm.vv_max_gap_angle) continue;
      const Index opts[4][4] = {{a, v, b, w.prev(b, u)}, {a, v, b, u}, {b, u, a, w.prev(a, v)}, {b, u, a, v}};
      bool have = false;
      Contact chosen;
      for (const auto& o : opts) {
        const Index p = o[0], pv = o[1], q = o[2], e0 = o[3];
        const Index e1 = w.next(q, e0);
        const double dx = w.x(e1) - w.x(e0), dy = w.y(e1) - w.y(e0);
        const double l = std::hypot(dx, dy);
        if (!wedge_faces_edge(w, p, pv, dy / l, -dx / l, sin_tol)) continue;
        Contact c = make_contact(w, p, pv, q, e0, e1, true);
        if (!have || c.d0 > chosen.d0) {
          chosen = c;
          have = true;
        }
      }
      if (have) offer(slot_of(chosen.vblock, chosen.vertex), chosen);
    }
  }
  for (const Candidate& c : best)
    if (c.valid) out.push_back(c.c);
}

}  // namespace

std::vector<Contact> detect_contacts(const BlockSystem& s, const DetectionParams& prm,
                                     DetectionWorkspace& work) {
  const std::size_t n = s.block_count();
  const auto ni = static_cast<std::int64_t>(n);
  std::vector<Contact> result;
  if (n == 0) return result;
  const double half = 0.5 * prm.search_distance;
  work.xmin.resize(n);
  work.xmax.resize(n);
  work.ymin.resize(n);
  work.ymax.resize(n);
#pragma omp parallel for schedule(static)
  for (std::int64_t b = 0; b < ni; ++b) {
    double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
    for (Index v = s.begin(b); v < s.end(b); ++v) {
      x0 = std::min(x0, s.vx[v]);
      x1 = std::max(x1, s.vx[v]);
      y0 = std::min(y0, s.vy[v]);
      y1 = std::max(y1, s.vy[v]);
    }
    work.xmin[b] = x0 - half;
    work.xmax[b] = x1 + half;
    work.ymin[b] = y0 - half;
    work.ymax[b] = y1 + half;
  }
  // Uniform grid: cell = mean block extent, but never more than kMaxCellsPerBlock·N cells.
  double gx0 = INFINITY, gx1 = -INFINITY, gy0 = INFINITY, gy1 = -INFINITY, extent = 0.0;
  for (std::size_t b = 0; b < n; ++b) {
    gx0 = std::min(gx0, work.xmin[b]);
    gx1 = std::max(gx1, work.xmax[b]);
    gy0 = std::min(gy0, work.ymin[b]);
    gy1 = std::max(gy1, work.ymax[b]);
    extent += std::max(work.xmax[b] - work.xmin[b], work.ymax[b] - work.ymin[b]);
  }
  double h = extent / static_cast<double>(n);
  h = std::max(h, std::sqrt((gx1 - gx0) * (gy1 - gy0) / (kMaxCellsPerBlock * static_cast<double>(n))));
  h = std::max(h, 1e-300);
  const auto gnx = static_cast<std::int64_t>(std::floor((gx1 - gx0) / h)) + 1;
  const auto gny = static_cast<std::int64_t>(std::floor((gy1 - gy0) / h)) + 1;
  auto cell_range = [&](std::size_t b, std::int64_t& i0, std::int64_t& i1, std::int64_t& j0, std::int64_t& j1) {
    i0 = std::clamp<std::int64_t>(static_cast<std::int64_t>((work.xmin[b] - gx0) / h), 0, gnx - 1);
    i1 = std::clamp<std::int64_t>(static_cast<std::int64_t>((work.xmax[b] - gx0) / h), 0, gnx - 1);
    j0 = std::clamp<std::int64_t>(static_cast<std::int64_t>((work.ymin[b] - gy0) / h), 0, gny - 1);
    j1 = std::clamp<std::int64_t>(static_cast<std::int64_t>((work.ymax[b] - gy0) / h), 0, gny - 1);
  };
  work.cell_offsets.assign(static_cast<std::size_t>(gnx * gny + 1), 0);
  for (std::size_t b = 0; b < n; ++b) {
    std::int64_t i0, i1, j0, j1;
    cell_range(b, i0, i1, j0, j1);
    for (std::int64_t j = j0; j <= j1; ++j)
      for (std::int64_t i = i0; i <= i1; ++i) ++work.cell_offsets[static_cast<std::size_t>(j * gnx + i + 1)];
  }
  for (std::size_t c = 1; c < work.cell_offsets.size(); ++c) work.cell_offsets[c] += work.cell_offsets[c - 1];
  work.cell_blocks.assign(static_cast<std::size_t>(work.cell_offsets.back()), 0);
  {
    std::vector<Index> fill(work.cell_offsets.begin(), work.cell_offsets.end() - 1);
    for (std::size_t b = 0; b < n; ++b) {
      std::int64_t i0, i1, j0, j1;
      cell_range(b, i0, i1, j0, j1);
      for (std::int64_t j = j0; j <= j1; ++j)
        for (std::int64_t i = i0; i <= i1; ++i)
          work.cell_blocks[static_cast<std::size_t>(fill[static_cast<std::size_t>(j * gnx + i)]++)] = static_cast<Index>(b);
    }
  }
  work.candidates.resize(n);
  work.found.resize(n);
  const View w{s};
#pragma omp parallel
  {
    std::vector<Candidate> best;
#pragma omp for schedule(dynamic, 32)
    for (std::int64_t b = 0; b < ni; ++b) {
      auto& cand = work.candidates[b];
      cand.clear();
      std::int64_t i0, i1, j0, j1;
      cell_range(static_cast<std::size_t>(b), i0, i1, j0, j1);
      for (std::int64_t j = j0; j <= j1; ++j)
        for (std::int64_t i = i0; i <= i1; ++i) {
          const auto cell = static_cast<std::size_t>(j * gnx + i);
          for (Index k = work.cell_offsets[cell]; k < work.cell_offsets[cell + 1]; ++k) {
            const Index o = work.cell_blocks[static_cast<std::size_t>(k)];
            if (o <= b) continue;
            if (work.xmin[o] > work.xmax[b] || work.xmax[o] < work.xmin[b] || work.ymin[o] > work.ymax[b] ||
                work.ymax[o] < work.ymin[b])
              continue;
            cand.push_back(o);
          }
        }
      std::sort(cand.begin(), cand.end());
      cand.erase(std::unique(cand.begin(), cand.end()), cand.end());
      auto& found = work.found[b];
      found.clear();
      for (Index o : cand) narrow_phase(w, static_cast<Index>(b), o, prm, best, found);
    }
  }
  std::vector<std::size_t> start(n + 1, 0);
  for (std::size_t b = 0; b < n; ++b) start[b + 1] = start[b] + work.found[b].size();
  result.resize(start[n]);
#pragma omp parallel for schedule(static)
  for (std::int64_t b = 0; b < ni; ++b) std::copy(work.found[b].begin(), work.found[b].end(), result.begin() + static_cast<std::ptrdiff_t>(start[b]));
  return result;
}

namespace {
bool key_less(const Contact& p, const Contact& q) {
  return std::make_tuple(p.pair_low(), p.pair_high(), p.vertex) < std::make_tuple(q.pair_low(), q.pair_high(), q.vertex);
}
}  // namespace

void transfer_contact_state(const std::vector<Contact>& previous, std::vector<Contact>& current) {
  const auto n = static_cast<std::int64_t>(current.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t k = 0; k < n; ++k) {
    Contact& c = current[k];
    c.state = c.d0 <= 0.0 || c.joint >= 0 ? ContactState::Locked : ContactState::Open;
    auto it = std::lower_bound(previous.begin(), previous.end(), c, key_less);
    if (it == previous.end() || key_less(c, *it)) continue;
    const Contact& p = *it;
    c.state = p.state;
    c.normal_force = p.normal_force;
    c.shear_force = p.shear_force;
    c.slip = p.slip;
    c.slide_sign = p.slide_sign;
    if (p.edge0 == c.edge0 && p.edge1 == c.edge1) c.ref_t = p.ref_t;
  }
}

void build_contact_topology(ContactSet& set, std::size_t nb) {
  set.pairs.clear();
  const auto& cs = set.contacts;
  for (std::size_t k = 0; k < cs.size();) {
    ContactPair p;
    p.a = cs[k].pair_low();
    p.b = cs[k].pair_high();
    p.first = static_cast<Index>(k);
    while (k < cs.size() && cs[k].pair_low() == p.a && cs[k].pair_high() == p.b) ++k;
    p.last = static_cast<Index>(k);
    set.pairs.push_back(p);
  }
  set.block_contact_offsets.assign(nb + 1, 0);
  for (const Contact& c : cs) {
    ++set.block_contact_offsets[static_cast<std::size_t>(c.vblock) + 1];
    ++set.block_contact_offsets[static_cast<std::size_t>(c.eblock) + 1];
  }
  for (std::size_t b = 0; b < nb; ++b) set.block_contact_offsets[b + 1] += set.block_contact_offsets[b];
  set.block_contacts.assign(static_cast<std::size_t>(set.block_contact_offsets[nb]), 0);
  std::vector<Index> fill(set.block_contact_offsets.begin(), set.block_contact_offsets.end() - 1);
  for (std::size_t k = 0; k < cs.size(); ++k) {
    set.block_contacts[static_cast<std::size_t>(fill[static_cast<std::size_t>(cs[k].vblock)]++)] = static_cast<Index>(k);
    set.block_contacts[static_cast<std::size_t>(fill[static_cast<std::size_t>(cs[k].eblock)]++)] = static_cast<Index>(k);
  }
  set.block_pair_offsets.assign(nb + 1, 0);
  for (const ContactPair& p : set.pairs) {
    ++set.block_pair_offsets[static_cast<std::size_t>(p.a) + 1];
    ++set.block_pair_offsets[static_cast<std::size_t>(p.b) + 1];
  }
  for (std::size_t b = 0; b < nb; ++b) set.block_pair_offsets[b + 1] += set.block_pair_offsets[b];
  set.block_pairs.assign(static_cast<std::size_t>(set.block_pair_offsets[nb]), 0);
  fill.assign(set.block_pair_offsets.begin(), set.block_pair_offsets.end() - 1);
  for (std::size_t k = 0; k < set.pairs.size(); ++k) {
    set.block_pairs[static_cast<std::size_t>(fill[static_cast<std::size_t>(set.pairs[k].a)]++)] = static_cast<Index>(k);
    set.block_pairs[static_cast<std::size_t>(fill[static_cast<std::size_t>(set.pairs[k].b)]++)] = static_cast<Index>(k);
  }
}

}  // namespace ddafrac::dda
