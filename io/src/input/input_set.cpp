#include "shoremesh/io/input_set.hpp"

#include <algorithm>
#include <map>

#include "duplicates.hpp"
#include "shoremesh/error.hpp"
#include "shoremesh/domain.hpp"

namespace shoremesh::io {

const char* to_string(Units u) {
  switch (u) {
    case Units::Metres: return "metres";
    case Units::Pixels: return "pixels";
    case Units::MapUnits: return "map units";
  }
  return "map units";
}

std::string describe_origin(const InputSet& set, std::size_t i) {
  const PointOrigin& o = set.origins.at(i);
  const Source& s = set.sources.at(o.source);
  std::string out = s.file;
  switch (s.location) {
    // Appended piecewise: GCC 12 warns falsely (-Wrestrict) about `out += literal + std::to_string(...)`.
    case Source::Location::Line:
      out += ':';
      out += std::to_string(o.location);
      break;
    case Source::Location::Element:
      out += ", element ";
      out += std::to_string(o.location);
      break;
    case Source::Location::None: break;
  }
  if (o.ring != PointOrigin::kNoRing) {
    out += ", ring ";
    out += std::to_string(o.ring + 1);
  }
  return out;
}

void check_rings(const InputSet& set) {
  // Rings share a vertex where the reader made them share one point (a .poly's segments meeting there).
  std::vector<std::size_t> ids;
  for (const auto& ring : set.ring_ids) ids.insert(ids.end(), ring.begin(), ring.end());
  std::sort(ids.begin(), ids.end());
  const bool shared = std::adjacent_find(ids.begin(), ids.end()) != ids.end();
  const auto defect = find_ring_defect(set.domain, shared);
  if (!defect) return;
  std::string file;
  std::optional<std::size_t> location;
  if (defect->ring_a < set.ring_ids.size() && defect->vertex_a < set.ring_ids[defect->ring_a].size()) {
    const std::size_t p = set.ring_ids[defect->ring_a][defect->vertex_a];
    if (p < set.origins.size()) {
      const PointOrigin& o = set.origins[p];
      file = set.sources.at(o.source).file;
      if (set.sources[o.source].location != Source::Location::None) location = o.location;
    }
  }
  std::string msg = defect->describe();
  if (defect->kind == RingDefect::Kind::Intersection && defect->ring_b < set.ring_ids.size() &&
      defect->vertex_b < set.ring_ids[defect->ring_b].size()) {
    const std::size_t q = set.ring_ids[defect->ring_b][defect->vertex_b];
    if (q < set.origins.size()) msg += " (at " + describe_origin(set, q) + ")";
  }
  if (defect->kind == RingDefect::Kind::Intersection) msg = "self-intersecting rings: " + msg;
  throw InputError(msg, file, location);
}

InputSet merge(const std::vector<InputSet>& sets) {
  if (sets.empty()) throw InputError("no inputs to merge");
  InputSet out;
  out.dimension = sets.front().dimension;
  out.units = sets.front().units;
  out.projection = sets.front().projection;
  auto first_file = [](const InputSet& s) { return s.sources.empty() ? std::string() : s.sources.front().file; };
  for (const InputSet& s : sets) {
    if (s.dimension != out.dimension)
      throw InputError("cannot merge " + std::to_string(s.dimension) + "D points with " +
                           std::to_string(out.dimension) + "D points of " + first_file(sets.front()),
                       first_file(s));
    if (s.units != out.units)
      throw InputError(std::string("cannot merge inputs in ") + to_string(s.units) + " with inputs in " +
                           to_string(out.units) + " (" + first_file(sets.front()) + ")",
                       first_file(s));
    if (!(s.projection == out.projection))
      throw InputError("cannot merge inputs with different projections: " + s.projection.describe() + " here, " +
                           out.projection.describe() + " in " + first_file(sets.front()) +
                           " (give one projection for all inputs)",
                       first_file(s));
    const auto source_offset = static_cast<std::uint32_t>(out.sources.size());
    const auto ring_offset = static_cast<std::uint32_t>(out.domain.rings.size());
    const std::size_t point_offset = out.size();
    out.sources.insert(out.sources.end(), s.sources.begin(), s.sources.end());
    out.points.insert(out.points.end(), s.points.begin(), s.points.end());
    out.points3.insert(out.points3.end(), s.points3.begin(), s.points3.end());
    for (PointOrigin o : s.origins) {
      o.source += source_offset;
      if (o.ring != PointOrigin::kNoRing) o.ring += ring_offset;
      out.origins.push_back(o);
    }
    out.domain.rings.insert(out.domain.rings.end(), s.domain.rings.begin(), s.domain.rings.end());
    for (auto ids : s.ring_ids) {
      for (std::size_t& id : ids) id += point_offset;
      out.ring_ids.push_back(std::move(ids));
    }
    out.notes.insert(out.notes.end(), s.notes.begin(), s.notes.end());
    out.dropped_small_islands += s.dropped_small_islands;
    out.open_points.insert(out.open_points.end(), s.open_points.begin(), s.open_points.end());
  }
  std::sort(out.open_points.begin(), out.open_points.end());
  const auto dup = out.dimension == 3 ? detail::find_duplicate(out.points3) : detail::find_duplicate(out.points);
  if (dup) {
    const PointOrigin& o = out.origins.at(dup->first);
    const Source& src = out.sources.at(o.source);
    throw InputError("duplicate point: " + describe_origin(out, dup->first) + " repeats " +
                         describe_origin(out, dup->second),
                     src.file, src.location == Source::Location::None ? std::nullopt : std::optional(o.location));
  }
  return out;
}

}  // namespace shoremesh::io
