#pragma once
// Index handles: distinct 32-bit types with a named invalid value (no pointer-linked objects).
#include <cstdint>
#include <limits>

namespace shoremesh::engine {

using VertexId = std::uint32_t;
using NodeId = std::uint32_t;
using OpId = std::uint32_t;

inline constexpr VertexId kNoVertex = std::numeric_limits<VertexId>::max();
inline constexpr NodeId kNoNode = std::numeric_limits<NodeId>::max();
inline constexpr OpId kNoOp = std::numeric_limits<OpId>::max();

}  // namespace shoremesh::engine
