#pragma once
// Named families of generated inputs for tests, benchmarks and `shoremesh bench`. Every generator is
// deterministic: the same arguments give the same points, bit for bit, on every standard library (the
// random transforms are our own, over std::mt19937_64). All points lie in [0,1]^D and are pairwise distinct.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "shoremesh/point.hpp"

namespace shoremesh::families {

// n points uniformly in [0,1)^D.
template <int D>
std::vector<Point<D>> uniform(std::size_t n, std::uint64_t seed);

// n points in `clusters` Gaussian blobs (centres uniform in [0.15,0.85]^D, standard deviations between
// 0.005 and 0.05); samples outside [0,1]^D are drawn again.
template <int D>
std::vector<Point<D>> gaussian_clusters(std::size_t n, std::size_t clusters, std::uint64_t seed);

// n points on the circle (2D) or sphere (3D) of radius 0.4 around the box centre: equal angles in 2D,
// the Fibonacci lattice in 3D. Many co-circular points.
template <int D>
std::vector<Point<D>> on_circle(std::size_t n);

// per_axis^D points at the cell centres (i + 1/2) / per_axis: a regular grid, maximally co-circular.
template <int D>
std::vector<Point<D>> grid(std::size_t per_axis);

// Two points `gap` apart (along x, at the centre of one cell of a coarse grid) among n_sparse points that
// are otherwise at least 1 / (2k) apart (one jittered point per cell of a k^D grid). n_sparse + 2 points.
template <int D>
std::vector<Point<D>> close_pair(std::size_t n_sparse, double gap = 1e-9, std::uint64_t seed = 1);

// n points on the box diagonal, (t, t[, t]) with t = (i + 1/2) / n: exactly collinear.
template <int D>
std::vector<Point<D>> on_line(std::size_t n);

// n points with the heavy-tailed radial density of Kuzmin's disk, surface density ∝ (1 + r^2)^(-3/2),
// around the box centre (in 3D the same radial law with uniform directions), scaled so that radius 1000
// reaches the box face (farther samples are drawn again).
template <int D>
std::vector<Point<D>> kuzmin(std::size_t n, std::uint64_t seed);

enum class FamilyName { Uniform, GaussianClusters, OnCircle, Grid, ClosePair, OnLine, Kuzmin };

// "uniform", "clusters", "circle", "grid", "close-pair", "line", "kuzmin"; InputError listing the names
// for anything else.
FamilyName parse_family(std::string_view name);
std::string_view family_name(FamilyName family);
std::string family_names();  // the accepted names, comma-separated, for help texts

// About n points of a family with the family's defaults: 10 clusters; a grid of round(n^(1/D)) per axis;
// a close pair among n - 2 sparse points. Seeds are ignored by the deterministic families.
template <int D>
std::vector<Point<D>> generate(FamilyName family, std::size_t n, std::uint64_t seed);

}  // namespace shoremesh::families
