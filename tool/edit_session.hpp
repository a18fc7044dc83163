#pragma once
// The state of `shoremesh edit`: the dynamic well-spaced set, its mesh (which holds the water domain) and
// the ids, kept up to date one edit line at a time. Every line gets one reply (a JSON object, printed as
// JSON or as text); a bad line gets an error reply and leaves the state as it was.
#include <nlohmann/json.hpp>

#include <chrono>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "pipeline.hpp"
#include "shoremesh/io/input_set.hpp"
#include "shoremesh/io/ring_edge_index.hpp"
#include "shoremesh/mesh.hpp"
#include "shoremesh/shore_refinement.hpp"
#include "shoremesh/well_spaced.hpp"
#include "user_frame.hpp"

namespace shoremesh::tool {

// Exact coordinates as a key.
struct SplitHash {
  std::size_t operator()(const Point2& p) const {
    return std::hash<double>{}(p[0] + 0.0) * 0x9E3779B97F4A7C15ull ^ std::hash<double>{}(p[1] + 0.0);
  }
};

template <int D>
class EditSession {
 public:
  // Builds the set and the mesh of `set`'s points (ids 0..n-1 in reading order). `keep_hull`: the mesh
  // keeps the elements along the box's edge (make_mesh).
  // `lonlat_edits`: edit lines give lon lat (degrees), projected like the input (2D lon/lat input only:
  // the caller checks).
  EditSession(const io::InputSet& set, double rho, std::optional<BoxTransform<D>> box, bool keep_hull,
              PreviewArgs preview, bool lonlat_edits = false);

  // The reply to the initial build (op "build", line 0): counts, the box, and `ms`, the time it took.
  nlohmann::json build_reply(double ms) const;

  // Runs one edit line (1-based `line` for the reply). Blank and '#' lines give no reply (nullopt).
  std::optional<nlohmann::json> run(std::size_t line, const std::string& text);

  // The files the session read (its inputs, the edit lines' file): export and preview replace none of them.
  void set_inputs(std::vector<std::filesystem::path> inputs) { inputs_ = std::move(inputs); }

 private:
  nlohmann::json add(const std::vector<std::string>& words);
  nlohmann::json remove(const std::vector<std::string>& words);
  nlohmann::json move(const std::vector<std::string>& words);
  nlohmann::json export_to(const std::vector<std::string>& words);
  nlohmann::json preview(const std::vector<std::string>& words);
  nlohmann::json preview_change(const std::vector<std::string>& words);
  nlohmann::json stats() const;

  Point<D> parse_point(const std::vector<std::string>& words, std::size_t first) const;
  std::size_t parse_id(const std::string& word) const;
  // A shore point's edit: the rings after it, and the edit as the ring index takes it.
  struct RingChange {
    Domain2 domain;
    io::RingVertexEdit edit;
  };
  // The rings after a shore edit at input `id`: moved to `p` (Move), removed (Remove; `p` unused), or a new
  // vertex at `p` after it (Insert). InputError when they would be invalid; nullopt when `id` is on no ring.
  std::optional<RingChange> rings_with(io::RingVertexEdit::Kind kind, std::size_t id, const Point<D>& p) const;
  // The ids of the ring the change edits, after the engine took it: `id` removed, or inserted as the new
  // vertex (moves keep them).
  void commit_ring_ids(const RingChange& change, std::size_t id);
  // After an engine update that started at `engine_start`: the mesh takes the engine's Steiner changes
  // plus the edited input points (and the new rings when a shore point moved, went or came); the reply gets the
  // counts and the times (`ms`: the whole edit from `edit_start`, the shoreline check included).
  void update_mesh(const UpdateReport<D>& report, std::vector<Point<D>> inputs_removed,
                   std::vector<Point<D>> inputs_added, std::optional<RingChange> rings,
                   std::chrono::steady_clock::time_point edit_start,
                   std::chrono::steady_clock::time_point engine_start, nlohmann::json& reply);
  void check_id(std::size_t id) const;
  std::size_t engine_id(std::size_t id) const { return engine_of_user_.at(id); }
  // Applies the user's edits of the engine's input (engine ids) together with what they do to the shore's
  // canonical splits, in one propagation: `rings` are the user's rings after the edit (null: unchanged),
  // `loose_removed`/`loose_added` the loose points the edit takes and gives. The input points that went
  // and came (splits included) are added to `inputs_removed`/`inputs_added`; returns the engine ids of the
  // edits' added points, in order. On an error nothing changed.
  std::vector<std::size_t> apply_edits(std::vector<Edit<D>> edits, const Domain2* rings,
                                       std::vector<Point<D>> loose_removed, std::vector<Point<D>> loose_added,
                                       std::vector<Point<D>>& inputs_removed, std::vector<Point<D>>& inputs_added,
                                       UpdateReport<D>& report);
  // The point set as a fresh run on the current input lists it: the user's input points by id, the
  // shore's splits (sorted), then the Steiner points.
  std::vector<Point<D>> canonical_points() const;
  std::size_t user_input_count() const { return set_.input_count() - split_id_.size(); }
  nlohmann::json point_json(const Point<D>& p) const;

  UserFrame frame_;
  bool lonlat_edits_ = false;
  double rho_;
  bool keep_hull_ = false;
  PreviewArgs preview_;
  std::optional<ShoreRefinement> refinement_;  // 2D with rings: the user's rings and their canonical splits
  DynamicWellSpaced<D> set_;
  std::unordered_map<Point2, std::size_t, SplitHash> split_id_;  // a split point's engine id
  std::vector<std::size_t> engine_of_user_;  // by user id: the engine's input id (kRemoved once removed)
  static constexpr std::size_t kRemoved = static_cast<std::size_t>(-1);
  std::optional<io::RingEdgeIndex> ring_index_;  // the edges of the user's rings (refinement_->rings())
  std::vector<std::vector<std::size_t>> ring_ids_;                          // ring r's vertices as input ids
  std::unordered_map<std::size_t, std::pair<std::size_t, std::size_t>> ring_of_;  // id -> (ring, position)
  Mesh<D> mesh_;
  MeshDelta<D> last_delta_;
  std::size_t next_id_ = 0;
  std::vector<std::filesystem::path> inputs_;
};

// One reply as a line of text for a person.
std::string reply_text(const nlohmann::json& reply);

}  // namespace shoremesh::tool
