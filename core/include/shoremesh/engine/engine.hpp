#pragma once
// StableWS (paper, Figure 3) with its computation graph. Vertices, operations and the quadtree live in
// flat arrays reached by 32-bit ids. An operation is a dispatch (colour 0) or a fill (colour 1..kappa^D)
// acting on one vertex at a time (rank, colour); operations run in time order. While it runs, the engine
// records for every operation its children (the fills a dispatch asked for, the dispatches of the Steiner
// vertices a fill inserted) and for every leaf the operations that read it: what PropagateWS replays.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <span>
#include <tuple>
#include <vector>

#include "shoremesh/engine/block_pool.hpp"
#include "shoremesh/engine/cell_reach.hpp"
#include "shoremesh/engine/convex_cell.hpp"
#include "shoremesh/engine/delaunay_neighbours.hpp"
#include "shoremesh/engine/facet_filter.hpp"
#include "shoremesh/engine/ids.hpp"
#include "shoremesh/engine/quadtree.hpp"
#include "shoremesh/engine/rank_scale.hpp"
#include "shoremesh/engine/reader_lists.hpp"
#include "shoremesh/engine/water.hpp"
#include "shoremesh/parameters.hpp"
#include "shoremesh/point.hpp"

namespace shoremesh {

namespace engine {
// How many threads a build computes the operations of one (rank, colour) batch on: 0 (the default) for
// every core. The output does not depend on it (the commit is serial, in batch order). Process-wide.
void set_thread_count(unsigned threads);
unsigned thread_count();
}  // namespace engine

template <int D>
class WellSpacedEngine {
 public:
  using VertexId = engine::VertexId;
  using OpId = engine::OpId;
  using NodeId = engine::NodeId;

  enum class OpKind : std::uint8_t { Dispatch, Fill };

  // Its position is positions_[v] (positions()): the one copy, contiguous for the tree and the searches.
  // What every build keeps of a vertex (12 bytes); a build for updates also keeps its VertexOps.
  struct Vertex {
    NodeId leaf = engine::kNoNode;
    OpId first_fill = engine::kNoOp;   // its fills, linked by Op::next_fill (one per rank)
    bool is_input = false;
    bool alive = false;
  };
  // By vertex id, in a build for updates: what undoing and redispatching read.
  struct VertexOps {
    OpId creator = engine::kNoOp;      // the fill that inserted this Steiner vertex; none for inputs
    OpId dispatch = engine::kNoOp;     // the one dispatch acting on it
  };
  // A vertex as a whole (vertex()): creator and dispatch are kNoOp after a one-shot build.
  struct VertexInfo : Vertex, VertexOps {};

  // Operation states during change propagation (paper, Figure 4).
  enum OpFlag : std::uint8_t {
    kExecuted = 1,    // has run: its children, reads and Steiner vertices are recorded
    kQueued = 2,      // on the agenda at its time
    kFresh = 4,       // to execute (new)
    kRedo = 8,        // inconsistent: read a square that changed, to undo and execute again
    kObsolete = 16,   // to undo and delete
    kDead = 32,       // deleted; the slot is freed when the propagation ends
    kStashed = 64,    // an inconsistent fill undone but for its Steiner vertices: it may insert them again
  };

