#include "ddafrac/dda/contact.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "ddafrac/common/polygon.hpp"

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
/// Deepest penetration still paired with an edge, relative to the shorter block edge: a vertex
/// pushed deeper than the search distance by a hard impact must keep its contact.
constexpr double kPenetrationEdgeFraction = 0.3;

/// What the narrow phase of one block pair has made of a vertex.
constexpr char kFree = 0;           // judged by the geometric rules
constexpr char kOnIntactJoint = 1;  // held by an intact virtual joint of the pair: no other contact
constexpr char kInCornerPair = 2;   // one of two corners reduced to one vertex-vertex contact

struct View {
  const BlockSystem& s;
  const DetectionWorkspace& w;
  double sin_tol = 0.0;  // sine of DetectionParams::angle_tolerance
  double x(Index v) const { return s.vx[static_cast<std::size_t>(v)]; }
  double y(Index v) const { return s.vy[static_cast<std::size_t>(v)]; }
  Index prev(Index block, Index v) const { return v == s.begin(block) ? s.end(block) - 1 : v - 1; }
  Index next(Index block, Index v) const { return v + 1 == s.end(block) ? s.begin(block) : v + 1; }
};

/// Angle rule: the wedge at vertex v lies on the outer side of an edge with outward unit normal
/// (nx, ny), within the tolerance, and the vertex is convex (reflex vertices contact by edges).
bool wedge_faces_edge(const View& w, Index v, double nx, double ny) {
  const VertexFrame& f = w.w.frames[static_cast<std::size_t>(v)];
  if (!f.convex) return false;
  return f.ax * nx + f.ay * ny >= -w.sin_tol && f.bx * nx + f.by * ny >= -w.sin_tol;
}

double angle_mod(double a) { return std::fmod(std::fmod(a, kTwoPi) + kTwoPi, kTwoPi); }

/// Interior wedge of vertex v of a block as the angle interval [start, start + open), radians.
/// Computed on demand: only vertex pairs inside the vertex-vertex radius need it.
struct Wedge {
  double start = 0.0, open = 0.0;
};
Wedge wedge_of(const View& w, Index block, Index v) {
  const Index p = w.prev(block, v), q = w.next(block, v);
  const double ax = w.x(p) - w.x(v), ay = w.y(p) - w.y(v);
  const double bx = w.x(q) - w.x(v), by = w.y(q) - w.y(v);
  const double start = std::atan2(by, bx);
  return {start, std::fmod(std::atan2(ay, ax) - start + 2.0 * kTwoPi, kTwoPi)};
}

/// Smallest angular gap between the wedges of two coincident vertices, va of block a and vb of
/// block b (0 if they overlap).
double wedge_gap(const View& w, Index a, Index va, Index b, Index vb) {
  const Wedge wa = wedge_of(w, a, va), wb = wedge_of(w, b, vb);
  const double g1 = angle_mod(wb.start - (wa.start + wa.open));
  const double g2 = angle_mod(wa.start - (wb.start + wb.open));
  if (wa.open + wb.open + g1 + g2 > kTwoPi + 1e-9) return 0.0;
  return std::min(g1, g2);
}

using Candidate = ContactCandidate;

