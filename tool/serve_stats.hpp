#pragma once
// GET /stats off the edit lock: the summary measures the whole mesh (every triangle's quality, the refined
// rings' segments against the mesh's edges: seconds at a million triangles on a loaded machine), so it is
// computed on a second session on the same inputs that replays the accepted edit lines when a summary is
// asked for. By Lemma 7.2 that session equals the served one after the same lines (ids are never reused,
// so the same lines give the same ids, as --resume relies on), and so does its summary; an edit meanwhile
// only appends its line (docs/editor.md, "The summary").
#include <nlohmann/json.hpp>

#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "edit_session.hpp"

namespace shoremesh::tool {

class StatsReplica {
 public:
  // `build`: the second session, built on a thread of its own (a summary asked for before it is ready
  // waits for it, without holding any edit up). `resumed`: the lines --resume replayed before version 0.
  StatsReplica(std::function<std::unique_ptr<EditSession<2>>()> build, std::vector<std::string> resumed);
  ~StatsReplica();  // waits for the build
  StatsReplica(const StatsReplica&) = delete;
  StatsReplica& operator=(const StatsReplica&) = delete;

  // An accepted edit line of the served session (the edit's version is the number of these so far).
  void accepted(const std::string& line);

  // The `stats` reply of the served session as of the last accepted line when asked, and that version.
  // One summary at a time; edits go on meanwhile.
  nlohmann::json stats(std::uint64_t& version);

 private:
  std::mutex lines_mutex_;  // held for an append or a copy, never for session work
  std::vector<std::string> lines_;
  std::size_t resumed_ = 0;

  std::mutex run_mutex_;  // the replica's session: one summary at a time
  std::condition_variable built_cv_;
  bool built_ = false;
  std::exception_ptr build_error_;
  std::unique_ptr<EditSession<2>> session_;
  std::size_t applied_ = 0;  // lines_ replayed into session_
  std::thread builder_;
};

}  // namespace shoremesh::tool
