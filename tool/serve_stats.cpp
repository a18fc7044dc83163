#include "serve_stats.hpp"

#include <stdexcept>

namespace shoremesh::tool {

StatsReplica::StatsReplica(std::function<std::unique_ptr<EditSession<2>>()> build, std::vector<std::string> resumed)
    : lines_(std::move(resumed)), resumed_(lines_.size()) {
  builder_ = std::thread([this, build = std::move(build)] {
    std::unique_ptr<EditSession<2>> s;
    std::exception_ptr error;
    try {
      s = build();
    } catch (...) {
      error = std::current_exception();
    }
    {
      std::lock_guard lock(run_mutex_);
      session_ = std::move(s);
      build_error_ = error;
      built_ = true;
    }
    built_cv_.notify_all();
  });
}

StatsReplica::~StatsReplica() {
  if (builder_.joinable()) builder_.join();
}

void StatsReplica::accepted(const std::string& line) {
  std::lock_guard lock(lines_mutex_);
  lines_.push_back(line);
}

nlohmann::json StatsReplica::stats(std::uint64_t& version) {
  std::unique_lock run(run_mutex_);
  built_cv_.wait(run, [&] { return built_; });
  if (build_error_) std::rethrow_exception(build_error_);
  std::vector<std::string> todo;
  {
    std::lock_guard lock(lines_mutex_);
    todo.assign(lines_.begin() + static_cast<std::ptrdiff_t>(applied_), lines_.end());
    version = lines_.size() - resumed_;
  }
  for (const std::string& line : todo) {
    const auto reply = session_->run(0, line);
    if (!reply || !reply->value("ok", false))
      throw std::logic_error("the summary's session refused an edit line the served session accepted: " + line);
    ++applied_;
  }
  nlohmann::json r = *session_->run(0, "stats");
  r["ring_count"] = session_->session().ring_count();
  return r;
}

}  // namespace shoremesh::tool