  // What every build keeps of an operation: 16 bytes. A one-shot build's operations are the waiting
  // ones (every operation is freed once it has run), a build for updates keeps them all, each with what
  // only updates read (RecordedOp). Ranks lie within [RankScale::min_rank, max_rank] (a few hundred at
  // most) and colours within kappa^D + 1 (checked at construction); requesters are counted in 16 bits
  // (checked where they are written).
  struct Op {
    std::int16_t rank = 0;
    std::uint16_t color = 0;           // 0 for dispatches
    VertexId vertex = engine::kNoVertex;
    OpId next_fill = engine::kNoOp;    // next fill acting on the same vertex
    std::uint16_t requesters = 0;      // fills: how many dispatches currently ask for it
    std::uint8_t flags = 0;
    OpKind kind : 1 = OpKind::Dispatch;
    // A hint for its searches, kept for its life: one of its cells had many candidates, or it was made
    // by an operation that was crowded (a fill asked for by a crowded dispatch, the dispatch of a
    // Steiner vertex a crowded fill inserted: they lie near). Its searches then skip what cannot cut
    // its cell (compute_cell). Changes only the work, never the result.
    bool crowded : 1 = false;
    // A fill skipped because its vertex's cell could not meet the water (docs/water_only.md).
    bool on_land : 1 = false;
    // A fill that looked for the shore at its vertex (its cell was not well-spaced, shore_cells on):
    // it read the rings there, so a ring edit nearby reruns it (docs/water_only.md).
    bool shore_read : 1 = false;
    // How many tree nodes a build for updates registered it as a reader of (RecordedOp::reads_cover):
    // the nodes covering one box, at most 2^D (Quadtree::covering_nodes). Here, in the flag byte's
    // spare bits, it leaves RecordedOp 8 bytes smaller in 2D.
    std::uint8_t reads_count : 4 = 0;
    static constexpr std::size_t kMaxReads = 15;
  };
  static_assert(sizeof(Op) == 16, "Op packs to 16 bytes");
  static_assert(Op::kMaxReads >= (1u << D), "an operation's reads count fits its bits");
  // An operation of a build for updates: 48 bytes in 2D, 80 in 3D. What marking readers reads of each
  // reader it scans (rank to reach) lies in the first 38 bytes: a 2D one starts at any of four offsets
  // in a cache line, and these straddle two lines at two of them. Runs are counted in 16 bits
  // (checked where they are written).
  struct RecordedOp : Op {
    // Removing a vertex matters only if it bounds the cell (facet_filter.hpp); everything: any vertex.
    engine::FacetFilter<D> facets = engine::FacetFilter<D>::everything();
    // Its result depends only on the vertices within these squared distances: removing one within
    // depends2, or inserting one within inserted_depends2() (smaller for a fill that found its vertex
    // well-spaced: a new vertex farther than NN only shrinks the cell, and it stays well-spaced).
    // Rounded up (see at_least): a radius only ever errs on the side of a rerun.
    float depends2 = 0;
    // inserted_depends2() in 256ths of depends2, rounded up, 255 for all of it: one byte instead of a
    // float's four. Decoding is exact (a float times a byte and a power of two), whatever the rounding.
    std::uint8_t inserted_256ths = kWhole;
    // Inserting a vertex within inserted_depends2() matters only if it can cut the cell (cell_reach.hpp).
    engine::CellReach<D> reach = engine::CellReach<D>::unbounded();
    std::uint16_t children_count = 0;
    std::uint32_t children_begin = 0;  // into children_, children_count of them
    // The nodes it read, as Quadtree::covering_nodes coded them about its vertex: found again from the
    // code when it is undone, not kept (21 M node ids at 2D n = 1e6). Should the tree's shape over them
    // have changed meanwhile, the nodes split or merged away lost their reader lists with their readers
    // marked (apply_tree_change), and the nodes found in their place never listed it.
    std::uint32_t reads_cover = 0;

    static constexpr std::uint8_t kWhole = 255;
    static double fraction(std::uint8_t q) { return q == kWhole ? 1.0 : double(q) * 0x1p-8; }
    double inserted_depends2() const { return double(depends2) * fraction(inserted_256ths); }
    // Both radii the same.
    void set_depends2(float both) {
      depends2 = both;
      inserted_256ths = kWhole;
    }
    // The insertion radius: the least fraction of depends2 at least `inserted` (all of depends2 when
    // `inserted` is larger: depends2 then grows to it).
    void set_inserted_depends2(float inserted) {
      if (!(inserted < depends2)) {
        set_depends2(std::max(depends2, inserted));
        return;
      }
      auto holds = [&](int q) { return double(depends2) * fraction(std::uint8_t(q)) >= double(inserted); };
      int q = std::clamp(int(std::ceil(double(inserted) / double(depends2) * 256)), 0, int(kWhole));
      while (q < kWhole && !holds(q)) ++q;
      while (q > 0 && holds(q - 1)) --q;
      inserted_256ths = std::uint8_t(q);
    }
  };
  static_assert(sizeof(RecordedOp) == (D == 2 ? 48 : 80), "RecordedOp packs to 48 bytes in 2D and 80 in 3D");

  // One edit for apply(): add a point (id returned) or remove an input vertex.
  struct InputEdit {
    bool add = true;
    Point<D> point{};
    VertexId vertex = engine::kNoVertex;
  };

