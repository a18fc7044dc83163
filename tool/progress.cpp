#include "progress.hpp"

#include <unistd.h>

#include <cstdio>

namespace shoremesh::tool {

namespace {
constexpr auto kDelay = std::chrono::milliseconds(800);    // draw nothing for shorter work
constexpr auto kPeriod = std::chrono::milliseconds(200);  // redraw interval
constexpr int kBarWidth = 24;
}  // namespace

bool Progress::stderr_is_terminal() { return ::isatty(STDERR_FILENO) == 1; }

Progress::Progress(bool enabled, std::size_t stages)
    : enabled_(enabled), stages_(stages == 0 ? 1 : stages), job_start_(std::chrono::steady_clock::now()),
      stage_start_(job_start_) {
  if (enabled_) thread_ = std::thread([this] { run(); });
}

Progress::~Progress() { finish(); }

void Progress::stage(const std::string& label) {
  if (!enabled_) return;
  std::lock_guard lock(mutex_);
  if (!label_.empty() && current_ + 1 < stages_) ++current_;
  label_ = label;
  stage_start_ = std::chrono::steady_clock::now();
}

void Progress::finish() {
  if (!thread_.joinable()) return;
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
  if (drawn_) {
    std::fputs("\r\033[K", stderr);
    std::fflush(stderr);
  }
}

void Progress::run() {
  std::unique_lock lock(mutex_);
  while (!stop_) {
    wake_.wait_for(lock, kPeriod, [this] { return stop_; });
    if (stop_) break;
    if (std::chrono::steady_clock::now() - job_start_ >= kDelay) draw();
  }
}

// Called with the mutex held.
void Progress::draw() {
  using seconds = std::chrono::duration<double>;
  const double elapsed = seconds(std::chrono::steady_clock::now() - job_start_).count();
  const double in_stage = seconds(std::chrono::steady_clock::now() - stage_start_).count();
  // Within a stage the bar creeps toward the stage's end (never reaching it): work of unknown length.
  const double fraction = (static_cast<double>(current_) + in_stage / (in_stage + 2.0)) / static_cast<double>(stages_);
  const int filled = static_cast<int>(fraction * kBarWidth);
  std::string bar(static_cast<std::size_t>(kBarWidth), ' ');
  for (int i = 0; i < filled && i < kBarWidth; ++i) bar[static_cast<std::size_t>(i)] = '#';
  std::fprintf(stderr, "\r\033[K[%s] %zu/%zu %s  %.1f s", bar.c_str(), current_ + 1, stages_, label_.c_str(), elapsed);
  std::fflush(stderr);
  drawn_ = true;
}

}  // namespace shoremesh::tool
