#pragma once
// Contacts between blocks: records carried from step to step, O(N) detection (uniform grid broad
// phase + vertex-edge / vertex-vertex narrow phase with angle rules), and the pair topology the
// assembly needs (one off-diagonal 6x6 block per contacting block pair).

#include <cstdint>
#include <vector>

#include "ddafrac/dda/block_system.hpp"
#include "ddafrac/dda/types.hpp"

namespace ddafrac::dda {

enum class ContactState : std::uint8_t { Open = 0, Sliding = 1, Locked = 2 };
const char* to_string(ContactState s);

/// One vertex-edge contact: the vertex of `vblock` against the edge edge0->edge1 (CCW) of
/// `eblock`. Vertex-vertex contacts are reduced to one such reference line by the angle rules.
struct Contact {
  // Identity.
  Index vblock = 0, eblock = 0;  // block owning the vertex / the edge
  Index vertex = 0;              // global vertex index (BlockSystem::vx)
  Index edge0 = 0, edge1 = 0;    // global vertex indices of the reference edge
  Index joint = -1;              // virtual joint (BlockSystem::joints); bonded while intact
  Index joint_set = -1;          // Scene::joint_sets index of its properties (-1: defaults)
  bool vertex_vertex = false;
  // Vertex and reference edge are copies of one mesh node in two blocks of one body that share
  // that node but no intact joint at it (docs/design.md §4.6): found
  // from t = 0 whatever the wedge angles, so that the copies can never overlap unseen. Such a
  // contact starts open at zero gap and never gets the cohesion of a real joint closed at t = 0.
  bool shared_node = false;
  // A shared-node contact whose copies are tied (scene::IntactNodes::Tie): while intact virtual
  // joints at the node connect its two blocks around the node (NodeTieGroups), a bilateral
  // spring of the joints' kn, normal and shear alike, with its reference point on the other copy,
  // holds ½·kn·|x_v − x_u|²: a function of the two blocks' positions alone, like the continuum it
  // stands for (docs/design.md §4.6). Set by the engine at each detection.
  bool tied = false;
  // Carried from step to step.
  ContactState state = ContactState::Open;
  double ref_t = 0.0;         // locked reference point on the edge, as edge parameter 0..1
  double normal_force = 0.0;  // N/m, compression positive (tension for bonded joints)
  double shear_force = 0.0;   // N/m
  double slip = 0.0;          // accumulated sliding displacement, m
  double slide_sign = 0.0;    // direction of sliding along the edge (+1/-1)
  // Gap at which the normal spring is unstretched, m: an ordinary contact that closes after
  // overlapping inside the open-close band (judge_contact) pushes from the overlap it had when its
  // step started, not from zero gap, so that the band's overlap, built up with no spring, adds no
  // energy (≤ 0, docs/design.md §4.4). 0 for joints and for contacts that close from a gap. The
  // swapped corner of a joint that has just broken keeps the joint's compression
  // (keep_normal_spring): its rest gap may be positive, until it next opens.
  double rest_gap = 0.0;
  // Cohesive real joint (closed at t = 0, never failed): carries tension up to σt·l_c and shear
  // up to c·l_c + fn·tanφ; once either is exceeded it keeps friction only, for good.
  bool cohesive = false;
  double cohesive_length = 0.0;  // l_c, m: this contact's share of the joint face
  // Energy ledger: what the springs stored at the end of the previous step (J/m) and whether the
  // contact was held then, an intact virtual joint or a tie (energy_ledger.hpp).
  double stored_normal = 0.0, stored_shear = 0.0;
  bool was_bonded = false;
  // Of a softening joint's damaged part (damaged_ks below): stuck (Locked) or sliding.
  ContactState damaged_state = ContactState::Locked;
  // Properties.
  double kn = 0.0, ks = 0.0;  // penalty springs, N/m
  double tan_phi = 0.0;
  double cohesion = 0.0, tensile_strength = 0.0;  // Pa, of the joint set (used while cohesive)
  // Damage of its joint while bonded (Joint::damage; 0 otherwise): the normal spring carries
  // tension with (1 − damage)·kn (normal_stiffness); ks already holds the damaged shear spring.
  double damage = 0.0;
  // The damaged part of a softening joint's shear (docs/design.md §5), beside the intact part's
  // spring ks = (1 − D)·ks_set: a spring of D·ks_set (N/m; 0 unless bonded with D > 0) measured
  // from the part's plastic slip s_p (damaged_slip, m, along the edge as s), which slides with
  // Coulomb friction up to D·tanφ·f_n under compression and freely in tension. While the
  // contact is bonded, slide_sign and friction_force serve this part (the contact itself is
  // locked). Its state: damaged_state, damaged_trial.
  double damaged_ks = 0.0;
  double damaged_slip = 0.0;
  double stored_damaged = 0.0;  // J/m, its share of stored_shear at the end of the previous step
  // Per step (geometry at step start): gap and shear (their gradients: ContactLinearisation).
  double d0 = 0.0;  // normal gap, m, positive = apart
  double s0 = 0.0;  // shear displacement from the reference point along the edge, m
  double edge_length = 0.0;
  // Per open-close iteration.
  ContactState trial = ContactState::Open;  // state assumed by the current assembly
  ContactState damaged_trial = ContactState::Locked;  // damaged_state assumed by it
  double fn_iter = 0.0;                     // normal force of the latest solve, N/m
  double friction_force = 0.0;              // N/m, friction load of the latest assembly (sliding)
  double d_iter = 0.0, s_iter = 0.0;        // gap and shear of the latest solve, m
  bool cohesion_lost = false;               // a cohesive contact failed in this step's iterations
  bool carried = false;                     // detection found it in the previous step's list too
  // It carries the state of the previous step's contact of the same vertex and reference edge
  // (not new, not a corner passed to another line): its spring's energy at the step's start
  // differs from what was booked only by the geometry's re-measure (ResidualSources).
  bool same_line = false;