  struct PropagationStats {
    std::size_t undone = 0, executed = 0;
    std::vector<Point<D>> steiner_removed, steiner_added;  // net: a point removed and re-inserted cancels
  };

  explicit WellSpacedEngine(const Parameters<D>& parameters);
  ~WellSpacedEngine();

  // StableWS on points of the unit box. Throws PointInputError (non-finite, outside, duplicate).
  // Returns the vertex of each point. With lay_out_for_updates, all vertices, inputs and Steiner, are
  // then numbered along a space-filling curve (spatial_order.hpp), inputs among the others, and the
  // operations after their vertices, and reader lists get room to grow: what updates read together lies
  // together, and stays so. Without it (the output is read once) the numbering stays as built: inputs
  // along the curve, then Steiner vertices and operations in time order. The output is the same either
  // way. Without `for_updates` (a one-shot run: the output is read once) the build records nothing that
  // only updates read (reads, reader lists, children, facets, reach) and frees each operation once it
  // has run: apply() then throws std::logic_error.
  std::vector<VertexId> build(std::span<const Point<D>> unit_points, bool for_updates = true);
  // The same, the points' array becoming the positions' (one copy of them fewer during the build).
  std::vector<VertexId> build(std::vector<Point<D>>&& unit_points, bool for_updates = true);
  bool updatable() const { return recording_; }

  // PropagateWS: input edits applied to the live computation, which then equals build() on the new
  // input. The caller checks the edits first (inside the box, no duplicate input, live ids).
  // Returns the vertex ids of added points, in order.
  // With a water domain (2D): `water` are the changes of its edges (unit box), taken in before the
  // propagation; each marks the fills that read the water where it changed.
  std::vector<VertexId> apply(std::span<const InputEdit> edits, PropagationStats* stats = nullptr,
                              std::span<const engine::WaterEdit> water = {});

  // Work only where the water is (2D; docs/water_only.md): from the next build on, a fill whose vertex's
  // cell cannot meet the closed water of these rings (even-odd; unit-box points; a ring with fewer than 3
  // points, such as a line, bounds nothing) inserts nothing.
  void set_water(std::vector<std::vector<Point2>> unit_rings);
  const engine::WaterRings* water() const { return water_.get(); }
  // The vertices with a live fill skipped on land (a build for updates: a one-shot build forgets its fills).
  std::vector<VertexId> vertices_skipped_on_land() const;

  // The live operations as (vertex position, rank, colour), sorted: equal for a dynamic and a fresh run.
  std::vector<std::tuple<Point<D>, int, std::uint32_t>> operation_signature() const;
  std::size_t live_op_count() const { return op_count() - free_ops_.size() - lean_free_count_; }
  std::size_t live_vertex_count() const { return vertices_.size() - free_vertices_.size(); }
  // Whether some live input vertex sits exactly at p.
  VertexId input_at(const Point<D>& p) const;

  std::size_t input_count() const { return input_count_; }
  std::size_t vertex_count() const { return vertices_.size(); }
  VertexInfo vertex(VertexId v) const {
    VertexInfo info;
    static_cast<Vertex&>(info) = vertices_[v];
    if (recording_) static_cast<VertexOps&>(info) = vertex_ops_[v];
    return info;
  }
  std::span<const Point<D>> positions() const { return positions_; }
  std::size_t op_count() const { return recording_ ? recorded_ops_.size() : lean_ops_.size(); }
  const Op& op(OpId o) const { return recording_ ? recorded_ops_[o] : lean_ops_[o]; }
  // Runs of an engine built for updates (a one-shot build records none).
  std::span<const OpId> children(OpId o) const {
    if (!recording_) return {};
    const RecordedOp& op = recorded_ops_[o];
    return children_.run(op.children_begin, op.children_begin + op.children_count);
  }
  std::vector<NodeId> reads(OpId o) const {
    std::vector<NodeId> nodes;
    if (recording_ && recorded_ops_[o].reads_count != 0)
      tree_.cover_nodes(positions_[recorded_ops_[o].vertex], recorded_ops_[o].reads_cover, nodes);
    return nodes;
  }
  const engine::Quadtree<D>& quadtree() const { return tree_; }
  const DerivedParameters<D>& parameters() const { return params_; }
  const Counters& counters() const { return counters_; }
  // Bytes held by the live structures, by capacity, part by part (bench_dynamic prints them per output
  // vertex): what an engine kept for updates costs, and where.
  struct MemoryBreakdown {
    std::size_t vertices = 0, positions = 0, operations = 0, children = 0, readers = 0, tree = 0;
    std::size_t delaunay = 0;  // the one-shot build's triangulation of M_t, when it is the neighbour source
    std::size_t other = 0;     // the agenda, the free lists, the cell cache
    std::size_t scratch = 0;   // the batch's, and each thread's (its cell, candidates, outcomes)
    std::size_t total() const {
      return vertices + positions + operations + children + readers + tree + delaunay + other + scratch;
    }
  };
  MemoryBreakdown memory_breakdown() const;
  std::size_t memory_bytes() const { return memory_breakdown().total(); }
  void check_valid() const;