Index find_joint(const BlockSystem& s, Index p, Index q, meshes::Index nv, meshes::Index n2, meshes::Index n3) {
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

/// Full contact record of a candidate: identity, gap and edge parameter.
Contact make_contact(const View& w, const Candidate& cd) {
  Contact c;
  const Index v = cd.vertex, e0 = cd.e0, e1 = w.next(cd.eblock, cd.e0);
  c.vblock = cd.vblock;
  c.eblock = cd.eblock;
  c.vertex = v;
  c.edge0 = e0;
  c.edge1 = e1;
  c.vertex_vertex = cd.vv;
  c.shared_node = cd.shared_node;
  const double dx = w.x(e1) - w.x(e0), dy = w.y(e1) - w.y(e0);
  const double l2 = dx * dx + dy * dy;
  c.d0 = cd.d;
  c.ref_t = ((w.x(v) - w.x(e0)) * dx + (w.y(v) - w.y(e0)) * dy) / l2;
  c.edge_length = std::sqrt(l2);
  c.joint = cd.joint != Candidate::kJointToFind
                ? cd.joint
                : find_joint(w.s, cd.vblock, cd.eblock, w.s.vertex_node[static_cast<std::size_t>(v)],
                             w.s.vertex_node[static_cast<std::size_t>(e0)],
                             w.s.vertex_node[static_cast<std::size_t>(e1)]);
  return c;
}

/// Signed gap of vertex v against the edge starting at e0 (outward unit normal precomputed).
double gap(const View& w, Index v, Index e0) {
  const VertexFrame& f = w.w.frames[static_cast<std::size_t>(e0)];
  return (w.x(v) - w.x(e0)) * f.enx + (w.y(v) - w.y(e0)) * f.eny;
}

/// Is (px, py) inside the polygon of block q (convex or concave)?
bool inside_block(const View& w, Index q, double px, double py) {
  const auto v0 = static_cast<std::size_t>(w.s.begin(q));
  return common::inside_polygon(&w.s.vx[v0], &w.s.vy[v0], static_cast<std::size_t>(w.s.end(q) - w.s.begin(q)), px, py);
}

/// The copies (v of a, u of b) of the one mesh node shared by two blocks of one body that share
/// no edge, or {-1, -1}.
std::pair<Index, Index> node_only_neighbours(const BlockSystem& s, Index a, Index b) {
  std::pair<Index, Index> found{-1, -1};
  if (s.mesh_body[static_cast<std::size_t>(a)] != s.mesh_body[static_cast<std::size_t>(b)]) return found;
  int shared = 0;
  for (Index v = s.begin(a); v < s.end(a); ++v)
    for (Index u = s.begin(b); u < s.end(b); ++u)
      if (s.vertex_node[static_cast<std::size_t>(v)] == s.vertex_node[static_cast<std::size_t>(u)]) {
        found = {v, u};
        ++shared;
      }
  return shared == 1 ? found : std::pair<Index, Index>{-1, -1};
}

void offer(Candidate& slot, const Candidate& c) {
  if (!slot.valid || std::abs(c.d) < std::abs(slot.d)) slot = c;
}

/// The first vertex of the edge of eblock against which the previous step held vertex v of
/// vblock closed as a vertex-vertex contact, or -1 (no such closed corner).
Index closed_corner_edge(const View& w, Index vblock, Index v, Index eblock) {
  // The contact of v in the pair has v's block as its vertex block, so the edge is eblock's.
  const ContactsByVertex::Entry* e = w.w.previous_by_vertex.entry(v, vblock, eblock);
  return e && e->closed_corner ? e->edge : -1;
}

/// Vertex-vertex capture radius of blocks a and b: two of their vertices closer than this are
/// one corner (kVertexVertexEdgeFraction).
double corner_radius(const BlockSystem& s, double search, Index a, Index b) {
  return std::min(search, kVertexVertexEdgeFraction * std::min(s.min_edge[a], s.min_edge[b]));
}

/// The entrance line of vertex v of block p lying inside block q: the edge of v's contact of the
/// pair the step before if it had one (switching line while it overlaps would make its gap, and
/// the energy of its spring, jump), else the edge it lies least deep behind (for a convex block
/// its projection falls on that edge).
struct EntranceLine {
  Candidate line;
  bool kept = false;  // the previous contact's edge (else the least-deep one)
};
EntranceLine entrance_line(const View& w, Index p, Index v, Index q) {
  if (const ContactsByVertex::Entry* before = w.w.previous_by_vertex.entry(v, p, q))
    return {Candidate{true, false, gap(w, v, before->edge), p, v, q, before->edge}, true};
  Candidate least_deep;
  for (Index e0 = w.s.begin(q); e0 < w.s.end(q); ++e0) {
    const double d = gap(w, v, e0);
    if (!least_deep.valid || d > least_deep.d) least_deep = Candidate{true, false, d, p, v, q, e0};
  }
  return {least_deep, false};
}

/// Two copies of a mesh node (v of a, u of b; held_node_copies) are one corner, but as the pieces
/// around them move they drift apart, and the edges into them may overlap as a sliver with each
/// copy inside the other block. The corner's line (the largest gap) measures the sliver's thin
/// end; the copy at its thick end is the one the spring must hold. So the node's contact holds
/// whichever is deeper, the corner on its line or a copy inside the other block on its entrance
/// line: its spring's energy, ½·kn·(the larger depth)², then changes continuously as the copies
/// move (the larger of two continuous depths switches where they are equal). Held at the thin end,
/// the other copy sank unseen until the end opened and its depth came in at once (case 4 at
/// kn = 10·E: 3.6 µm, +0.66 J/m in one step; a flattened disc's fragments: 18 µm, +2%).
Candidate deeper_node_copy(const View& w, Index a, Index v, Index b, Index u, const Candidate& corner) {
  Candidate held = corner.valid && corner.d <= 0.0 ? corner : Candidate{};
  const Index copies[2][3] = {{a, v, b}, {b, u, a}};  // vertex block, copy, block it may lie inside
  for (const auto& c : copies) {
    if (held.valid && held.vertex == c[1]) continue;  // measured on the corner's line already
    if (!inside_block(w, c[2], w.x(c[1]), w.y(c[1]))) continue;
    Candidate line = entrance_line(w, c[0], c[1], c[2]).line;
    if (held.valid && line.d >= held.d) continue;
    line.vv = line.shared_node = true;
    held = line;
  }
  return held.valid ? held : corner;
}

/// The one contact of the corner where vertex v of block a meets vertex u of block b, reduced to
/// the reference line with the largest gap (the entrance line) among those the angle rules allow,
/// or an invalid candidate. A closed corner keeps the reference line it had while the angle rules
/// allow it: switching to another line of the same corner while overlapping would make the gap,
/// and the energy of its spring, jump. The copies of a shared mesh node hold the deeper of the
/// corner and a copy inside the other block (deeper_node_copy).
Candidate corner_contact(const View& w, Index a, Index v, Index b, Index u, bool shared_node) {
  const Index opts[4][4] = {{a, v, b, w.prev(b, u)}, {a, v, b, u}, {b, u, a, w.prev(a, v)}, {b, u, a, v}};
  const Index closed_edge_v = closed_corner_edge(w, a, v, b), closed_edge_u = closed_corner_edge(w, b, u, a);
  Candidate chosen, kept;
  for (const auto& o : opts) {
    const VertexFrame& edge = w.w.frames[static_cast<std::size_t>(o[3])];
    if (!wedge_faces_edge(w, o[1], edge.enx, edge.eny)) continue;
    const Candidate option{true, true, gap(w, o[1], o[3]), o[0], o[1], o[2], o[3], shared_node};
    if (!chosen.valid || option.d > chosen.d) chosen = option;
    if (o[3] == (o[1] == v ? closed_edge_v : closed_edge_u)) kept = option;
  }
  const Candidate corner = kept.valid ? kept : chosen;
  return shared_node ? deeper_node_copy(w, a, v, b, u, corner) : corner;
}

/// Deepest penetration still paired between blocks a and b (kPenetrationEdgeFraction).
double penetration_depth(const BlockSystem& s, double search, Index a, Index b) {
  return std::max(search, kPenetrationEdgeFraction * std::min(s.min_edge[a], s.min_edge[b]));
}

/// Intact virtual joints of a pair a < b are topological, not geometric: both vertices of block a
/// on the shared edge hold a contact with b's copy of the edge whatever the gap (a joint loaded
/// toward its tensile strength opens wider than the search distance). Their vertices, on both
/// sides, take no other contact of this pair; once the joint breaks they are detected like any
/// vertex (a broken joint behaves as if it had never been bonded).
/// Sets `role` (a's vertices, then b's) to kOnIntactJoint for those vertices and kFree for the
/// others, calls hold(joint, v, e0) for each of a's (b's CCW edge along the joint starts at e0),
/// and returns how many intact joints the pair has.
template <class Hold>
int mark_intact_joints(const View& w, Index a, Index b, std::vector<char>& role, Hold&& hold) {
  const BlockSystem& s = w.s;
  const Index na = s.end(a) - s.begin(a);
  role.assign(static_cast<std::size_t>(na + s.end(b) - s.begin(b)), kFree);
  int intact = 0;
  if (s.joints.empty()) return intact;
  for (Index k = s.joint_offsets[a]; k < s.joint_offsets[a + 1]; ++k) {
    const Joint& j = s.joints[static_cast<std::size_t>(s.joint_of_block[k])];
    if (j.block_a != a || j.block_b != b || j.broken) continue;
    Index ua = -1, ub = -1;  // b's vertices at node_a / node_b
    for (Index u = s.begin(b); u < s.end(b); ++u) {
      if (s.vertex_node[static_cast<std::size_t>(u)] == j.node_a) ua = u;
      if (s.vertex_node[static_cast<std::size_t>(u)] == j.node_b) ub = u;
    }
    if (ua < 0 || ub < 0 || j.vertex_a < 0 || j.vertex_b < 0) continue;
    ++intact;
    const Index e0 = w.next(b, ua) == ub ? ua : ub;  // b's CCW edge along the joint
    for (Index v : {j.vertex_a, j.vertex_b}) {
      role[static_cast<std::size_t>(v - s.begin(a))] = kOnIntactJoint;
      hold(s.joint_of_block[k], v, e0);
    }
    role[static_cast<std::size_t>(na + ua - s.begin(b))] = role[static_cast<std::size_t>(na + ub - s.begin(b))] =
        kOnIntactJoint;
  }
  return intact;
}

/// Blocks of one body that meet only at a mesh node (triangles of a fan with others between
/// them) are paired there topologically: the compliance of the joints around the node lets the
/// two copies of the node drift apart and overlap, by more than the search distance on soft
/// joints, so the corner is judged as one vertex-vertex contact whatever the distance (up to
/// the deepest penetration kept) and the angle between the wedges, never as a vertex against
/// the far edge of the other wedge (docs/design.md §4.6).
/// The copies (v of a, u of b) held so, or {-1, -1}.
std::pair<Index, Index> held_node_copies(const View& w, Index a, Index b, double depth) {
  const auto copies = node_only_neighbours(w.s, a, b);
  if (copies.first < 0) return copies;
  const double dx = w.x(copies.first) - w.x(copies.second), dy = w.y(copies.first) - w.y(copies.second);
  return dx * dx + dy * dy > depth * depth ? std::pair<Index, Index>{-1, -1} : copies;
}

/// Narrow phase of one block pair a < b; appends at most one contact per vertex. `hint` is what
/// the pair list knows of the pair (PairHint): a quiet pair whose topology has not changed since
/// gets only its topological contacts, which are all the geometric rules would give it.
/// Returns whether the pair was judged quiet.
bool narrow_phase(const View& w, Index a, Index b, const DetectionParams& prm, const PairHint& hint,
                  std::vector<Candidate>& best, std::vector<char>& role, std::vector<Candidate>& out) {
  const BlockSystem& s = w.s;
  const DetectionWorkspace& ws = w.w;
  const double search = prm.search_distance;
  const double depth = penetration_depth(s, search, a, b);
  // The pairs an intact body is made of, quiet with the topology recorded: blocks joined by one
  // intact joint get that joint's two contacts, blocks meeting only at a mesh node the node's
  // corner contact; what the full judgement below gives them, in the same order.
  if (hint.quiet && hint.intact_joints == 1 && hint.joint >= 0 &&
      !s.joints[static_cast<std::size_t>(hint.joint)].broken) {
    const Joint& j = s.joints[static_cast<std::size_t>(hint.joint)];
    for (const Index v : {std::min(j.vertex_a, j.vertex_b), std::max(j.vertex_a, j.vertex_b)})
      out.push_back(Candidate{true, false, gap(w, v, hint.joint_edge), a, v, b, hint.joint_edge, false, hint.joint});
    return true;
  }
  if (hint.quiet && hint.intact_joints == 0 && hint.node_copies && hint.node_v >= 0) {
    const double dx = w.x(hint.node_v) - w.x(hint.node_u), dy = w.y(hint.node_v) - w.y(hint.node_u);
    if (dx * dx + dy * dy <= depth * depth) {
      Candidate corner = corner_contact(w, a, hint.node_v, b, hint.node_u, true);
      corner.joint = -1;  // blocks that share one node share no edge, so no joint either
      if (corner.valid) out.push_back(corner);
      return true;
    }
  }
  const Index na = s.end(a) - s.begin(a);
  const Index nb = s.end(b) - s.begin(b);
  best.assign(static_cast<std::size_t>(na + nb), Candidate{});
  const double vv = corner_radius(s, search, a, b);
  const double vv2 = vv * vv;
  auto slot_of = [&](Index block, Index v) -> Candidate& {
    return block == a ? best[static_cast<std::size_t>(v - s.begin(a))]
                      : best[static_cast<std::size_t>(na + v - s.begin(b))];
  };
  auto role_of = [&](Index block, Index v) -> char& {
    return role[static_cast<std::size_t>(block == a ? v - s.begin(a) : na + v - s.begin(b))];
  };
  const int intact_joints = mark_intact_joints(
      w, a, b, role,
      [&](Index, Index v, Index e0) { slot_of(a, v) = Candidate{true, false, gap(w, v, e0), a, v, b, e0}; });
  auto skipped = [&](Index block, Index v) { return role_of(block, v) == kOnIntactJoint; };
  // Plain variables, not a structured binding: C++17 lets no lambda capture one (clang refuses).
  Index node_v = -1, node_u = -1;
  std::tie(node_v, node_u) = held_node_copies(w, a, b, depth);
  auto node_copy = [&](Index v) { return v >= 0 && (v == node_v || v == node_u); };
  const bool quiet = hint.quiet && hint.intact_joints == intact_joints && hint.node_copies == (node_v >= 0);
  // Vertex-edge (none in a quiet pair).
  for (int side = 0; side < 2 && !quiet; ++side) {
    const Index p = side == 0 ? a : b;  // vertex block
    const Index q = side == 0 ? b : a;  // edge block
    const double bx0 = ws.boxes.xmin[q], bx1 = ws.boxes.xmax[q], by0 = ws.boxes.ymin[q], by1 = ws.boxes.ymax[q];
    for (Index v = s.begin(p); v < s.end(p); ++v) {
      if (skipped(p, v) || node_copy(v)) continue;
      const double px = w.x(v), py = w.y(v);
      if (px < bx0 - depth || px > bx1 + depth || py < by0 - depth || py > by1 + depth) continue;
      for (Index e0 = s.begin(q); e0 < s.end(q); ++e0) {
        const VertexFrame& edge = ws.frames[static_cast<std::size_t>(e0)];
        const Index e1 = w.next(q, e0);
        const double rx = px - w.x(e0), ry = py - w.y(e0);
        const double d = rx * edge.enx + ry * edge.eny;
        if (d > search || d < -depth) continue;
        const double l = edge.elen;
        const double along = -rx * edge.eny + ry * edge.enx;  // (P - P2)·u with u = (-ny, nx)
        if (along < 0.0 || along > l) continue;
        const double sx = px - w.x(e1), sy = py - w.y(e1);
        if (rx * rx + ry * ry <= vv2 || sx * sx + sy * sy <= vv2) continue;
        if (!wedge_faces_edge(w, v, edge.enx, edge.eny)) continue;
        // Behind an edge is a penetration only inside the block: a vertex outside a triangle
        // near one of its corners lies behind an edge too (loose fragments of a cracked mesh).
        if (d < 0.0 && !inside_block(w, q, px, py)) continue;
        offer(slot_of(p, v), Candidate{true, false, d, p, v, q, e0});
      }
    }
  }
  // Vertex-vertex: reduce to the reference line with the largest gap (the entrance line).
  for (Index v = s.begin(a); v < s.end(a); ++v) {
    if (skipped(a, v)) continue;
    for (Index u = s.begin(b); u < s.end(b); ++u) {
      if (skipped(b, u)) continue;
      const bool shared_node = v == node_v && u == node_u;
      if (!shared_node) {
        if (quiet) continue;  // its other vertices lie farther apart than the capture radius
        const double dx = w.x(v) - w.x(u), dy = w.y(v) - w.y(u);
        if (dx * dx + dy * dy > vv2 || node_copy(v) || node_copy(u)) continue;
        if (wedge_gap(w, a, v, b, u) > prm.vv_max_gap_angle) continue;
      }
      const Candidate chosen = corner_contact(w, a, v, b, u, shared_node);
      if (!chosen.valid) continue;
      offer(slot_of(chosen.vblock, chosen.vertex), chosen);
      role_of(a, v) = role_of(b, u) = kInCornerPair;
    }
  }
  // A vertex inside the other block, not one of two corners whose one contact went to the other,
  // is held on its entrance line whatever the angle rules (entrance_line), unless the rules above
  // gave a shallower one where it had no contact of the pair the step before. The rules judge a
  // corner by the angles of its wedge and by its distance to the other block's corners, and some
  // corners that enter pass none of them (a wedge dipping more than the tolerance behind the edge
  // it crosses; a tip driven into a corner, inside the capture radius where no vertex-edge contact
  // forms and too far in angle for a vertex-vertex one) or only against an edge far behind
  // (entering a triangle by 0.1 µm through one edge, a vertex was paired with another 80 µm away,
  // whose spring released ½·kn·d² at once). No vertex lies inside in a quiet pair.
  for (int side = 0; side < 2 && !quiet; ++side) {
    const Index p = side == 0 ? a : b;  // vertex block
    const Index q = side == 0 ? b : a;  // block it may lie inside
    const double bx0 = ws.boxes.xmin[q], bx1 = ws.boxes.xmax[q], by0 = ws.boxes.ymin[q], by1 = ws.boxes.ymax[q];
    for (Index v = s.begin(p); v < s.end(p); ++v) {
      if (role_of(p, v) != kFree || node_copy(v)) continue;
      const double px = w.x(v), py = w.y(v);
      if (px < bx0 || px > bx1 || py < by0 || py > by1 || !inside_block(w, q, px, py)) continue;
      Candidate& held = slot_of(p, v);
      const auto [line, kept] = entrance_line(w, p, v, q);
      if (kept ? !held.valid || held.e0 != line.e0 : !held.valid || held.d < line.d) held = line;
    }
  }
  for (const Candidate& c : best)
    if (c.valid) out.push_back(c);
  return quiet;
}

/// Per-vertex data of the narrow phase: unit directions of the two adjacent edges, convexity,
/// and the outward normal and length of the next edge.
void vertex_data(const BlockSystem& s, DetectionWorkspace& w) {
  w.frames.resize(s.vertex_count());
  const auto nb = static_cast<std::int64_t>(s.block_count());
#pragma omp parallel for schedule(static)
  for (std::int64_t b = 0; b < nb; ++b) {
    const Index v0 = s.begin(b), v1 = s.end(b);
    for (Index v = v0; v < v1; ++v) {
      const Index p = v == v0 ? v1 - 1 : v - 1;
      const Index q = v + 1 == v1 ? v0 : v + 1;
      const double ax = s.vx[p] - s.vx[v], ay = s.vy[p] - s.vy[v];
      const double bx = s.vx[q] - s.vx[v], by = s.vy[q] - s.vy[v];
      const double la = std::sqrt(ax * ax + ay * ay), lb = std::sqrt(bx * bx + by * by);
      VertexFrame& f = w.frames[static_cast<std::size_t>(v)];
      f.ax = ax / la;
      f.ay = ay / la;
      f.bx = bx / lb;
      f.by = by / lb;
      f.convex = bx * ay - by * ax > 0.0;
      f.enx = by / lb;
      f.eny = -bx / lb;
      f.elen = lb;
    }
  }
}

}  // namespace

