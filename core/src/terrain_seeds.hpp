#pragma once
// The seeds of a terrain TIN (terrain.hpp, step 1): the corners of the leaves of a quadtree over the
// grid's samples. Node (c0, r0, s) covers the samples [c0, c0 + s] x [r0, r0 + s]; it is a leaf when s = 1
// or when every valid sample of its window (the node grown by s/2 on each side, clipped to the grid) lies
// within `tolerance` of the window's least-squares plane. The decision reads the window only, and a
// child's window lies inside its parent's: an edit of a window of samples re-decides exactly the nodes
// whose window meets it, and the seeds equal those of a fresh build on the edited grid.
#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "shoremesh/terrain.hpp"

namespace shoremesh::terrain {

struct SampleWindow {
  int c0 = 0, r0 = 0, c1 = 0, r1 = 0;  // inclusive
};

class Seeds {
 public:
  Seeds() = default;
  // tolerance <= 0: no seeds but the grid's four corners.
  void build(const HeightGrid& grid, double tolerance);
  // The grid's samples in `changed` were edited: re-decides the nodes whose window meets it. Appends to
  // `added` and `removed` the seeds (sample indices) that came and went.
  void update(const HeightGrid& grid, const SampleWindow& changed, std::vector<std::size_t>& added,
              std::vector<std::size_t>& removed);
  // Sample indices, ascending.
  std::vector<std::size_t> sorted() const;
  bool contains(std::size_t sample) const { return corner_count_.count(sample) != 0; }
  std::size_t size() const { return corner_count_.size(); }
  std::size_t leaf_count() const;

 private:
  struct Node {
    int c0, r0, s;
  };
  static std::uint64_t key(const Node& n);
  void prefix_sums(const HeightGrid& grid, int from_row, int from_col);
  bool is_leaf(const HeightGrid& grid, const Node& n) const;
  SampleWindow window(const HeightGrid& grid, const Node& n) const;
  std::vector<Node> children(const HeightGrid& grid, const Node& n) const;
  // Decides n and its subtree afresh, adding its leaves.
  void grow(const HeightGrid& grid, const Node& n);
  // Takes back n's subtree (as the tree holds it).
  void drop(const HeightGrid& grid, const Node& n);
  // Re-decides the part of n's subtree whose windows meet `changed`.
  void refresh(const HeightGrid& grid, const Node& n, const SampleWindow& changed);
  void add_leaf(const HeightGrid& grid, const Node& n);
  void remove_leaf(const HeightGrid& grid, const Node& n);

  double tolerance_ = 0;
  int width_ = 0, height_ = 0;
  Node root_{0, 0, 1};
  // Every node of the tree: true for a leaf.
  std::unordered_map<std::uint64_t, bool> nodes_;
  // Per seed: how many leaves have it as a corner.
  std::unordered_map<std::size_t, std::uint32_t> corner_count_;
  std::vector<std::size_t>* added_ = nullptr;
  std::vector<std::size_t>* removed_ = nullptr;
  // Prefix sums over valid samples of 1, c, r, z, cc, cr, rr, cz, rz: (width + 1) x (height + 1) each.
  std::vector<double> sums_[9];
};

// The block picks of a terrain TIN (terrain.hpp step 2; docs/terrain.md "One setting for both targets"):
// the raster is cut into fixed blocks of `block` cells (block (i, j) covers the samples
// [i B, (i + 1) B] x [j B, (j + 1) B], clipped to the grid; neighbours share their edge samples). Every block edge is approximated on its own by
// Douglas-Peucker within `tolerance` (the profile of its samples, its ends the block corners); every block
// then runs Garland-Heckbert greedy insertion (the worst interior sample first, ties the smallest row-major
// index) on a Delaunay triangulation of its own corners, edge picks and picks, until every interior sample
// is within `tolerance`. An edge's picks read its samples only, a block's read its closed square only: an
// edit of a window re-decides the edges and blocks that meet it, and the picks equal a fresh build's.
class BlockPicks {
 public:
  BlockPicks() = default;
  // block <= 0: no picks.
  void build(const HeightGrid& grid, int block, double tolerance, double bound_from);
  // The samples in `changed` were edited: re-decides the edges and blocks that meet it, appending the picks
  // that came and went (sample indices; a sample that went from one list and came in another is neither).
  void update(const HeightGrid& grid, const SampleWindow& changed, std::vector<std::size_t>& added,
              std::vector<std::size_t>& removed);
  std::vector<std::size_t> sorted() const;  // ascending
  bool contains(std::size_t sample) const { return !count_.empty() && count_[sample] != 0; }
  std::size_t size() const { return size_; }
  std::size_t block_count() const { return blocks_.size(); }

 private:
  // A block's or an edge's picks, from the grid alone.
  std::vector<std::size_t> edge_picks(const HeightGrid& grid, int c0, int r0, int c1, int r1) const;
  std::vector<std::size_t> block_picks(const HeightGrid& grid, int bi, int bj) const;
  int line_col(int i) const;
  int line_row(int j) const;
  void take(const std::vector<std::size_t>& picks, int sign);

  int block_ = 0;
  double tolerance_ = 0, bound_from_ = 0;
  int width_ = 0, height_ = 0, nbx_ = 0, nby_ = 0;
  std::vector<std::vector<std::size_t>> blocks_;  // per block (j * nbx + i): its interior picks
  std::vector<std::vector<std::size_t>> hedges_;  // horizontal edge (segment i of row line j, j * nbx + i)
  std::vector<std::vector<std::size_t>> vedges_;  // vertical edge (segment j of column line i, i * nby + j)
  std::vector<std::uint8_t> count_;               // per sample: the lists holding it
  std::size_t size_ = 0;
  std::vector<std::size_t>* added_ = nullptr;
  std::vector<std::size_t>* removed_ = nullptr;
};

}  // namespace shoremesh::terrain
