#pragma once
// A progress line on stderr for work that takes longer than about a second: the stage, a bar over the
// stages, and the elapsed time. Drawn only when stderr is a terminal and not silenced (--quiet); nothing
// is drawn for work that finishes within the delay, and the line is erased when the work ends.
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <mutex>
#include <string>
#include <thread>

namespace shoremesh::tool {

class Progress {
 public:
  // `stages`: how many stages the whole job has (the bar advances one step per stage).
  Progress(bool enabled, std::size_t stages);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  // Starts the next stage ("tracing superior.png"); the previous one is done.
  void stage(const std::string& label);
  // Ends the job: erases the line (also done by the destructor).
  void finish();

  // True when stderr is a terminal: the default for `enabled` unless --quiet.
  static bool stderr_is_terminal();

 private:
  void run();
  void draw();

  bool enabled_;
  std::size_t stages_;
  std::size_t current_ = 0;
  std::string label_;
  std::chrono::steady_clock::time_point job_start_, stage_start_;
  bool drawn_ = false;
  bool stop_ = false;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::thread thread_;
};

}  // namespace shoremesh::tool