void ContactsByVertex::build(const std::vector<Contact>& list, std::size_t vertex_count) {
  const auto nc = static_cast<std::int64_t>(list.size());
  // The fields an entry needs, read from the records once, in list order and in parallel; the
  // serial passes below then walk these small arrays.
  std::vector<Index> vertex(list.size());
  std::vector<Entry> in_list_order(list.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t k = 0; k < nc; ++k) {
    const Contact& c = list[k];
    vertex[k] = c.vertex;
    in_list_order[k] = {static_cast<Index>(k), c.pair_low(), c.pair_high(), c.edge0,
                        c.vertex_vertex && c.state != ContactState::Open};
  }
  offsets.assign(vertex_count + 1, 0);
  for (const Index v : vertex) ++offsets[static_cast<std::size_t>(v) + 1];
  for (std::size_t v = 0; v < vertex_count; ++v) offsets[v + 1] += offsets[v];
  entries.resize(list.size());
  std::vector<Index> fill(offsets.begin(), offsets.end() - 1);
  for (std::int64_t k = 0; k < nc; ++k)
    entries[static_cast<std::size_t>(fill[static_cast<std::size_t>(vertex[k])]++)] = in_list_order[k];
}

const ContactsByVertex::Entry* ContactsByVertex::entry(Index v, Index p, Index q) const {
  const Index lo = std::min(p, q), hi = std::max(p, q);
  for (Index m = offsets[static_cast<std::size_t>(v)]; m < offsets[static_cast<std::size_t>(v) + 1]; ++m) {
    const Entry& e = entries[static_cast<std::size_t>(m)];
    if (e.low == lo && e.high == hi) return &e;
  }
  return nullptr;
}

