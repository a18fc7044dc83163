#pragma once
// StableWS (paper, Figure 3) with its computation graph. Vertices, operations and the quadtree live in
// flat arrays reached by 32-bit ids. An operation is a dispatch (colour 0) or a fill (colour 1..kappa^D)
// acting on one vertex at a time (rank, colour); operations run in time order. While it runs, the engine
// records for every operation its children (the fills a dispatch asked for, the dispatches of the Steiner
// vertices a fill inserted) and for every leaf the operations that read it: what PropagateWS replays.
#include <cstdint>
#include <span>
#include <vector>

#include "shoremesh/engine/convex_cell.hpp"
#include "shoremesh/engine/ids.hpp"
#include "shoremesh/engine/quadtree.hpp"
#include "shoremesh/engine/rank_scale.hpp"
#include "shoremesh/parameters.hpp"
#include "shoremesh/point.hpp"

namespace shoremesh {

template <int D>
class WellSpacedEngine {
 public:
  using VertexId = engine::VertexId;
  using OpId = engine::OpId;
  using NodeId = engine::NodeId;

  enum class OpKind : std::uint8_t { Dispatch, Fill };

  struct Vertex {
    Point<D> position{};
    NodeId leaf = engine::kNoNode;
    OpId creator = engine::kNoOp;      // the fill that inserted this Steiner vertex; none for inputs
    OpId dispatch = engine::kNoOp;     // the one dispatch acting on it
    OpId first_fill = engine::kNoOp;   // its fills, linked by Op::next_fill (one per rank)
    bool is_input = false;
  };

  struct Op {
    VertexId vertex = engine::kNoVertex;
    std::int32_t rank = 0;
    std::uint32_t color = 0;           // 0 for dispatches
    OpKind kind = OpKind::Dispatch;
    OpId parent = engine::kNoOp;       // the operation that created it (none for input dispatches)
    OpId next_fill = engine::kNoOp;    // next fill acting on the same vertex
    std::uint32_t requesters = 0;      // fills: how many dispatches asked for it
    std::uint32_t children_begin = 0, children_end = 0;  // into children_
    std::uint32_t reads_begin = 0, reads_end = 0;        // into reads_
  };

  explicit WellSpacedEngine(const Parameters<D>& parameters);

  // StableWS on points of the unit box. Throws PointInputError (non-finite, outside, duplicate).
  void build(std::span<const Point<D>> unit_points);

  std::size_t input_count() const { return input_count_; }
  std::size_t vertex_count() const { return vertices_.size(); }
  const Vertex& vertex(VertexId v) const { return vertices_[v]; }
  std::span<const Point<D>> positions() const { return positions_; }
  std::size_t op_count() const { return ops_.size(); }
  const Op& op(OpId o) const { return ops_[o]; }
  std::span<const OpId> children(OpId o) const {
    return {children_.data() + ops_[o].children_begin, children_.data() + ops_[o].children_end};
  }
  std::span<const NodeId> reads(OpId o) const {
    return {reads_.data() + ops_[o].reads_begin, reads_.data() + ops_[o].reads_end};
  }
  const engine::Quadtree<D>& quadtree() const { return tree_; }
  const DerivedParameters<D>& parameters() const { return params_; }
  const Counters& counters() const { return counters_; }
  std::size_t memory_bytes() const;
  void check_valid() const;

 private:
  struct Candidate {
    double d2;  // squared distance to v, rounded (orders the clipping; decisions are exact)
    VertexId id;
  };
  struct Neighbourhood {
    VertexId nearest = engine::kNoVertex;
    // Every vertex of the leaves searched: all vertices that can cut v's cell, and more.
    std::vector<Candidate> candidates;
  };

  void reset();
  OpId new_op(OpKind kind, VertexId v, int rank, std::uint32_t color, OpId parent);
  void schedule(OpId o);
  void run();
  void dispatch(OpId o);
  void fill(OpId o);
  void request_fill(OpId parent, VertexId w, int rank);
  // Finds v's nearest neighbour and the vertices within 2 beta NN(v), records the leaves read by op o,
  // and computes v's cell clipped to the box and to the cube of half-side beta NN(v).
  void compute_cell(OpId o, VertexId v);
  Point<D> pick_steiner(VertexId v);
  VertexId insert_steiner(const Point<D>& p, OpId creator, NodeId near);
  double squared_distance(VertexId a, VertexId b) const;

  DerivedParameters<D> params_;
  engine::RankScale<D> ranks_;
  engine::Quadtree<D> tree_;
  std::vector<Vertex> vertices_;
  std::vector<Point<D>> positions_;     // positions_[v] == vertices_[v].position, contiguous for the tree
  std::size_t input_count_ = 0;
  std::vector<Op> ops_;
  std::vector<OpId> children_;
  std::vector<NodeId> reads_;
  std::vector<std::vector<OpId>> readers_;  // per quadtree node: operations that read it
  // Operations waiting, by rank: dispatches, then fills (sorted by colour when their rank comes).
  std::vector<std::vector<OpId>> pending_dispatch_, pending_fill_;
  int current_rank_ = 0;
  // Scratch of the operation being executed (reused: no allocation per operation).
  engine::ConvexCell<D> cell_;
  Neighbourhood hood_;
  std::vector<VertexId> neighbours_;
  std::vector<NodeId> covering_;
  Counters counters_;
};

}  // namespace shoremesh
