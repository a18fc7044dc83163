// StableWS output is rho-well-spaced, contains the input and is size-conforming (independent verifier),
// on every input family, in 2D and 3D; it does not depend on input order; bad input is refused clearly.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <random>

#include "shoremesh/engine/engine.hpp"
#include "shoremesh/engine/spatial_order.hpp"
#include "shoremesh/error.hpp"
#include "shoremesh/families.hpp"
#include "shoremesh/verify.hpp"
#include "shoremesh/well_spaced.hpp"

namespace shoremesh {
namespace {

// Size conformity lfs(v)/NN(v): the proof gives c >= 2 rho / (rho - 1) ~ 6.8 for the insertion order of
// one fill; across ranks it compounds by a constant. The measured worst is reported by each test.
constexpr double kSizeConformityBound = 40.0;

template <int D>
WellSpacedReport<D> run_and_verify(const std::vector<Point<D>>& input, StableResult<D>* out = nullptr) {
  StableResult<D> result = stable_well_spaced<D>(input);
  const auto report = verify_well_spaced<D>(result.points, input, result.box, std::sqrt(2.0));
  EXPECT_TRUE(report.ok()) << "violations " << report.violations << " worst ratio " << report.worst_ratio
                           << " at vertex " << report.worst_vertex << ", missing input " << report.missing_input
                           << ", duplicates " << report.duplicate_points << ", outside " << report.outside_box;
  EXPECT_LE(report.worst_ratio, std::sqrt(2.0) * (1 + 1e-12));
  EXPECT_LE(report.worst_size_conformity, kSizeConformityBound);
  EXPECT_EQ(result.input_count, input.size());
  ::testing::Test::RecordProperty("output_vertices", int(result.points.size()));
  ::testing::Test::RecordProperty("worst_size_conformity_x1000", int(1000 * report.worst_size_conformity));
  if (out) *out = std::move(result);
  return report;
}

TEST(WellSpaced, Uniform2D) { run_and_verify<2>(families::uniform<2>(2000, 1)); }
TEST(WellSpaced, Uniform3D) { run_and_verify<3>(families::uniform<3>(300, 1)); }
TEST(WellSpaced, GaussianClusters2D) { run_and_verify<2>(families::gaussian_clusters<2>(1500, 6, 2)); }
TEST(WellSpaced, GaussianClusters3D) { run_and_verify<3>(families::gaussian_clusters<3>(200, 4, 2)); }
TEST(WellSpaced, OnCircle2D) { run_and_verify<2>(families::on_circle<2>(500)); }
TEST(WellSpaced, OnSphere3D) { run_and_verify<3>(families::on_circle<3>(200)); }
TEST(WellSpaced, GridInput2D) { run_and_verify<2>(families::grid<2>(25)); }
TEST(WellSpaced, GridInput3D) { run_and_verify<3>(families::grid<3>(6)); }
TEST(WellSpaced, ClosePairLargeSpread2D) { run_and_verify<2>(families::close_pair<2>(100, 1e-9)); }
TEST(WellSpaced, ClosePairLargeSpread3D) { run_and_verify<3>(families::close_pair<3>(30, 1e-9)); }
TEST(WellSpaced, ThousandPointsOnALine2D) { run_and_verify<2>(families::on_line<2>(1000)); }
TEST(WellSpaced, PointsOnALine3D) { run_and_verify<3>(families::on_line<3>(200)); }
TEST(WellSpaced, Kuzmin2D) { run_and_verify<2>(families::kuzmin<2>(1000, 3)); }

TEST(WellSpaced, SinglePointIsItsOwnOutput) {
  StableResult<2> r2;
  run_and_verify<2>({{0.25, 0.75}}, &r2);
  EXPECT_EQ(r2.points.size(), 1u);
  StableResult<3> r3;
  run_and_verify<3>({{0.25, 0.75, 0.5}}, &r3);
  EXPECT_EQ(r3.points.size(), 1u);
}

TEST(WellSpaced, TwoClosePointsInALargeBoxFillIt2D) {
  // In their own fitted box two points are already well-spaced (each half-box reaches 0.74 NN); in the
  // unit box, 0.1 apart, they are not, and Steiner points must fill the box around them.
  const std::vector<Point<2>> input{{0.45, 0.5}, {0.55, 0.5}};
  const BoxTransform<2> unit{{0, 0}, 1.0};
  const StableResult<2> r = stable_well_spaced<2>(input, {}, unit);
  EXPECT_GT(r.points.size(), 10u);
  EXPECT_TRUE(verify_well_spaced<2>(r.points, input, unit, std::sqrt(2.0)).ok());
}

// The same input rescaled by 1e-9 and 1e+9 and shifted: the engine works in the unit box, so the output
// is well-spaced and of about the same size at every scale (rounding the mapped coordinates differently
// moves Steiner choices a little, so the sizes agree to a few percent, not exactly).
template <int D>
void same_size_at_every_scale(const std::vector<Point<D>>& base) {
  StableResult<D> reference;
  run_and_verify<D>(base, &reference);
  for (double scale : {1e-9, 1e9}) {
    std::vector<Point<D>> scaled(base);
    for (auto& p : scaled)
      for (int i = 0; i < D; ++i) p[i] = p[i] * scale + 12345.678 * scale;
    StableResult<D> r;
    run_and_verify<D>(scaled, &r);
    EXPECT_NEAR(double(r.points.size()), double(reference.points.size()), 0.05 * double(reference.points.size()))
        << "scale " << scale;
  }
}
TEST(Robustness, RescaledAndShifted2D) { same_size_at_every_scale<2>(families::gaussian_clusters<2>(400, 3, 5)); }
TEST(Robustness, RescaledAndShifted3D) { same_size_at_every_scale<3>(families::uniform<3>(100, 5)); }

// Shuffling the input gives the same output points, bit for bit (Steiner points are listed sorted).
template <int D>
void output_does_not_depend_on_input_order(std::vector<Point<D>> input) {
  const StableResult<D> a = stable_well_spaced<D>(input);
  std::mt19937_64 rng(99);
  std::shuffle(input.begin(), input.end(), rng);
  const StableResult<D> b = stable_well_spaced<D>(input);
  ASSERT_EQ(a.points.size(), b.points.size());
  std::vector<Point<D>> sa(a.points), sb(b.points);
  std::sort(sa.begin(), sa.end());
  std::sort(sb.begin(), sb.end());
  EXPECT_TRUE(sa == sb);
  // And the work is the same operations.
  EXPECT_EQ(a.counters.dispatches, b.counters.dispatches);
  EXPECT_EQ(a.counters.fills, b.counters.fills);
}
TEST(InputOrder, ShuffledUniformSameOutput2D) { output_does_not_depend_on_input_order<2>(families::uniform<2>(1500, 8)); }
TEST(InputOrder, ShuffledGridSameOutput2D) { output_does_not_depend_on_input_order<2>(families::grid<2>(15)); }
TEST(InputOrder, ShuffledClustersSameOutput3D) {
  output_does_not_depend_on_input_order<3>(families::gaussian_clusters<3>(150, 3, 8));
}

// The engine numbers its vertices by place (spatial_order.hpp), not by input order: two orders of the
// same points give the same numbering, and every id still names the point it was given for.
TEST(InputOrder, IdsNameTheirPointsAndVerticesAreNumberedByPlace) {
  std::vector<Point<2>> input = families::uniform<2>(500, 3);
  std::vector<Point<2>> shuffled = input;
  std::mt19937_64 rng(5);
  std::shuffle(shuffled.begin(), shuffled.end(), rng);
  WellSpacedSet<2> a, b;
  a.build(input);
  b.build(shuffled);
  for (std::size_t id = 0; id < input.size(); ++id) {
    ASSERT_EQ(a.input_point(id), input[id]);
    ASSERT_EQ(b.input_point(id), shuffled[id]);
  }
  const auto pa = a.engine().positions(), pb = b.engine().positions();
  ASSERT_EQ(pa.size(), pb.size());
  EXPECT_TRUE(std::equal(pa.begin(), pa.end(), pb.begin()));
  a.remove(7);
  EXPECT_FALSE(a.has_input(7));
  EXPECT_EQ(a.input_point(8), input[8]);
}

TEST(InputErrors, DuplicateNamesBothPoints) {
  std::vector<Point<2>> pts{{0.1, 0.2}, {0.5, 0.5}, {0.3, 0.3}, {0.5, 0.5}};
  try {
    stable_well_spaced<2>(pts);
    FAIL() << "duplicate accepted";
  } catch (const PointInputError& e) {
    EXPECT_EQ(e.points(), (std::vector<std::size_t>{1, 3}));
    EXPECT_NE(std::string(e.what()).find("equal"), std::string::npos);
  }
}

TEST(InputErrors, NonFiniteNamesThePoint) {
  std::vector<Point<3>> pts{{0.1, 0.2, 0.3}, {0.5, std::nan(""), 0.5}};
  try {
    stable_well_spaced<3>(pts);
    FAIL() << "NaN accepted";
  } catch (const PointInputError& e) {
    EXPECT_EQ(e.points(), (std::vector<std::size_t>{1}));
  }
  pts[1][1] = INFINITY;
  EXPECT_THROW(stable_well_spaced<3>(pts), PointInputError);
}

TEST(InputErrors, PointOutsideGivenBox) {
  std::vector<Point<2>> pts{{0.1, 0.2}, {2.5, 0.5}};
  try {
    stable_well_spaced<2>(pts, {}, BoxTransform<2>{{0, 0}, 2.0});
    FAIL() << "point outside the box accepted";
  } catch (const PointInputError& e) {
    EXPECT_EQ(e.points(), (std::vector<std::size_t>{1}));
  }
  EXPECT_THROW(stable_well_spaced<2>(std::vector<Point<2>>{}), InputError);
}

TEST(Parameters, InvalidChoicesAreRefused) {
  EXPECT_THROW(WellSpacedSet<2>(Parameters<2>{1.0, 2.0, 0}), ParameterError);
  EXPECT_THROW(WellSpacedSet<2>(Parameters<2>{1.5, 1.4, 0}), ParameterError);
  EXPECT_THROW(WellSpacedSet<3>(Parameters<3>{std::sqrt(2.0), 1.7, 5}), ParameterError);  // kappa too small
  EXPECT_EQ(DerivedParameters<2>::derive({}).kappa, 16);
  EXPECT_EQ(DerivedParameters<3>::derive({}).kappa, 16);
  EXPECT_EQ(DerivedParameters<2>::derive({}).rho_squared, 2.0);
}

TEST(Parameters, OtherRhoIsStillWellSpaced) {
  const auto input = families::uniform<2>(500, 4);
  Parameters<2> p;
  p.rho = 1.8;
  p.beta = 2.5;
  const StableResult<2> r = stable_well_spaced<2>(input, p);
  const auto report = verify_well_spaced<2>(r.points, input, r.box, 1.8);
  EXPECT_TRUE(report.ok()) << report.violations;
  // A looser rho needs fewer Steiner points than the default.
  EXPECT_LT(r.points.size(), stable_well_spaced<2>(input).points.size());
}

// A dispatch leaves out the fills of neighbours already nearer another vertex than rho^rank, and that of
// its own vertex when it is well-spaced already; a fill whose vertex already has a neighbour that near
// stops without a cell. They would insert nothing (engine.cpp: dispatch, already_below_rank,
// record_idle_fill). The output is Figure 3's to the last bit, with far fewer operations, on five
// families in 2D and three in 3D, and for other rho (rounded rank tables).
template <int D>
void leaving_out_idle_fills_keeps_the_output(const std::vector<Point<D>>& input, double rho, double max_ops_share) {
  Parameters<D> literal;
  literal.rho = rho;
  literal.literal_stable_ws = true;
  Parameters<D> pruned = literal;
  pruned.literal_stable_ws = false;
  const BoxTransform<D> box = BoxTransform<D>::fit(input);
  StableResult<D> a = stable_well_spaced<D>(input, literal, box);
  StableResult<D> b = stable_well_spaced<D>(input, pruned, box);
  std::sort(a.points.begin(), a.points.end());
  std::sort(b.points.begin(), b.points.end());
  EXPECT_EQ(a.points, b.points) << a.points.size() << " vs " << b.points.size() << " points";
  EXPECT_LE(double(b.counters.operations()), max_ops_share * double(a.counters.operations()))
      << b.counters.operations() << " vs " << a.counters.operations() << " operations";
  EXPECT_EQ(a.counters.fills_idle_by_rank, 0u);
  if (max_ops_share < 1) {
    EXPECT_GT(b.counters.fills_idle_by_rank, 0u);
  }
}

TEST(IdleFills, LeftOutWithTheSameOutput2D) {
  leaving_out_idle_fills_keeps_the_output<2>(families::uniform<2>(1500, 41), std::sqrt(2.0), 0.75);
  leaving_out_idle_fills_keeps_the_output<2>(families::gaussian_clusters<2>(1500, 5, 42), std::sqrt(2.0), 0.75);
  leaving_out_idle_fills_keeps_the_output<2>(families::close_pair<2>(300, 1e-9), std::sqrt(2.0), 0.85);
  leaving_out_idle_fills_keeps_the_output<2>(families::kuzmin<2>(1000, 43), 1.2, 0.75);
  leaving_out_idle_fills_keeps_the_output<2>(families::uniform<2>(1000, 44), 1.8, 0.85);
  // On a grid input nothing is inserted and every neighbour is at the same distance: little to leave out.
  leaving_out_idle_fills_keeps_the_output<2>(families::grid<2>(20), std::sqrt(2.0), 1.0);
}

TEST(IdleFills, LeftOutWithTheSameOutput3D) {
  leaving_out_idle_fills_keeps_the_output<3>(families::uniform<3>(300, 45), std::sqrt(2.0), 0.7);
  leaving_out_idle_fills_keeps_the_output<3>(families::on_line<3>(150), std::sqrt(2.0), 0.7);
  leaving_out_idle_fills_keeps_the_output<3>(families::gaussian_clusters<3>(200, 3, 46), 1.5, 0.7);
}

TEST(ComputationGraph, RecordedAndValid) {
  WellSpacedSet<2> set;
  set.build(families::gaussian_clusters<2>(800, 4, 6));
  ASSERT_NO_THROW(set.check_valid());
  const auto& e = set.engine();
  // Every Steiner vertex was inserted by a fill, whose children include its dispatch.
  for (engine::VertexId v = 0; v < e.vertex_count(); ++v) {
    if (!e.vertex(v).alive || e.vertex(v).is_input) continue;
    const auto creator = e.vertex(v).creator;
    const auto kids = e.children(creator);
    EXPECT_NE(std::find(kids.begin(), kids.end(), e.vertex(v).dispatch), kids.end());
  }
  // Every operation read at least one square.
  for (engine::OpId o = 0; o < e.op_count(); ++o) EXPECT_GT(e.reads(o).size(), 0u);
}

// After the build, vertices (inputs and Steiner together) follow the space-filling curve and each
// vertex's operations come after those of the vertex before it, in time order: an update then reads
// neighbouring memory (engine.cpp, renumber_vertices_by_place). The renumbered computation stays valid.
template <int D>
void expect_numbered_by_place(const std::vector<Point<D>>& input) {
  WellSpacedSet<D> set;
  set.build(input);
  ASSERT_NO_THROW(set.check_valid());
  const auto& e = set.engine();
  std::size_t steiner_between_inputs = 0;
  bool input_seen = false;
  const engine::VertexId live = engine::VertexId(e.live_vertex_count());
  for (engine::VertexId v = 0; v < live; ++v) {  // free slots, if any, come last
    ASSERT_TRUE(e.vertex(v).alive) << "a free slot before live vertex " << v;
    if (v > 0) {
      ASSERT_LE(engine::z_order_key<D>(e.positions()[v - 1]), engine::z_order_key<D>(e.positions()[v])) << v;
    }
    if (e.vertex(v).is_input) input_seen = true;
    else if (input_seen) ++steiner_between_inputs;
  }
  EXPECT_GT(steiner_between_inputs, 0u);  // Steiner vertices are not all numbered after the inputs
  using Engine = WellSpacedEngine<D>;
  auto time_of = [&](engine::OpId o) { return std::pair(e.op(o).rank, e.op(o).color); };
  for (engine::OpId o = 1; o < e.live_op_count(); ++o) {  // deleted slots, if any, come last
    const auto& a = e.op(o - 1);
    const auto& b = e.op(o);
    ASSERT_LE(a.vertex, b.vertex) << "operation " << o;
    if (a.vertex == b.vertex) {
      ASSERT_LT(time_of(o - 1), time_of(o)) << "operation " << o;
    }
  }
  EXPECT_EQ(e.op(e.vertex(0).dispatch).kind, Engine::OpKind::Dispatch);
  // The references followed the renumbering: each vertex's dispatch is a dispatch of that vertex.
  for (engine::VertexId v = 0; v < live; ++v) {
    const engine::OpId d = e.vertex(v).dispatch;
    if (d == engine::kNoOp) continue;
    ASSERT_EQ(e.op(d).vertex, v) << "vertex " << v;
    ASSERT_EQ(e.op(d).kind, Engine::OpKind::Dispatch) << "vertex " << v;
  }
}

TEST(ComputationGraph, NumberedByPlaceAfterTheBuild2D) { expect_numbered_by_place<2>(families::gaussian_clusters<2>(600, 4, 3)); }
TEST(ComputationGraph, NumberedByPlaceAfterTheBuild3D) { expect_numbered_by_place<3>(families::uniform<3>(300, 4)); }

// Work is linear: operations per output vertex and output vertices per input vertex stay bounded as n
// grows 100-fold (a test of counts, not of time).
TEST(LinearWork, OperationsPerOutputVertexBounded2D) {
  const bool sanitizer = std::getenv("SHOREMESH_SANITIZER_BUILD") != nullptr;
  std::vector<double> ops_per_vertex, out_per_in;
  for (std::size_t n : {std::size_t(1000), std::size_t(10000), std::size_t(sanitizer ? 20000 : 100000)}) {
    const auto input = families::uniform<2>(n, 11);
    const StableResult<2> r = stable_well_spaced<2>(input, {}, BoxTransform<2>{{0, 0}, 1.0});
    ops_per_vertex.push_back(double(r.counters.operations()) / double(r.points.size()));
    out_per_in.push_back(double(r.points.size()) / double(n));
    EXPECT_LT(double(r.counters.clipped_voronoi_calls) / double(r.points.size()), 8.0);
    EXPECT_LT(double(r.counters.leaves_visited) / double(r.counters.clipped_voronoi_calls), 200.0);
  }
  for (std::size_t k = 0; k < ops_per_vertex.size(); ++k) {
    EXPECT_LT(ops_per_vertex[k], 8.0);
    EXPECT_LT(out_per_in[k], 6.0);
    // No drift with n: within 10% of the smallest run.
    EXPECT_NEAR(ops_per_vertex[k], ops_per_vertex[0], 0.1 * ops_per_vertex[0]);
    EXPECT_NEAR(out_per_in[k], out_per_in[0], 0.1 * out_per_in[0]);
  }
}

TEST(LinearWork, OperationsPerOutputVertexBounded3D) {
  std::vector<double> ops_per_vertex, out_per_in;
  for (std::size_t n : {std::size_t(200), std::size_t(2000)}) {
    const auto input = families::uniform<3>(n, 11);
    const StableResult<3> r = stable_well_spaced<3>(input, {}, BoxTransform<3>{{0, 0, 0}, 1.0});
    ops_per_vertex.push_back(double(r.counters.operations()) / double(r.points.size()));
    out_per_in.push_back(double(r.points.size()) / double(n));
  }
  EXPECT_LT(ops_per_vertex[1], 8.0);
  EXPECT_NEAR(ops_per_vertex[1], ops_per_vertex[0], 0.15 * ops_per_vertex[0]);
  EXPECT_NEAR(out_per_in[1], out_per_in[0], 0.25 * out_per_in[0]);
}

}  // namespace
}  // namespace shoremesh