namespace {

/// Axis-aligned boxes of the blocks grown by `margin` on every side.
void grow_boxes(const BlockSystem& s, double margin, BlockBoxes& box) {
  const std::size_t n = s.block_count();
  box.xmin.resize(n);
  box.xmax.resize(n);
  box.ymin.resize(n);
  box.ymax.resize(n);
#pragma omp parallel for schedule(static)
  for (std::int64_t b = 0; b < static_cast<std::int64_t>(n); ++b) {
    double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
    for (Index v = s.begin(b); v < s.end(b); ++v) {
      x0 = std::min(x0, s.vx[v]);
      x1 = std::max(x1, s.vx[v]);
      y0 = std::min(y0, s.vy[v]);
      y1 = std::max(y1, s.vy[v]);
    }
    box.xmin[b] = x0 - margin;
    box.xmax[b] = x1 + margin;
    box.ymin[b] = y0 - margin;
    box.ymax[b] = y1 + margin;
  }
}

bool boxes_overlap(const BlockBoxes& box, std::size_t a, std::size_t b) {
  return !(box.xmin[b] > box.xmax[a] || box.xmax[b] < box.xmin[a] || box.ymin[b] > box.ymax[a] ||
           box.ymax[b] < box.ymin[a]);
}

/// Broad phase: for every block, the blocks after it whose boxes overlap (uniform grid, cell =
/// mean block extent, never more than kMaxCellsPerBlock·N cells), ascending.
void overlapping_boxes(const BlockBoxes& box, DetectionWorkspace& work, std::vector<std::vector<Index>>& partners) {
  const std::size_t n = box.xmin.size();
  double gx0 = INFINITY, gx1 = -INFINITY, gy0 = INFINITY, gy1 = -INFINITY, extent = 0.0;
  for (std::size_t b = 0; b < n; ++b) {
    gx0 = std::min(gx0, box.xmin[b]);
    gx1 = std::max(gx1, box.xmax[b]);
    gy0 = std::min(gy0, box.ymin[b]);
    gy1 = std::max(gy1, box.ymax[b]);
    extent += std::max(box.xmax[b] - box.xmin[b], box.ymax[b] - box.ymin[b]);
  }
  double h = extent / static_cast<double>(n);
  h = std::max(h, std::sqrt((gx1 - gx0) * (gy1 - gy0) / (kMaxCellsPerBlock * static_cast<double>(n))));
  h = std::max(h, 1e-300);
  const auto gnx = static_cast<std::int64_t>(std::floor((gx1 - gx0) / h)) + 1;
  const auto gny = static_cast<std::int64_t>(std::floor((gy1 - gy0) / h)) + 1;
  auto cell_range = [&](std::size_t b, std::int64_t& i0, std::int64_t& i1, std::int64_t& j0, std::int64_t& j1) {
    i0 = std::clamp<std::int64_t>(static_cast<std::int64_t>((box.xmin[b] - gx0) / h), 0, gnx - 1);
    i1 = std::clamp<std::int64_t>(static_cast<std::int64_t>((box.xmax[b] - gx0) / h), 0, gnx - 1);
    j0 = std::clamp<std::int64_t>(static_cast<std::int64_t>((box.ymin[b] - gy0) / h), 0, gny - 1);
    j1 = std::clamp<std::int64_t>(static_cast<std::int64_t>((box.ymax[b] - gy0) / h), 0, gny - 1);
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
          work.cell_blocks[static_cast<std::size_t>(fill[static_cast<std::size_t>(j * gnx + i)]++)] =
              static_cast<Index>(b);
    }
  }
  partners.resize(n);
#pragma omp parallel for schedule(dynamic, 32)
  for (std::int64_t b = 0; b < static_cast<std::int64_t>(n); ++b) {
    auto& found = partners[b];
    found.clear();
    std::int64_t i0, i1, j0, j1;
    cell_range(static_cast<std::size_t>(b), i0, i1, j0, j1);
    for (std::int64_t j = j0; j <= j1; ++j)
      for (std::int64_t i = i0; i <= i1; ++i) {
        const auto cell = static_cast<std::size_t>(j * gnx + i);
        for (Index k = work.cell_offsets[cell]; k < work.cell_offsets[cell + 1]; ++k) {
          const Index o = work.cell_blocks[static_cast<std::size_t>(k)];
          if (o > b && boxes_overlap(box, static_cast<std::size_t>(b), static_cast<std::size_t>(o))) found.push_back(o);
        }
      }
    std::sort(found.begin(), found.end());
    found.erase(std::unique(found.begin(), found.end()), found.end());
  }
}

