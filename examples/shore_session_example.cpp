// The library's edit session in a few lines: a lake with an island, a shore point dragged in small steps
// (as the browser editor drags one), an island added and removed, each edit's change and time printed;
// at the end the session's mesh is compared with a fresh session on the edited input (Lemma 7.2: the
// same triangles). Exit code 0 when they are the same and the shore is the mesh's boundary throughout.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "shoremesh/error.hpp"
#include "shoremesh/shore_session.hpp"

using namespace shoremesh;

namespace {

std::vector<Point2> polygon(Point2 centre, double radius, int corners, double wobble) {
  std::vector<Point2> out;
  for (int i = 0; i < corners; ++i) {
    const double t = 2 * std::numbers::pi * i / corners, r = radius * (1 + wobble * std::sin(5 * t));
    out.push_back({centre[0] + r * std::cos(t), centre[1] + r * std::sin(t)});
  }
  return out;
}

// The mesh's triangles as sorted corner triples: what a fresh run must reproduce.
std::vector<ElementCorners<2>> triangles(const Mesh<2>& mesh) {
  const auto elements = mesh.elements();
  return sorted_corners<2>(mesh.points(), elements);
}

void print(const char* what, const SessionEdit<2>& e, const ShoreSession<2>& s) {
  const ShorelineStatus shore = s.shoreline();
  std::printf("%-28s %4zu triangles changed, %7.3f ms; shoreline %zu/%zu segments are mesh edges\n", what,
              e.mesh.removed.size() + e.mesh.added.size(), e.ms, shore.covered, shore.segments);
}

}  // namespace

int main() {
  // The input: a wavy lake of 48 shore points (ring 1) and a 12-point island (ring 2), in metres.
  SessionInput<2> input;
  const std::vector<std::vector<Point2>> rings{polygon({0, 0}, 1000, 48, 0.1), polygon({250, 100}, 150, 12, 0)};
  for (std::size_t r = 0; r < rings.size(); ++r) {
    input.ring_ids.emplace_back();
    for (std::size_t k = 0; k < rings[r].size(); ++k) input.ring_ids.back().push_back(input.points.size() + k);
    input.points.insert(input.points.end(), rings[r].begin(), rings[r].end());
    input.rings.rings.push_back({rings[r], r == 0 ? RingRole::Shore : RingRole::Island});
  }
  ShoreSession<2>::Options options;  // rho = sqrt 2: every angle >= 20.7 degrees away from the shore
  options.box = BoxTransform<2>{{-1500, -1500}, 3000};
  ShoreSession<2> session(input, options);
  std::printf("built: %zu input points, %zu shore splits, %zu Steiner points, %zu triangles\n",
              session.input_count(), session.split_count(), session.steiner_count(), session.mesh().element_count());

  bool conforming = true;
  // Drag shore point 10 out into the land in ten steps.
  const Point2 from = session.input_point(10);
  for (int step = 1; step <= 10; ++step) {
    const SessionEdit<2> e = session.move(10, {from[0] * (1 + 0.02 * step), from[1] * (1 + 0.02 * step)});
    print(("drag point 10, step " + std::to_string(step)).c_str(), e, session);
    conforming = conforming && session.shoreline().conforming();
  }
  // A new island, then the old one removed; then a refused edit (a ring across the shore).
  const SessionEdit<2> added = session.add_ring(polygon({-400, -300}, 80, 6, 0));
  print(("add ring " + std::to_string(*added.ring + 1)).c_str(), added, session);
  print("remove ring 2", session.remove_ring(1), session);
  try {
    session.add_ring(polygon({900, 0}, 200, 6, 0));
  } catch (const InputError& e) {
    std::printf("refused: %s\n", e.what());
  }
  conforming = conforming && session.shoreline().conforming();

  // Lemma 7.2: the same mesh as a fresh session on the edited input and the same box.
  const ShoreSession<2> fresh(session.current_input(), options);
  const bool same = triangles(session.mesh()) == triangles(fresh.mesh());
  std::printf("after the edits: %zu triangles; a fresh run on the edited input: %zu triangles, %s\n",
              session.mesh().element_count(), fresh.mesh().element_count(), same ? "identical" : "DIFFERENT");
  return same && conforming ? 0 : 1;
}