 private:
  struct Candidate {
    double d2;  // squared distance to v, rounded (orders the clipping; decisions are exact)
    VertexId id;
    Point<D> position;
  };
  // Above this many candidates, a cell is clipped in distance bands, its candidates are filtered by what
  // can still cut it, its searches skip what cannot, and its operation is crowded (compute_cell). A
  // uniform cell has about 30 in 2D and 160 in 3D, where a cell has many more vertices to test against;
  // lower thresholds cost uniform inputs more than they saved.
  static constexpr std::size_t kCrowdedPool = D == 2 ? 128 : 1024;
  struct Neighbourhood {
    VertexId nearest = engine::kNoVertex;
    // Every vertex of the leaves searched: all vertices that can cut v's cell, and more.
    std::vector<Candidate> candidates;
  };
  // A vertex of the tree with its birth (the tag its leaf keeps).
  struct TimedVertex {
    Point<D> position;
    std::uint64_t birth;
    VertexId id;
  };
  // The scratch of one thread computing operations (reused: no allocation per operation).
  struct Worker {
    engine::ConvexCell<D> cell;
    Neighbourhood hood;
    std::vector<TimedVertex> unborn;      // vertices a search skipped as born at or after now
    std::vector<VertexId> neighbours;
    std::vector<NodeId> covering;         // the nodes the operation read (when recording)
    std::uint32_t cover = 0;              // their code (Quadtree::covering_nodes)
    Counters counters;
    engine::ConvexCell<D> part;           // shore_cells: the cell restricted to a water half-plane
    std::vector<std::array<Point2, 2>> shore_edges;  // shore_cells: ring edges near the vertex
  };
  // What computing an operation decided, for its commit: computing reads the engine only (and writes
  // its own Op's hints and dependency radii), so the operations of one time can be computed at once
  // (Lemma 6.1: each sees only the vertices born before their time) and committed one after the other.
  struct Outcome {
    std::vector<std::pair<VertexId, int>> requests;  // a dispatch's fills to ask for: (vertex, rank)
    // A fill's Steiner points, their dispatches' ranks and their leaves: Steiner points leave the tree's
    // shape as it is, so a leaf found while computing is the leaf at the commit, and the look-up runs on
    // every thread instead of in the serial commit.
    struct Steiner {
      Point<D> at;
      int rank;
      NodeId leaf;
    };
    std::vector<Steiner> steiner;
    std::vector<NodeId> covering;                    // the nodes to register it as a reader of
    std::uint32_t cover = 0;                         // their code
  };

