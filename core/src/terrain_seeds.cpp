#include "terrain_seeds.hpp"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>

#include <algorithm>
#include <queue>
#include <bit>
#include <cmath>
#include <iterator>

namespace shoremesh::terrain {

namespace {

struct Moments {
  double n = 0, c = 0, r = 0, z = 0, cc = 0, cr = 0, rr = 0, cz = 0, rz = 0;
};

// An update appended samples to added and removed from positions a0 and r0 on; one that went with one
// leaf or block and came with another is neither: keep the two sorted differences.
void cancel_moves(std::vector<std::size_t>& added, std::vector<std::size_t>& removed, std::size_t a0, std::size_t r0) {
  std::vector<std::size_t> a(added.begin() + a0, added.end()), r(removed.begin() + r0, removed.end());
  std::sort(a.begin(), a.end());
  std::sort(r.begin(), r.end());
  added.resize(a0), removed.resize(r0);
  std::set_difference(a.begin(), a.end(), r.begin(), r.end(), std::back_inserter(added));
  std::set_difference(r.begin(), r.end(), a.begin(), a.end(), std::back_inserter(removed));
}

}  // namespace

std::uint64_t Seeds::key(const Node& n) {
  // s is a power of two below 2^31: its exponent in 5 bits, the corner in 29 bits each.
  const auto level = static_cast<std::uint64_t>(std::countr_zero(static_cast<unsigned>(n.s)));
  return (level << 58) | (static_cast<std::uint64_t>(n.c0) << 29) | static_cast<std::uint64_t>(n.r0);
}

void Seeds::prefix_sums(const HeightGrid& grid, int from_row, int from_col) {
  const std::size_t stride = static_cast<std::size_t>(grid.width) + 1;
  for (auto& s : sums_) s.resize(stride * (static_cast<std::size_t>(grid.height) + 1), 0.0);
  // Entry (c + 1, r + 1) sums the samples [0, c] x [0, r]; an entry depends only on those above and to its
  // left, so recomputing from (from_col, from_row) on gives the values of a fresh computation.
  for (int r = from_row; r < grid.height; ++r)
    for (int c = from_col; c < grid.width; ++c) {
      const std::size_t i = grid.index(c, r);
      double v[9] = {};
      if (grid.is_valid(i)) {
        const double z = grid.z[i];
        v[0] = 1, v[1] = c, v[2] = r, v[3] = z, v[4] = double(c) * c, v[5] = double(c) * r, v[6] = double(r) * r,
        v[7] = c * z, v[8] = r * z;
      }
      const std::size_t e = (static_cast<std::size_t>(r) + 1) * stride + c + 1;
      for (int k = 0; k < 9; ++k) sums_[k][e] = v[k] + sums_[k][e - stride] + sums_[k][e - 1] - sums_[k][e - stride - 1];
    }
}

SampleWindow Seeds::window(const HeightGrid& grid, const Node& n) const {
  const int m = n.s / 2;
  return {std::max(n.c0 - m, 0), std::max(n.r0 - m, 0), std::min(n.c0 + n.s + m, grid.width - 1),
          std::min(n.r0 + n.s + m, grid.height - 1)};
}

bool Seeds::is_leaf(const HeightGrid& grid, const Node& n) const {
  if (n.s <= 1) return true;
  const SampleWindow w = window(grid, n);
  const std::size_t stride = static_cast<std::size_t>(grid.width) + 1;
  auto box_sum = [&](int k) {
    const auto& s = sums_[k];
    const std::size_t a = static_cast<std::size_t>(w.r0) * stride + w.c0, b = static_cast<std::size_t>(w.r0) * stride + w.c1 + 1,
                      c = (static_cast<std::size_t>(w.r1) + 1) * stride + w.c0,
                      d = (static_cast<std::size_t>(w.r1) + 1) * stride + w.c1 + 1;
    return s[d] - s[b] - s[c] + s[a];
  };
  Moments m{box_sum(0), box_sum(1), box_sum(2), box_sum(3), box_sum(4), box_sum(5), box_sum(6), box_sum(7), box_sum(8)};
  if (m.n < 0.5) return true;  // no valid sample to fit
  // The plane z = zm + b (c - cm) + d (r - rm) by least squares (centred moments); a constant where the
  // valid samples lie on a line.
  const double cm = m.c / m.n, rm = m.r / m.n, zm = m.z / m.n;
  const double vcc = m.cc - m.c * cm, vcr = m.cr - m.c * rm, vrr = m.rr - m.r * rm;
  const double vcz = m.cz - m.c * zm, vrz = m.rz - m.r * zm;
  const double det = vcc * vrr - vcr * vcr;
  double b = 0, d = 0;
  if (det > 1e-9 * vcc * vrr && det > 0) {
    b = (vcz * vrr - vrz * vcr) / det;
    d = (vrz * vcc - vcz * vcr) / det;
  }
  for (int r = w.r0; r <= w.r1; ++r)
    for (int c = w.c0; c <= w.c1; ++c) {
      const std::size_t i = grid.index(c, r);
      if (!grid.is_valid(i)) continue;
      if (std::abs(grid.z[i] - (zm + b * (c - cm) + d * (r - rm))) > tolerance_) return false;
    }
  return true;
}

std::vector<Seeds::Node> Seeds::children(const HeightGrid& grid, const Node& n) const {
  std::vector<Node> out;
  const int h = n.s / 2;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      const Node child{n.c0 + i * h, n.r0 + j * h, h};
      // A child meets the samples' rectangle in more than a line.
      if (child.c0 < grid.width - 1 && child.r0 < grid.height - 1) out.push_back(child);
    }
  return out;
}

