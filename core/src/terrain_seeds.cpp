#include "terrain_seeds.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <iterator>

namespace shoremesh::terrain {

namespace {

struct Moments {
  double n = 0, c = 0, r = 0, z = 0, cc = 0, cr = 0, rr = 0, cz = 0, rz = 0;
};

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
  // A seed that went with one leaf and came with another is neither.
  std::vector<std::size_t> a(added.begin() + a0, added.end()), r(removed.begin() + r0, removed.end());
  std::sort(a.begin(), a.end());
  std::sort(r.begin(), r.end());
  added.resize(a0), removed.resize(r0);
  std::set_difference(a.begin(), a.end(), r.begin(), r.end(), std::back_inserter(added));
  std::set_difference(r.begin(), r.end(), a.begin(), a.end(), std::back_inserter(removed));
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

}  // namespace shoremesh::terrain
