#pragma once
// --timings: the wall time of each phase of a run, one line on stderr at its end, for modellers who want
// to know where a run's time goes (the reading, the shore's splits, the engine, the mesh, the outputs).
// Phases that run at the same time are each timed from their own start.
#include <chrono>
#include <cstdio>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

namespace shoremesh::tool {

class Timings {
 public:
  using Clock = std::chrono::steady_clock;

  explicit Timings(bool enabled) : enabled_(enabled), start_(Clock::now()) {}

  // Times `work()` as the phase `name` and returns what it returns. Safe from several threads at once.
  template <class F>
  decltype(auto) time(const char* name, F&& work) {
    struct Record {
      Timings& t;
      const char* name;
      Clock::time_point begun = Clock::now();
      ~Record() { t.add(name, Clock::now() - begun); }
    } record{*this, name};
    return std::forward<F>(work)();
  }

  // "timings (wall): read 0.41 s, shore 0.52 s, ..., total 9.10 s\n"; empty when not enabled.
  std::string line() const {
    if (!enabled_) return {};
    std::lock_guard lock(mutex_);
    std::string out = "timings (wall):";
    char buf[64];
    for (const auto& [name, seconds] : phases_) {
      std::snprintf(buf, sizeof buf, " %s %.2f s,", name, seconds);
      out += buf;
    }
    std::snprintf(buf, sizeof buf, " total %.2f s\n", std::chrono::duration<double>(Clock::now() - start_).count());
    return out + buf;
  }

 private:
  void add(const char* name, Clock::duration d) {
    if (!enabled_) return;
    std::lock_guard lock(mutex_);
    phases_.emplace_back(name, std::chrono::duration<double>(d).count());
  }

  bool enabled_;
  Clock::time_point start_;
  mutable std::mutex mutex_;
  std::vector<std::pair<const char*, double>> phases_;
};

}  // namespace shoremesh::tool