void Seeds::add_leaf(const HeightGrid& grid, const Node& n) {
  nodes_[key(n)] = true;
  const int c1 = std::min(n.c0 + n.s, grid.width - 1), r1 = std::min(n.r0 + n.s, grid.height - 1);
  const std::size_t corners[4] = {grid.index(n.c0, n.r0), grid.index(c1, n.r0), grid.index(n.c0, r1), grid.index(c1, r1)};
  for (std::size_t k : corners)
    if (corner_count_[k]++ == 0 && added_) added_->push_back(k);
}

void Seeds::remove_leaf(const HeightGrid& grid, const Node& n) {
  nodes_.erase(key(n));
  const int c1 = std::min(n.c0 + n.s, grid.width - 1), r1 = std::min(n.r0 + n.s, grid.height - 1);
  const std::size_t corners[4] = {grid.index(n.c0, n.r0), grid.index(c1, n.r0), grid.index(n.c0, r1), grid.index(c1, r1)};
  for (std::size_t k : corners) {
    auto it = corner_count_.find(k);
    if (--it->second == 0) {
      corner_count_.erase(it);
      if (removed_) removed_->push_back(k);
    }
  }
}

void Seeds::grow(const HeightGrid& grid, const Node& n) {
  if (is_leaf(grid, n)) return add_leaf(grid, n);
  nodes_[key(n)] = false;
  for (const Node& child : children(grid, n)) grow(grid, child);
}

void Seeds::drop(const HeightGrid& grid, const Node& n) {
  const auto it = nodes_.find(key(n));
  if (it->second) return remove_leaf(grid, n);
  nodes_.erase(it);
  for (const Node& child : children(grid, n)) drop(grid, child);
}

void Seeds::refresh(const HeightGrid& grid, const Node& n, const SampleWindow& changed) {
  const SampleWindow w = window(grid, n);
  if (w.c1 < changed.c0 || changed.c1 < w.c0 || w.r1 < changed.r0 || changed.r1 < w.r0) return;  // subtree unchanged
  const bool was_leaf = nodes_.at(key(n));
  const bool leaf = is_leaf(grid, n);
  if (was_leaf && leaf) return;
  if (leaf) {
    drop(grid, n);
    add_leaf(grid, n);
  } else if (was_leaf) {
    remove_leaf(grid, n);
    grow(grid, n);
  } else {
    for (const Node& child : children(grid, n)) refresh(grid, child, changed);
  }
}

void Seeds::build(const HeightGrid& grid, double tolerance) {
  tolerance_ = tolerance;
  width_ = grid.width, height_ = grid.height;
  nodes_.clear();
  corner_count_.clear();
  added_ = removed_ = nullptr;
  int s = 1;
  while (s < std::max(grid.width, grid.height) - 1) s *= 2;
  root_ = {0, 0, s};
  if (tolerance_ <= 0) {
    // The root as the only leaf: its corners, clamped, are the grid's corners.
    add_leaf(grid, root_);
    return;
  }
  prefix_sums(grid, 0, 0);
  grow(grid, root_);
}

