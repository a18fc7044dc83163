#pragma once
// `shoremesh edit`: the edit language over a library ShoreSession (the dynamic well-spaced set, the shore's
// splits, the water mesh and the ids), one edit line at a time. Every line gets one reply (a JSON object,
// printed as JSON or as text); a bad line gets an error reply and leaves the session as it was.
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
#include "shoremesh/mesh.hpp"
#include "shoremesh/shore_session.hpp"
#include "user_frame.hpp"

namespace shoremesh::tool {

template <int D>
class EditSession {
 public:
  // Builds the session (ShoreSession) on `set`'s points (ids 0..n-1 in reading order) and rings.
  // `keep_hull`: without rings, the mesh keeps the elements along the box's edge.
  // `lonlat_edits`: edit lines give lon lat (degrees), projected like the input (2D lon/lat input only:
  // the caller checks).
  // `size`: element size control (2D; docs/sizing.md), which adds the `size POLYGON H` line.
  EditSession(const io::InputSet& set, double rho, std::optional<BoxTransform<D>> box, bool keep_hull,
              PreviewArgs preview, bool lonlat_edits = false, std::optional<SizeTerms> size = std::nullopt);

  // The reply to the initial build (op "build", line 0): counts, the box, and `ms`, the time it took.
  nlohmann::json build_reply(double ms) const;

  // Runs one edit line (1-based `line` for the reply). Blank and '#' lines give no reply (nullopt).
  std::optional<nlohmann::json> run(std::size_t line, const std::string& text);

  // The library session, and the last accepted edit (its mesh delta and engine report): what `serve`
  // sends a page so that it redraws only the change.
  const ShoreSession<D>& session() const { return session_; }
  const SessionEdit<D>& last_edit() const { return last_edit_; }
  // The user's units, projection and depth source (what exports add to the mesh).
  const UserFrame& frame() const { return frame_; }
  // The files the session read (its inputs, the edit lines' file): export and preview replace none of them.
  void set_inputs(std::vector<std::filesystem::path> inputs) { inputs_ = std::move(inputs); }

 private:
  nlohmann::json add(const std::vector<std::string>& words);
  nlohmann::json remove(const std::vector<std::string>& words);
  nlohmann::json move(const std::vector<std::string>& words);
  nlohmann::json add_ring(const std::vector<std::string>& words, const std::string& rest);
  nlohmann::json remove_ring(const std::vector<std::string>& words);
  nlohmann::json set_size(const std::vector<std::string>& words);
  nlohmann::json export_to(const std::vector<std::string>& words);
  nlohmann::json preview(const std::vector<std::string>& words);
  nlohmann::json preview_change(const std::vector<std::string>& words);
  nlohmann::json stats() const;

  Point<D> parse_point(const std::vector<std::string>& words, std::size_t first) const;
  Point<D> user_point(Point<D> p) const;  // projected when the edits give lon/lat
  std::size_t parse_id(const std::string& word) const;
  // The reply's counts and times of an edit, and the mesh's delta kept for preview-change.
  void record(const SessionEdit<D>& edit, nlohmann::json& reply);
  nlohmann::json point_json(const Point<D>& p) const;

  UserFrame frame_;
  bool lonlat_edits_ = false;
  PreviewArgs preview_;
  ShoreSession<D> session_;
  MeshDelta<D> last_delta_;
  SessionEdit<D> last_edit_;
  std::vector<std::filesystem::path> inputs_;
};

// An edit line's words, and the text after its first word (trimmed: a path may contain blanks).
std::vector<std::string> split_words(const std::string& text);
std::string rest_after_op(const std::string& text);

// One reply as a line of text for a person.
std::string reply_text(const nlohmann::json& reply);

}  // namespace shoremesh::tool