  // A time (rank, colour) as one integer in the same order. A vertex's tag in its leaf is its birth
  // time: its creator's time, 0 for inputs (before everything). An operation at time t sees only the
  // vertices born before t, the output M_t of the paper: during a propagation the tree still holds
  // vertices of later operations from the previous run, which a from-scratch run would not have yet.
  // Ranks fit 16 bits above -2^15 and colours 16 bits (checked at construction): 32 bits, never 0.
  static std::uint32_t time_key(int rank, std::uint32_t color) {
    return (std::uint32_t(std::uint16_t(rank) ^ 0x8000u) << 16) | color;
  }
  void reset();
  // build(): `own`, when given, holds unit_points and becomes positions_.
  std::vector<VertexId> build(std::span<const Point<D>> unit_points, std::vector<Point<D>>* own, bool for_updates);
  OpId new_op(OpKind kind, VertexId v, int rank, std::uint32_t color);
  // The agenda: operations keyed by time (rank, colour), executed in time order.
  void enqueue(OpId o);
  void mark_fresh(OpId o);
  void mark_obsolete(OpId o);
  void mark_redo(OpId o);
  // The vertex at p was inserted or removed at time (rank, color) (before everything when rank is the
  // minimum int): marks inconsistent every later operation that depends on it, among the readers
  // registered on p's leaf and its ancestors (its facet bits are its position's).
  enum class VertexChange { Inserted, Removed };
  void mark_readers_at(const Point<D>& p, NodeId leaf, VertexChange change, int rank,
                       std::uint32_t color);
  // Dispatches and fills that insert nothing decide from v's nearest neighbour and the set of vertices
  // whose bisectors bound v's cell: removing any other vertex leaves the cell and the decision as they
  // were. That set is kept as a Bloom filter of vertex positions (facet_filter.hpp): a false "maybe" only
  // costs a rerun.
  void record_facets(OpId o, const Worker& w);
  void mark_all_readers(NodeId n);
  void propagate(PropagationStats* stats);
  void undo(OpId o);
  void execute(OpId o);
  void kill(OpId o);
  // An operation in two steps: compute (reads the engine, writes only its own Op's hints and radii, and
  // the cell cache when caching_, which is serial) and commit (changes the engine).
  void compute(OpId o, Worker& w, Outcome& out);
  void commit(OpId o, Outcome& out);
  void compute_dispatch(OpId o, Worker& w, Outcome& out);
  void compute_fill(OpId o, Worker& w, Outcome& out);
  void commit_dispatch(OpId o, Outcome& out);
  void commit_fill(OpId o, Outcome& out);
  // A batch of fresh operations computed on every thread, then committed in batch order.
  void execute_batch_in_parallel();
  void release_executed(OpId o);
  void unlink_from_vertex(OpId o);
  void request_fill(VertexId w, int rank, bool crowded);
  // Whether a neighbour of the dispatched vertex other than w (in w.neighbours) lies nearer w than
  // rho^rank: then a fill of w at that rank would do nothing (see engine.cpp).
  bool already_below_rank(const Worker& wk, VertexId w, int rank, engine::PredicateCounters& pc) const;
  void redispatch_input(VertexId v);
  void apply_tree_change(const typename engine::Quadtree<D>::Change& change);
  // The water changed inside the closed box [lo, hi]: every fill that read a node meeting it runs again.
  void mark_water_readers(const Point<D>& lo, const Point<D>& hi);
  // Whether the fill of v, whose cell w.cell is not well-spaced, is skipped: the cell cannot meet the water.
  bool fill_on_land(VertexId v, Worker& w) const;
  // Cells that stop at the shore (engine_shore_cells.cpp, docs/water_only.md): the water wedge at input
  // vertex v on the rings, if v is one and the wedge is found; then whether v is rho-well-spaced in its
  // cell restricted to the wedge, leaving a part that is not in w.part.
  struct ShoreWedge {
    Point2 prev{}, next{};  // the wedge's sides: the lines through v and prev, v and next
    int side = 1;           // water: side * orient2d(prev, v, x) >= 0 and side * orient2d(v, next, x) >= 0 ...
    bool convex = true;     // ... both (convex), or either (a reflex water angle)
  };
  bool shore_wedge(VertexId v, Worker& w, ShoreWedge& wedge) const;
  bool well_spaced_in_wedge(VertexId v, Worker& w, const ShoreWedge& wedge) const;
  // Where in w.part (left by well_spaced_in_wedge) a Steiner point aims: among its vertices strictly off
  // the wedge's lines, as pick_steiner aims in a cell; false when none of them lies beyond rho NN.
  bool aim_in_wedge(const Worker& w, const ShoreWedge& wedge, Point<D>& aim) const;
  // Finds v's nearest neighbour and the vertices that can cut its cell, registers op o's reads, and
  // computes v's cell clipped to the box and to the cube of half-side beta NN(v). For a fill, returns
  // false without a cell when v's nearest neighbour makes the fill idle (record_idle_fill).
  bool compute_cell(OpId o, VertexId v, bool fill, Worker& w);
  // Its steps: gathering the candidates, clipping, recording the dependencies (engine_cells.cpp).
  struct CellSearch;
  void record_idle_fill(OpId o, VertexId v, Worker& w);
  // The nodes covering the box of half-side h around p, left in w.covering with their code in w.cover
  // (when recording): what op o's commit registers it as a reader of. p is the operation's vertex's.
  void record_reads(Worker& w, const Point<D>& p, double h) const;
  void register_reads(OpId o, std::span<const NodeId> nodes, std::uint32_t cover);
  // The cell cache of one propagation (cell_cache.cpp has the argument why reuse equals recomputing).
  struct CachedCell;
  // v's entry, stale or not: its last cell, and what the leaves around v held when it was computed.
  const CachedCell* cached_neighbourhood(VertexId v, const Point<D>& p);
  // Takes v's cell from its entry c for op o at time now, if the entry still holds then.
  bool reuse_cell(OpId o, const CachedCell& c, std::uint64_t now);
  void store_cell(OpId o, VertexId v, const Point<D>& p, double searched);
  void forget_cell(VertexId v);
  // A fill just inserted vertex w at q: the cells it may change are stale, and the entries whose box
  // it entered list it.
  void vertex_arrived(VertexId w, const Point<D>& q, std::uint64_t birth);
  void clear_cell_cache();
  // A Steiner point in the picking region of w.cell, toward `aim` (relative to v) when given.
  Point<D> pick_steiner(VertexId v, Worker& w, const Point<D>* aim = nullptr) const;
  VertexId new_vertex(const Point<D>& p);
  void kill_vertex(VertexId v);
  void lay_out_children();
  // The children pool's entries that the live operations' runs take (their blocks, not their lengths).
  std::size_t live_children_entries() const;
  void release_reads(RecordedOp& op);
  void release_children(RecordedOp& op);
  void store_children(OpId o);
  void add_counters(Worker& w);
  std::size_t scratch_bytes() const;  // the batch's and the workers' buffers (memory_breakdown)
  void collect_counters();  // every worker's counts into counters_
  // After the build: vertices, then operations, renumbered along the curve (engine.cpp says why).
  // Returns the new id of each old vertex id.
  std::vector<VertexId> renumber_vertices_by_place();
  void renumber_operations_by_place();
  // A vertex's bits in the facet filters: its position's (a vertex keeps its place for its life).
  engine::FacetFilter<D> facet_bits(VertexId w) const { return facet_bits_at(positions_[w]); }
  static engine::FacetFilter<D> facet_bits_at(const Point<D>& p) {
    return engine::FacetFilter<D>::of(engine::FacetFilter<D>::key_of(p));
  }
  double squared_distance(VertexId a, VertexId b) const;