void Seeds::update(const HeightGrid& grid, const SampleWindow& changed, std::vector<std::size_t>& added,
                   std::vector<std::size_t>& removed) {
  if (tolerance_ <= 0) return;
  prefix_sums(grid, changed.r0, changed.c0);
  added_ = &added, removed_ = &removed;
  const std::size_t a0 = added.size(), r0 = removed.size();
  refresh(grid, root_, changed);
  added_ = removed_ = nullptr;
  cancel_moves(added, removed, a0, r0);
}

std::vector<std::size_t> Seeds::sorted() const {
  std::vector<std::size_t> out;
  out.reserve(corner_count_.size());
  for (const auto& [k, count] : corner_count_) out.push_back(k);
  std::sort(out.begin(), out.end());
  return out;
}

std::size_t Seeds::leaf_count() const {
  std::size_t n = 0;
  for (const auto& [k, leaf] : nodes_) n += leaf;
  return n;
}

// ---- Block picks ------------------------------------------------------------------------------------

int BlockPicks::line_col(int i) const { return std::min(i * block_, width_ - 1); }
int BlockPicks::line_row(int j) const { return std::min(j * block_, height_ - 1); }

std::vector<std::size_t> BlockPicks::edge_picks(const HeightGrid& grid, int c0, int r0, int c1, int r1) const {
  // Samples along the edge, t = 0 .. n; Douglas-Peucker: the worst sample between two kept ones (ties: the
  // first along the edge, which is the smaller row-major index) is kept while its error exceeds the bound.
  // The kept set is a function of the profile: each split depends only on the span it splits.
  const int n = std::max(c1 - c0, r1 - r0);
  auto sample = [&](int t) { return c0 == c1 ? grid.index(c0, r0 + t) : grid.index(c0 + t, r0); };
  std::vector<std::size_t> out{sample(0), sample(n)};
  std::vector<std::pair<int, int>> spans{{0, n}};
  while (!spans.empty()) {
    const auto [a, b] = spans.back();
    spans.pop_back();
    const double za = grid.z[sample(a)], zb = grid.z[sample(b)];
    double worst = tolerance_;
    int at = -1;
    for (int t = a + 1; t < b; ++t) {
      const std::size_t s = sample(t);
      if (!grid.is_valid(s) || !(grid.z[s] >= bound_from_)) continue;
      const double e = std::abs(grid.z[s] - (za + (zb - za) * double(t - a) / double(b - a)));
      if (e > worst) worst = e, at = t;
    }
    if (at < 0) continue;
    out.push_back(sample(at));
    spans.push_back({a, at});
    spans.push_back({at, b});
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

namespace {

struct StampInfo {
  std::uint64_t stamp = 0;
};
using BlockKernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using BlockTds = CGAL::Triangulation_data_structure_2<CGAL::Triangulation_vertex_base_2<BlockKernel>,
                                                      CGAL::Triangulation_face_base_with_info_2<StampInfo, BlockKernel>>;
using BlockDt = CGAL::Delaunay_triangulation_2<BlockKernel, BlockTds>;

}  // namespace

std::vector<std::size_t> BlockPicks::block_picks(const HeightGrid& grid, int bi, int bj) const {
  const int c0 = line_col(bi), c1 = line_col(bi + 1), r0 = line_row(bj), r1 = line_row(bj + 1);
  // Lattice coordinates scaled by the cell's sides: the block's Delaunay triangulation is the plane's. The
  // interpolation reads barycentric coordinates in the lattice (integers: exact), the same in any affine frame.
  const double sx = std::abs(grid.dx), sy = std::abs(grid.dy);
  BlockDt dt;
  std::vector<std::uint8_t> used(static_cast<std::size_t>(c1 - c0 + 1) * static_cast<std::size_t>(r1 - r0 + 1), 0);
  auto local = [&](int c, int r) { return static_cast<std::size_t>(r - r0) * static_cast<std::size_t>(c1 - c0 + 1) + (c - c0); };
  struct Entry {
    double error;
    std::size_t sample;
    BlockDt::Face_handle face;
    std::uint64_t stamp;
    bool operator<(const Entry& o) const { return error != o.error ? error < o.error : sample > o.sample; }
  };
  std::priority_queue<Entry> queue;
  std::uint64_t stamps = 0;
  auto lattice = [&](const BlockKernel::Point_2& p) {
    return std::array<int, 2>{static_cast<int>(std::lround(p.x() / sx)), static_cast<int>(std::lround(p.y() / sy))};
  };
  auto scan = [&](BlockDt::Face_handle f) {
    f->info().stamp = ++stamps;
    const auto a = lattice(f->vertex(0)->point()), b = lattice(f->vertex(1)->point()), c = lattice(f->vertex(2)->point());
    const double ha = grid.at(a[0], a[1]), hb = grid.at(b[0], b[1]), hc = grid.at(c[0], c[1]);
    const long long d = static_cast<long long>(b[0] - a[0]) * (c[1] - a[1]) - static_cast<long long>(b[1] - a[1]) * (c[0] - a[0]);
    if (d == 0) return;
    const int lc = std::max(c0 + 1, std::min({a[0], b[0], c[0]})), hc_ = std::min(c1 - 1, std::max({a[0], b[0], c[0]}));
    const int lr = std::max(r0 + 1, std::min({a[1], b[1], c[1]})), hr = std::min(r1 - 1, std::max({a[1], b[1], c[1]}));
    Entry best{tolerance_, 0, f, f->info().stamp};
    bool any = false;
    for (int r = lr; r <= hr; ++r)
      for (int cc = lc; cc <= hc_; ++cc) {
        const std::size_t s = grid.index(cc, r);
        if (used[local(cc, r)] || !grid.is_valid(s) || !(grid.z[s] >= bound_from_)) continue;
        const long long l0 = static_cast<long long>(b[0] - cc) * (c[1] - r) - static_cast<long long>(b[1] - r) * (c[0] - cc);
        const long long l1 = static_cast<long long>(c[0] - cc) * (a[1] - r) - static_cast<long long>(c[1] - r) * (a[0] - cc);
        const long long l2 = d - l0 - l1;
        if (d > 0 ? (l0 < 0 || l1 < 0 || l2 < 0) : (l0 > 0 || l1 > 0 || l2 > 0)) continue;
        const double e = std::abs(grid.z[s] - (double(l0) * ha + double(l1) * hb + double(l2) * hc) / double(d));
        // A sample on an edge shared by two faces is seen by both with the same error (ties: the smaller index).
        if (e > best.error || (any && e == best.error && s < best.sample)) best.error = e, best.sample = s, any = true;
      }
    if (any) queue.push(best);
  };
  // The corners and the four edges' picks, in ascending order: the start is a function of the edges.
  std::vector<std::size_t> start;
  for (const auto& e : {hedges_[static_cast<std::size_t>(bj) * nbx_ + bi], hedges_[static_cast<std::size_t>(bj + 1) * nbx_ + bi],
                        vedges_[static_cast<std::size_t>(bi) * nby_ + bj], vedges_[static_cast<std::size_t>(bi + 1) * nby_ + bj]})
    start.insert(start.end(), e.begin(), e.end());
  std::sort(start.begin(), start.end());
  start.erase(std::unique(start.begin(), start.end()), start.end());
  for (std::size_t s : start) {
    const int c = static_cast<int>(s % width_), r = static_cast<int>(s / width_);
    used[local(c, r)] = 1;
    dt.insert(BlockKernel::Point_2(c * sx, r * sy));
  }
  std::vector<std::size_t> out;
  if (dt.dimension() < 2) return out;  // a block one cell thin: its samples are all on edges
  for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f) scan(f);
  while (!queue.empty()) {
    const Entry e = queue.top();
    queue.pop();
    const int c = static_cast<int>(e.sample % width_), r = static_cast<int>(e.sample / width_);
    if (e.face->info().stamp != e.stamp || used[local(c, r)]) continue;
    used[local(c, r)] = 1;
    out.push_back(e.sample);
    const BlockDt::Vertex_handle v = dt.insert(BlockKernel::Point_2(c * sx, r * sy), e.face);
    BlockDt::Face_circulator f = dt.incident_faces(v), end = f;
    do {
      if (!dt.is_infinite(f)) scan(f);
    } while (++f != end);
  }
  std::sort(out.begin(), out.end());
  return out;
}

void BlockPicks::take(const std::vector<std::size_t>& picks, int sign) {
  for (std::size_t s : picks) {
    if (sign > 0) {
      if (count_[s]++ == 0) {
        ++size_;
        if (added_) added_->push_back(s);
      }
    } else if (--count_[s] == 0) {
      --size_;
      if (removed_) removed_->push_back(s);
    }
  }
}

void BlockPicks::build(const HeightGrid& grid, int block, double tolerance, double bound_from) {
  block_ = block, tolerance_ = tolerance, bound_from_ = bound_from;
  width_ = grid.width, height_ = grid.height;
  blocks_.clear(), hedges_.clear(), vedges_.clear(), count_.clear();
  size_ = 0;
  added_ = removed_ = nullptr;
  if (block_ <= 0) return;
  nbx_ = (width_ - 2) / block_ + 1, nby_ = (height_ - 2) / block_ + 1;
  count_.assign(grid.z.size(), 0);
  hedges_.resize(static_cast<std::size_t>(nby_ + 1) * nbx_);
  vedges_.resize(static_cast<std::size_t>(nbx_ + 1) * nby_);
  blocks_.resize(static_cast<std::size_t>(nbx_) * nby_);
  for (int j = 0; j <= nby_; ++j)
    for (int i = 0; i < nbx_; ++i) {
      auto& e = hedges_[static_cast<std::size_t>(j) * nbx_ + i];
      e = edge_picks(grid, line_col(i), line_row(j), line_col(i + 1), line_row(j));
      take(e, 1);
    }
  for (int i = 0; i <= nbx_; ++i)
    for (int j = 0; j < nby_; ++j) {
      auto& e = vedges_[static_cast<std::size_t>(i) * nby_ + j];
      e = edge_picks(grid, line_col(i), line_row(j), line_col(i), line_row(j + 1));
      take(e, 1);
    }
  for (int j = 0; j < nby_; ++j)
    for (int i = 0; i < nbx_; ++i) {
      auto& b = blocks_[static_cast<std::size_t>(j) * nbx_ + i];
      b = block_picks(grid, i, j);
      take(b, 1);
    }
}

void BlockPicks::update(const HeightGrid& grid, const SampleWindow& changed, std::vector<std::size_t>& added,
                        std::vector<std::size_t>& removed) {
  if (block_ <= 0) return;
  const std::size_t a0 = added.size(), r0 = removed.size();
  added_ = &added, removed_ = &removed;
  auto meets = [&](int c0, int r0_, int c1, int r1) {
    return !(c1 < changed.c0 || changed.c1 < c0 || r1 < changed.r0 || changed.r1 < r0_);
  };
  auto redo = [&](std::vector<std::size_t>& list, std::vector<std::size_t> fresh) {
    take(fresh, 1);  // first, so that a sample in both lists never drops to zero on the way
    take(list, -1);
    list = std::move(fresh);
  };
  // Edges first: a block's picks start from its edges' picks.
  for (int j = 0; j <= nby_; ++j)
    for (int i = 0; i < nbx_; ++i)
      if (meets(line_col(i), line_row(j), line_col(i + 1), line_row(j)))
        redo(hedges_[static_cast<std::size_t>(j) * nbx_ + i], edge_picks(grid, line_col(i), line_row(j), line_col(i + 1), line_row(j)));
  for (int i = 0; i <= nbx_; ++i)
    for (int j = 0; j < nby_; ++j)
      if (meets(line_col(i), line_row(j), line_col(i), line_row(j + 1)))
        redo(vedges_[static_cast<std::size_t>(i) * nby_ + j], edge_picks(grid, line_col(i), line_row(j), line_col(i), line_row(j + 1)));
  for (int j = 0; j < nby_; ++j)
    for (int i = 0; i < nbx_; ++i)
      if (meets(line_col(i), line_row(j), line_col(i + 1), line_row(j + 1)))
        redo(blocks_[static_cast<std::size_t>(j) * nbx_ + i], block_picks(grid, i, j));
  added_ = removed_ = nullptr;
  cancel_moves(added, removed, a0, r0);
}

std::vector<std::size_t> BlockPicks::sorted() const {
  std::vector<std::size_t> out;
  out.reserve(size_);
  for (std::size_t s = 0; s < count_.size(); ++s)
    if (count_[s]) out.push_back(s);
  return out;
}

}  // namespace shoremesh::terrain