  bool bonded(const std::vector<Joint>& joints) const {
    return joint >= 0 && !joints[static_cast<std::size_t>(joint)].broken;
  }
  /// Bonded, or tied: locked whatever its force, tension included.
  bool held(const std::vector<Joint>& joints) const { return tied || bonded(joints); }
  /// Blocks of the pair in increasing order.
  Index pair_low() const { return vblock < eblock ? vblock : eblock; }
  Index pair_high() const { return vblock < eblock ? eblock : vblock; }
};

/// The gradients of a contact's gap and shear with respect to the unknowns of its vertex block
/// (D_v) and edge block (D_e), from the geometry at the step's start. Kept beside the contact
/// list, not in its records: only the assembly and the judgement read them, and the other
/// passes over the records then stream less than half the bytes.
struct ContactLinearisation {
  Vec6 e = Vec6::Zero(), g = Vec6::Zero();    // d ≈ d0 + e·D_v + g·D_e
  Vec6 es = Vec6::Zero(), gs = Vec6::Zero();  // s ≈ s0 + es·D_v + gs·D_e
};

/// A block pair with contacts: contacts[first, last) of the sorted list.
struct ContactPair {
  Index a = 0, b = 0;  // a < b
  Index first = 0, last = 0;
};

/// Contacts sorted by (pair, vertex), their pairs, and per-block lists (both built serially from
/// the sorted list, so every parallel gather below sums in a fixed order).
struct ContactSet {
  std::vector<Contact> contacts;
  // The vertex block of every contact (Contact::vblock), beside the records: the assembly's
  // gathers need only this of a contact's identity, and a 224-byte record's cache line per
  // contact was a third of their time.
  std::vector<Index> vertex_blocks;
  std::vector<ContactPair> pairs;
  std::vector<Index> block_contact_offsets;  // CSR: contacts touching each block, ascending
  std::vector<Index> block_contacts;
  std::vector<Index> block_pair_offsets;  // CSR: pairs touching each block, by other block
  std::vector<Index> block_pairs;
};

struct DetectionParams {
  double search_distance = 0.0;  // m: vertices farther than this from an edge are ignored
  // m: margin of the pair list (Verlet list): pairs within search distance + skin are kept, and
  // the list is rebuilt once some vertex has moved more than half the skin since it was built.
  // A wider skin rebuilds less often but hands the narrow phase more pairs; the contacts found
  // do not depend on it.
  double skin = 0.0;
  double angle_tolerance = 0.0523;  // rad (3°): a vertex wedge may dip this far behind an edge
  double vv_max_gap_angle = 0.2;    // rad: vertex-vertex contact only if the wedges are this close
};

/// A provisional contact of the narrow phase: vertex of vblock against the edge of eblock that
/// starts at vertex e0.
struct ContactCandidate {
  bool valid = false;
  bool vv = false;
  double d = 0.0;
  Index vblock = 0, vertex = 0, eblock = 0, e0 = 0;
  bool shared_node = false;  // vv between the copies of one mesh node in one body (Contact::shared_node)
  // Contact::joint where the narrow phase knows it (-1: none), else kJointToFind.
  static constexpr Index kJointToFind = -2;
  Index joint = kJointToFind;
};

/// The contacts of a list grouped by vertex (CSR): the contact of a vertex in a block pair is
/// found among the vertex's own few contacts instead of by a search through the whole list.
struct ContactsByVertex {
  /// What a search reads instead of the contact (the entries of a vertex share a cache line or
  /// two): its index in the list, its block pair, the first vertex of its reference edge, and
  /// whether it is a closed vertex-vertex contact.
  struct Entry {
    Index contact = -1, low = -1, high = -1, edge = -1;
    bool closed_corner = false;
  };
  std::vector<Index> offsets;   // per vertex, into `entries`
  std::vector<Entry> entries;   // ascending list index for each vertex
  void build(const std::vector<Contact>& list, std::size_t vertex_count);
  /// Entry of vertex v's contact in the block pair {p, q}, or null.
  const Entry* entry(Index v, Index p, Index q) const;
  /// Index in the list of the contact of vertex v in the block pair {p, q}, or -1.
  Index find(Index v, Index p, Index q) const {
    const Entry* e = entry(v, p, q);
    return e ? e->contact : -1;
  }
};

/// Axis-aligned boxes of the blocks, grown by a margin.
struct BlockBoxes {
  std::vector<double> xmin, xmax, ymin, ymax;
};

/// What the narrow phase needs of a vertex, in one cache line: unit directions to the previous
/// and next vertex, the outward unit normal and length of the edge to the next vertex, and
/// whether the vertex is convex.
struct alignas(64) VertexFrame {
  double ax = 0.0, ay = 0.0, bx = 0.0, by = 0.0;
  double enx = 0.0, eny = 0.0, elen = 0.0;  // elen in m
  bool convex = false;
};

/// What the pair list knows of a pair from its last build. A quiet pair is one whose vertices
/// that the geometric rules judge (those on no intact joint of the pair and not a node copy) all
/// lay outside the other block and farther than search distance + skin from its boundary: until
/// the next build no vertex moves more than half the skin, so none of them can come within the
/// search distance or enter, and the pair's contacts are its topological ones (intact joints, the
/// node copies) while its topology is the one recorded here.
struct PairHint {
  bool quiet = false;
  int intact_joints = 0;     // intact virtual joints of the pair at the build
  Index joint = -1;          // the last of them (BlockSystem::joints), -1 if none
  Index joint_edge = -1;     // first vertex of the second block's edge along that joint
  Index node_v = -1, node_u = -1;  // copies (first block's, second's) of the one mesh node the
                                   // blocks share if they share no edge, else -1
  bool node_copies = false;  // they were held as one vertex-vertex contact
};

/// Detection state kept between steps: the pair list and scratch space (no reallocation).
struct DetectionWorkspace {
  BlockBoxes boxes;                       // per block, grown by half the search distance
  BlockBoxes reach_boxes;                 // grown by half of search distance + skin (pair-list builds)
  std::vector<std::vector<Index>> pairs;  // pair list: per block, partner blocks > it, ascending
  std::vector<std::vector<PairHint>> pair_hints;  // per entry of `pairs`
  std::vector<double> built_x, built_y;   // vertex positions when the pair list was built
  long pair_list_builds = 0;
  long pairs_judged = 0, quiet_pairs_judged = 0;  // narrow-phase pairs, and the quiet ones among them
  std::vector<VertexFrame> frames;  // per vertex
  std::vector<Index> cell_offsets, cell_blocks;
  std::vector<std::vector<Index>> candidates;        // per block: partner blocks > it
  std::vector<std::vector<PairHint>> candidate_hints;  // per entry of `candidates`
  std::vector<std::vector<ContactCandidate>> found;  // per block: contacts of its pairs
  ContactsByVertex previous_by_vertex;               // the previous step's contacts
};

/// Finds all contacts (identity and geometry only; state is transferred afterwards; the rules:
/// docs/design.md §4.1). The
/// previous step's contacts (sorted, as returned) only decide which reference line a closed
/// vertex-vertex corner, or a vertex inside the other block, keeps; work.previous_by_vertex is
/// left indexing them for
/// carry_contact_state. Deterministic: the output is sorted by (low block, high block,
/// vertex) whatever the threads.
/// `found` is overwritten; its storage is reused (pass the list of the step before last).
void detect_contacts(const BlockSystem& blocks, const DetectionParams& params, DetectionWorkspace& work,
                     const std::vector<Contact>& previous, std::vector<Contact>& found);

/// Carries state (state, reference point, forces, slip, cohesion) to the current contact `c` from
/// the previous list's contact of the same vertex and block pair, or of the same corner with
/// vertex and edge swapped (a vertex-vertex corner, or a joint's corner at its break); a new
/// contact starts closed (locked) if it touches or is
/// held (Contact::held), else open (a broken joint starts like a contact that was never bonded).
/// A tie that is no longer tied (`c.tied` is set before the call) is not carried: the node's
/// contact starts afresh and the tie's spring is released with the vanished contacts.
/// Returns the previous contact it carried (null if `c` is new), whether `c` is the node contact
/// of a tie just released, and whether `c` is the corner of a joint that has just broken, with
/// vertex and edge swapped (keep_normal_spring then keeps its spring, once `c` has its
/// properties). `previous_by_vertex` indexes `previous` (DetectionWorkspace after detection);
/// `current` is the list `c` belongs to, sorted as detect_contacts returns it. Writes only `c`,
/// and reads of `current` only the contacts' identities (pair, vertex), so the contacts of a list
/// can be carried in parallel. (docs/design.md §4.7)
struct CarriedState {
  const Contact* previous = nullptr;
  bool tie_released = false;
  bool swapped_at_break = false;
};
CarriedState carry_contact_state(const std::vector<Contact>& previous, const ContactsByVertex& previous_by_vertex,
                                 const std::vector<Contact>& current, Contact& c, const std::vector<Joint>& joints,
                                 const BlockSystem& blocks);

/// The corner of a joint that has just broken, its vertex and edge swapped
/// (CarriedState::swapped_at_break), measures its overlap at the other copy of the node, which
/// lies deeper or shallower than the copy the joint held by the blocks' relative turn and slide
/// between the copies. So that the joint's compression passes to the contact without a jump in
/// force or energy, `c` (its kn assigned) takes the rest gap at which its normal spring holds the
/// compression `previous` held; the shear spring's extension is kept the same way
/// (carry_contact_state). The rest gap may then be positive: the corner keeps pushing until the
/// gap exceeds it, and opens there at zero force. Only at the break, once: the copies of an
/// intact body's node pass their contact back and forth, and offsets kept at every pass would
/// add up to an overlap nothing pushes out. Returns whether it kept a spring (`previous` closed
/// and in compression). (docs/design.md §4.7)
bool keep_normal_spring(Contact& c, const Contact& previous);

/// Fills pairs and per-block lists of a sorted contact list.
void build_contact_topology(ContactSet& set, std::size_t block_count);

}  // namespace ddafrac::dda