/// Distance from (px, py) to the segment (x0, y0)-(x1, y1).
double point_segment_distance(double px, double py, double x0, double y0, double x1, double y1) {
  const double dx = x1 - x0, dy = y1 - y0;
  const double l2 = dx * dx + dy * dy;
  const double t = l2 > 0.0 ? std::clamp(((px - x0) * dx + (py - y0) * dy) / l2, 0.0, 1.0) : 0.0;
  return std::hypot(px - x0 - t * dx, py - y0 - t * dy);
}

/// Do the segments p0-p1 and q0-q1 cross or touch?
bool segments_cross(double p0x, double p0y, double p1x, double p1y, double q0x, double q0y, double q1x, double q1y) {
  auto side = [](double ax, double ay, double bx, double by, double cx, double cy) {
    return (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
  };
  const double d1 = side(q0x, q0y, q1x, q1y, p0x, p0y), d2 = side(q0x, q0y, q1x, q1y, p1x, p1y);
  const double d3 = side(p0x, p0y, p1x, p1y, q0x, q0y), d4 = side(p0x, p0y, p1x, p1y, q1x, q1y);
  return d1 * d2 <= 0.0 && d3 * d4 <= 0.0;
}

/// Can blocks a and b hold a contact while no vertex moves more than half the skin? True when
/// their boundaries come within `reach` = search distance + skin (a vertex within reach of an
/// edge of the other block), cross, or one lies inside the other, and for blocks of one body
/// that share a mesh node (their node contact is kept up to the deepest penetration, which may
/// exceed the search distance).
bool may_touch(const View& w, Index a, Index b, double reach) {
  const BlockSystem& s = w.s;
  if (node_only_neighbours(s, a, b).first >= 0) return true;
  for (int side = 0; side < 2; ++side) {
    const Index p = side == 0 ? a : b, q = side == 0 ? b : a;
    for (Index v = s.begin(p); v < s.end(p); ++v) {
      if (inside_block(w, q, w.x(v), w.y(v))) return true;
      for (Index e0 = s.begin(q); e0 < s.end(q); ++e0) {
        const Index e1 = w.next(q, e0);
        if (point_segment_distance(w.x(v), w.y(v), w.x(e0), w.y(e0), w.x(e1), w.y(e1)) <= reach) return true;
      }
    }
  }
  for (Index v = s.begin(a); v < s.end(a); ++v)
    for (Index u = s.begin(b); u < s.end(b); ++u)
      if (segments_cross(w.x(v), w.y(v), w.x(w.next(a, v)), w.y(w.next(a, v)), w.x(u), w.y(u), w.x(w.next(b, u)),
                         w.y(w.next(b, u))))
        return true;
  return false;
}

/// What the pair list records of a pair a < b (PairHint): its topology now, and whether every
/// vertex the geometric rules judge lies outside the other block and farther than search distance
/// + skin from its boundary (the pair is then quiet until the next build: vertices move at most
/// half the skin each, so these distances shrink by less than the skin and none is crossed).
PairHint hint_of(const View& w, Index a, Index b, const DetectionParams& prm, std::vector<char>& role) {
  const BlockSystem& s = w.s;
  PairHint hint;
  hint.intact_joints = mark_intact_joints(w, a, b, role, [&](Index joint, Index, Index e0) {
    hint.joint = joint;
    hint.joint_edge = e0;
  });
  std::tie(hint.node_v, hint.node_u) = node_only_neighbours(s, a, b);
  const auto [node_v, node_u] = held_node_copies(w, a, b, penetration_depth(s, prm.search_distance, a, b));
  hint.node_copies = node_v >= 0;
  const double clear = prm.search_distance + prm.skin;
  const Index na = s.end(a) - s.begin(a);
  for (int side = 0; side < 2; ++side) {
    const Index p = side == 0 ? a : b, q = side == 0 ? b : a;
    const Index first_role = side == 0 ? -s.begin(a) : na - s.begin(b);  // role index of vertex v: v + first_role
    for (Index v = s.begin(p); v < s.end(p); ++v) {
      if (role[static_cast<std::size_t>(v + first_role)] != kFree || v == node_v || v == node_u) continue;
      if (inside_block(w, q, w.x(v), w.y(v))) return hint;
      for (Index e0 = s.begin(q); e0 < s.end(q); ++e0) {
        const Index e1 = w.next(q, e0);
        if (point_segment_distance(w.x(v), w.y(v), w.x(e0), w.y(e0), w.x(e1), w.y(e1)) <= clear) return hint;
      }
    }
  }
  hint.quiet = true;
  return hint;
}

/// Largest distance any vertex has moved since the pair list was built.
double largest_move_since_build(const BlockSystem& s, const DetectionWorkspace& work) {
  const auto nv = static_cast<std::int64_t>(s.vertex_count());
  double moved2 = 0.0;  // m², squared: one square root instead of one per vertex
#pragma omp parallel for schedule(static) reduction(max : moved2)
  for (std::int64_t v = 0; v < nv; ++v) {
    const double dx = s.vx[v] - work.built_x[v], dy = s.vy[v] - work.built_y[v];
    moved2 = std::max(moved2, dx * dx + dy * dy);
  }
  return std::sqrt(moved2);
}

/// Adds to a partner list of block b the blocks after it joined to it by an intact virtual joint
/// (paired whatever their gap), then sorts it and drops repeats.
void add_joint_partners(const BlockSystem& s, Index b, std::vector<Index>& partners) {
  if (!s.joints.empty())
    for (Index k = s.joint_offsets[b]; k < s.joint_offsets[b + 1]; ++k) {
      const Joint& jt = s.joints[static_cast<std::size_t>(s.joint_of_block[k])];
      if (!jt.broken && jt.block_a == b) partners.push_back(jt.block_b);
    }
  std::sort(partners.begin(), partners.end());
  partners.erase(std::unique(partners.begin(), partners.end()), partners.end());
}

/// Rebuilds the pair list (Verlet list): pairs that may touch before some vertex moves more
/// than half the skin. (Pairs joined by an intact virtual joint are added at every step,
/// whatever their gap.)
void build_pair_list(const View& w, const DetectionParams& prm, DetectionWorkspace& work) {
  const BlockSystem& s = w.s;
  const double reach = prm.search_distance + prm.skin;
  grow_boxes(s, 0.5 * reach, work.reach_boxes);
  overlapping_boxes(work.reach_boxes, work, work.pairs);
  const auto n = static_cast<std::int64_t>(s.block_count());
  work.pair_hints.resize(static_cast<std::size_t>(n));
#pragma omp parallel
  {
    std::vector<char> role;
#pragma omp for schedule(dynamic, 32)
    for (std::int64_t b = 0; b < n; ++b) {
      auto& list = work.pairs[b];
      list.erase(std::remove_if(list.begin(), list.end(),
                                [&](Index o) { return !may_touch(w, static_cast<Index>(b), o, reach); }),
                 list.end());
      auto& hints = work.pair_hints[b];
      hints.clear();
      for (const Index o : list) hints.push_back(hint_of(w, static_cast<Index>(b), o, prm, role));
    }
  }
  work.built_x = s.vx;
  work.built_y = s.vy;
  ++work.pair_list_builds;
}

}  // namespace