  DerivedParameters<D> params_;
  engine::RankScale<D> ranks_;
  engine::Quadtree<D> tree_;
  std::vector<Vertex> vertices_;
  std::vector<VertexOps> vertex_ops_;   // by vertex id; only in a build for updates
  std::vector<Point<D>> positions_;     // by vertex id
  std::size_t input_count_ = 0;
  // The operations: a one-shot build's in lean_ops_, a build for updates' in recorded_ops_ (the other
  // one empty). op_at reaches either.
  std::vector<Op> lean_ops_;
  std::vector<RecordedOp> recorded_ops_;
  Op& op_at(OpId o) { return recording_ ? static_cast<Op&>(recorded_ops_[o]) : lean_ops_[o]; }
  engine::BlockPool children_;  // each operation's run: children_count from children_begin
  std::vector<OpId> new_children_;  // the children of the operation being executed, stored when it ends
  // Per quadtree node: the operations that read it (reader_lists.hpp).
  engine::ReaderLists readers_;
  // The agenda: one bucket of operations per time (rank, colour) from agenda_base_rank_ on, the
  // buckets before agenda_next_ empty. Ranks span O(log spread) and colours kappa^D + 1.
  std::vector<std::vector<OpId>> agenda_;
  int agenda_base_rank_ = 0;
  std::size_t agenda_next_ = 0;
  std::size_t agenda_size_ = 0;
  std::size_t agenda_slot(int rank, std::uint32_t color);
  std::vector<OpId> batch_;               // the operations of the time being processed
  std::vector<std::pair<std::uint64_t, OpId>> batch_keys_, batch_keys_scratch_;  // a large batch's ops by place
  void sort_batch_by_place();
  static constexpr std::size_t kSortedBatch = 256;
  // Batches at least this large are computed on several threads (smaller ones cost more to hand out).
  static constexpr std::size_t kParallelBatch = 64;
  // A larger batch is computed and committed this many operations at a time (in batch order, as one
  // thread does: Lemma 6.1), so that the outcomes waiting for their commit, and their buffers, stay
  // few: one per operation of the largest batch held a few tens of bytes per input vertex.
  static constexpr std::size_t kParallelChunk = 4096;
  std::vector<Outcome> outcomes_;         // one per operation of a chunk computed in parallel
  struct Workers;                         // per-thread Workers (TBB), engine_operations.cpp
  struct WorkersDeleter {
    void operator()(Workers* w) const;
  };
  std::unique_ptr<Workers, WorkersDeleter> workers_;
  bool recording_ = true;                 // false: a one-shot build (build without for_updates)
  // 2D one-shot builds with engine::delaunay_neighbours(): M_t triangulated, which cells walk for their
  // candidates instead of searching the tree (docs/delaunay_neighbours.md).
  std::unique_ptr<engine::DelaunayNeighbours> delaunay_;
  std::unique_ptr<engine::WaterRings> water_;  // 2D: skip fills on land (docs/water_only.md)
  std::vector<OpId> free_ops_, dead_ops_;
  // A one-shot build's free slots, linked by their next_fill (release_executed): no list beside them.
  OpId lean_free_ = engine::kNoOp;
  std::size_t lean_free_count_ = 0;
  std::vector<VertexId> free_vertices_, dead_vertices_;
  bool dynamic_ = false;                  // marking readers is needed only once a computation exists
  PropagationStats* stats_ = nullptr;
  // Scratch of the operation being executed serially (reused: no allocation per operation).
  Worker serial_;
  Outcome serial_outcome_;
  std::vector<NodeId> undone_reads_;  // undo's scratch: the nodes the operation undone read
  // A vertex's cell is computed about three times per update (its dispatch and its fills at several
  // times), and half of the time nothing that can change it was born in between: the cache keeps, for
  // the length of one propagation, each vertex's last cell with what decides whether it still holds.
  struct CachedCell {
    Point<D> position{};
    // It holds at a later time t while t < valid_until: the birth of the first vertex already in the
    // tree, but born after it was computed, within sqrt(depends2). 0 once a vertex was inserted within
    // (or its own vertex died): it holds no more.
    std::uint64_t valid_until = 0;
    float depends2 = 0;
    engine::CellReach<D> reach;
    // The nodes its operation read (covering the box it searched): the tree's shape does not change
    // during a propagation (Steiner vertices only enter and leave leaves), so they stay the same.
    std::vector<NodeId> covering;
    std::uint32_t cover = 0;
    VertexId nearest = engine::kNoVertex;
    // Every vertex of the leaves that meet the box [p - searched, p + searched]: those born before the
    // cell's time (candidates), those born later (unborn), and those fills inserted there since
    // (arrived). A vertex born before the cell's time never leaves during the propagation.
    double searched = 0;
    std::vector<Candidate> candidates;
    std::vector<TimedVertex> unborn, arrived;
    engine::ConvexCell<D> cell;
  };
  static constexpr std::uint32_t kNoCacheSlot = ~std::uint32_t(0);
  static constexpr std::size_t kMaxCachedCells = 1024;  // bounds its memory in large batches (a miss only recomputes)
  // Entries kept (with their buffers) between propagations: a unit update uses about 30 in 2D, 180 in 3D.
  static constexpr std::size_t kKeptCachedCells = 64;
  bool caching_ = false;                  // during a propagation after the build
  std::vector<CachedCell> cell_cache_;    // [0, cell_cache_live_) in use; the rest keeps its buffers
  std::size_t cell_cache_live_ = 0;
  // Vertex id -> entry, open addressing with linear probing (a table of a few thousand slots emptied after
  // each propagation: an array over all vertex ids would cost O(n) to allocate and to grow).
  struct CacheSlot {
    VertexId vertex = engine::kNoVertex;
    std::uint32_t entry = kNoCacheSlot;
  };
  static constexpr int kCacheTableBits = 11;  // 2048 slots: at most half full (kMaxCachedCells)
  std::vector<CacheSlot> cache_table_;
  CacheSlot& cache_slot(VertexId v);
  std::vector<OpId> stash_;
  Counters counters_;
};

}  // namespace shoremesh