void detect_contacts(const BlockSystem& s, const DetectionParams& prm, DetectionWorkspace& work,
                     const std::vector<Contact>& previous, std::vector<Contact>& result) {
  const std::size_t n = s.block_count();
  const auto ni = static_cast<std::int64_t>(n);
  if (n == 0) {
    result.clear();
    return;
  }
  grow_boxes(s, 0.5 * prm.search_distance, work.boxes);
  work.candidates.resize(n);
  work.found.resize(n);
  work.previous_by_vertex.build(previous, s.vertex_count());
  vertex_data(s, work);
  const View w{s, work, std::sin(prm.angle_tolerance)};
  const bool stale = work.pairs.size() != n || work.built_x.size() != s.vertex_count() ||
                     2.0 * largest_move_since_build(s, work) > prm.skin;
  if (stale) build_pair_list(w, prm, work);
  const bool hinted = work.pair_hints.size() == n;
  work.candidate_hints.resize(n);
  long judged = 0, quiet = 0;
#pragma omp parallel
  {
    std::vector<Candidate> best;
    std::vector<char> role;
#pragma omp for schedule(dynamic, 32) reduction(+ : judged, quiet)
    for (std::int64_t b = 0; b < ni; ++b) {
      // Pairs of the list whose boxes (grown by half the search distance) overlap now, and the
      // pairs of intact joints, whatever their gap.
      auto& cand = work.candidates[b];
      cand.clear();
      const auto& listed = work.pairs[b];
      for (Index o : listed)
        if (boxes_overlap(work.boxes, static_cast<std::size_t>(b), static_cast<std::size_t>(o))) cand.push_back(o);
      add_joint_partners(s, static_cast<Index>(b), cand);
      // Each candidate's hint from the list (both ascending); a joint's pair not listed has none,
      // nor has any pair of a list restored from a checkpoint until its next build.
      auto& hints = work.candidate_hints[b];
      hints.clear();
      std::size_t k = 0;
      for (const Index o : cand) {
        while (k < listed.size() && listed[k] < o) ++k;
        hints.push_back(hinted && k < listed.size() && listed[k] == o ? work.pair_hints[b][k] : PairHint{});
      }
      auto& found = work.found[b];
      found.clear();
      for (std::size_t c = 0; c < cand.size(); ++c)
        quiet += narrow_phase(w, static_cast<Index>(b), cand[c], prm, hints[c], best, role, found) ? 1 : 0;
      judged += static_cast<long>(cand.size());
    }
  }
  work.pairs_judged += judged;
  work.quiet_pairs_judged += quiet;
  std::vector<std::size_t> start(n + 1, 0);
  for (std::size_t b = 0; b < n; ++b) start[b + 1] = start[b] + work.found[b].size();
  result.resize(start[n]);
#pragma omp parallel for schedule(static)
  for (std::int64_t b = 0; b < ni; ++b)
    for (std::size_t k = 0; k < work.found[b].size(); ++k) result[start[b] + k] = make_contact(w, work.found[b][k]);
}

namespace {

/// Whether vertex v has a contact in the block pair (low, high) of `list`, sorted by (low block,
/// high block, vertex) as detect_contacts returns it.
bool has_contact(const std::vector<Contact>& list, Index v, Index low, Index high) {
  const auto key = [](const Contact& c) { return std::tuple(c.pair_low(), c.pair_high(), c.vertex); };
  const auto at = std::lower_bound(list.begin(), list.end(), std::tuple(low, high, v),
                                   [&](const Contact& c, const auto& k) { return key(c) < k; });
  return at != list.end() && key(*at) == std::tuple(low, high, v);
}

/// Length of the reference edge of contact c on the blocks' current geometry, m.
double edge_length(const Contact& c, const BlockSystem& blocks) {
  return std::hypot(blocks.vx[c.edge1] - blocks.vx[c.edge0], blocks.vy[c.edge1] - blocks.vy[c.edge0]);
}

/// Whether `p`, a contact of the previous step, was held by a virtual joint that is broken now.
bool joint_just_broke(const Contact& p, const std::vector<Joint>& joints) {
  return p.was_bonded && p.joint >= 0 && !p.bonded(joints);
}

/// The previous contact of the same pair at the same corner with the roles of vertex and edge
/// swapped, or null: the angle rules may pick the other reference line of a vertex-vertex
/// contact as the blocks move, and a vertex-vertex contact whose vertices drift apart becomes a
/// vertex-edge contact of whichever vertex entered the other block (and back).
/// c's corner is its vertex and the end of its edge nearer to it: only that end's contact can be
/// the swapped one. Both ends will not do: where two blocks share a whole edge (a broken virtual
/// joint), each block's vertices are the ends of the other's edge, so the contact at the far
/// corner would match too and be carried twice, while the one at c's own corner vanished.
/// The corner of a joint that has just broken swaps between two vertex-edge contacts too: the
/// joint held its first block's vertex at the end of the other's edge, and a joint that slid before
/// it broke (softening in shear) leaves the other copy of the node on the first block's edge,
/// farther from its end than the vertex-vertex capture radius. Under compression that corner stays
/// loaded; its spring moves from one copy to the other, unless the held vertex kept a contact of
/// its own (`current`, the list being carried), which then carries it.
const Contact* swapped_corner(const std::vector<Contact>& previous, const ContactsByVertex& by_vertex,
                              const std::vector<Contact>& current, const Contact& c, const std::vector<Joint>& joints) {
  // The vertex's projection on the edge (ref_t, fresh from detection) says which end is nearer.
  const Index end = c.ref_t > 0.5 ? c.edge1 : c.edge0;
  const Index k = by_vertex.find(end, c.vblock, c.eblock);
  if (k < 0) return nullptr;
  const Contact& p = previous[static_cast<std::size_t>(k)];
  if (c.vertex != p.edge0 && c.vertex != p.edge1) return nullptr;
  if (p.vertex_vertex || c.vertex_vertex) return &p;
  return joint_just_broke(p, joints) && !has_contact(current, p.vertex, c.pair_low(), c.pair_high()) ? &p : nullptr;
}

}  // namespace

CarriedState carry_contact_state(const std::vector<Contact>& previous, const ContactsByVertex& previous_by_vertex,
                                 const std::vector<Contact>& current, Contact& c, const std::vector<Joint>& joints,
                                 const BlockSystem& blocks) {
  // New contacts touching or overlapping start closed; the copies of a shared mesh node
  // start at exactly zero gap and stay open until they overlap.
  const bool touching = c.shared_node ? c.d0 < 0.0 : c.d0 <= 0.0;
  c.state = touching || c.held(joints) ? ContactState::Locked : ContactState::Open;
  const Index same = previous_by_vertex.find(c.vertex, c.vblock, c.eblock);
  const Contact* p = same >= 0 ? &previous[static_cast<std::size_t>(same)] : nullptr;
  const bool swapped = !p && (p = swapped_corner(previous, previous_by_vertex, current, c, joints)) != nullptr;
  if (!p) return {};
  if (p->tied && !c.tied) return {nullptr, true};
  c.carried = true;
  c.state = p->state;
  c.normal_force = p->normal_force;
  c.shear_force = p->shear_force;
  c.slip = p->slip;
  c.cohesive = p->cohesive;
  c.cohesive_length = p->cohesive_length;
  c.slide_sign = p->slide_sign;
  c.rest_gap = p->rest_gap;
  c.stored_normal = p->stored_normal;
  c.stored_shear = p->stored_shear;
  c.was_bonded = p->was_bonded;
  c.damaged_slip = p->damaged_slip;
  c.stored_damaged = p->stored_damaged;
  c.damaged_state = p->damaged_state;
  // A softening joint's shear spring ks of the set, its damaged part's share D·ks included.
  const double shear_spring = p->ks + p->damaged_ks;
  const bool broke = joint_just_broke(*p, joints);
  if (swapped && shear_spring > 0.0) {
    // Measured along the other block's edge the relative slip has the same sign, so the shear
    // spring keeps its elastic extension f_s/ks: the reference point sits that far behind.
    c.ref_t -= p->shear_force / shear_spring / edge_length(c, blocks);
  } else if (p->edge0 == c.edge0 && p->edge1 == c.edge1) {
    c.ref_t = p->ref_t;
    // At a softening joint's break the spring of the set carries on from the joint's shear force
    // f_s = ks·s − D·ks·s_p (Contact::damaged_ks): its reference point moves by D·s_p.
    if (broke && p->damaged_ks > 0.0)
      c.ref_t += p->damaged_ks * p->damaged_slip / shear_spring / edge_length(c, blocks);
  }
  return {p, false, swapped && broke};
}

bool keep_normal_spring(Contact& c, const Contact& previous) {
  if (previous.state == ContactState::Open || previous.normal_force <= 0.0 || c.kn <= 0.0) return false;
  // In compression the spring is kn stiff: ½·kn·(d0 − rest gap)² = what the previous one stored.
  c.rest_gap = c.d0 + std::sqrt(2.0 * previous.stored_normal / c.kn);
  return true;
}

void build_contact_topology(ContactSet& set, std::size_t nb) {
  const auto& cs = set.contacts;
  const auto nc = static_cast<std::int64_t>(cs.size());
  // The blocks of every contact, read once in parallel: the serial passes below (and the
  // assembly, through vertex_blocks) then walk these small arrays instead of the contact records.
  std::vector<Index> low(cs.size()), high(cs.size());
  std::vector<std::uint8_t> starts_pair(cs.size());
  set.vertex_blocks.resize(cs.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t k = 0; k < nc; ++k) {
    set.vertex_blocks[k] = cs[k].vblock;
    low[k] = cs[k].pair_low();
    high[k] = cs[k].pair_high();
    starts_pair[k] = k == 0 || cs[k - 1].pair_low() != low[k] || cs[k - 1].pair_high() != high[k];
  }
  set.pairs.clear();
  for (std::int64_t k = 0; k < nc; ++k) {
    if (starts_pair[k]) {
      if (!set.pairs.empty()) set.pairs.back().last = static_cast<Index>(k);
      set.pairs.push_back({low[k], high[k], static_cast<Index>(k), static_cast<Index>(k)});
    }
  }
  if (!set.pairs.empty()) set.pairs.back().last = static_cast<Index>(nc);
  // Per block, ascending: a contact or pair is listed under its low block, then its high block.
  auto by_block = [nb](std::size_t count, auto block_a, auto block_b, std::vector<Index>& offsets,
                       std::vector<Index>& items) {
    offsets.assign(nb + 1, 0);
    for (std::size_t k = 0; k < count; ++k) {
      ++offsets[static_cast<std::size_t>(block_a(k)) + 1];
      ++offsets[static_cast<std::size_t>(block_b(k)) + 1];
    }
    for (std::size_t b = 0; b < nb; ++b) offsets[b + 1] += offsets[b];
    items.assign(static_cast<std::size_t>(offsets[nb]), 0);
    std::vector<Index> fill(offsets.begin(), offsets.end() - 1);
    for (std::size_t k = 0; k < count; ++k) {
      items[static_cast<std::size_t>(fill[static_cast<std::size_t>(block_a(k))]++)] = static_cast<Index>(k);
      items[static_cast<std::size_t>(fill[static_cast<std::size_t>(block_b(k))]++)] = static_cast<Index>(k);
    }
  };
  // (A contact's two blocks differ, so listing it under low/high gives the lists vblock/eblock would.)
  by_block(
      cs.size(), [&](std::size_t k) { return low[k]; }, [&](std::size_t k) { return high[k]; },
      set.block_contact_offsets, set.block_contacts);
  by_block(
      set.pairs.size(), [&](std::size_t k) { return set.pairs[k].a; }, [&](std::size_t k) { return set.pairs[k].b; },
      set.block_pair_offsets, set.block_pairs);
}

}  // namespace ddafrac::dda
