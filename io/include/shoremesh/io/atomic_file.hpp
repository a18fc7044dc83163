#pragma once
// Atomic file output: everything is written to a temporary file in the target's folder and renamed over
// the target only when complete, so a reader never sees a half-written file and a failed write leaves an
// existing file untouched. (Atomic, not durable: there is no fsync, a power cut may lose the new file.)
#include <filesystem>
#include <fstream>
#include <functional>
#include <ostream>

namespace shoremesh::io {

class AtomicFile {
 public:
  // Creates the temporary file `.<name>.tmp-<pid>-<n><extension>` next to `target` (the extension is kept
  // so that libraries that choose a format by extension still do). With open_stream false the file is
  // not opened: the caller writes temporary_path() itself. Throws InputError when the folder is missing.
  explicit AtomicFile(std::filesystem::path target, bool open_stream = true);
  ~AtomicFile();  // removes the temporary file unless committed
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  std::ostream& stream() { return out_; }
  const std::filesystem::path& temporary_path() const { return temporary_; }
  const std::filesystem::path& target() const { return target_; }

  // Flushes and closes the stream, checks that every write succeeded, and renames the temporary file
  // over the target. Throws std::runtime_error naming the target on any failure.
  void commit();

 private:
  std::filesystem::path target_, temporary_;
  std::ofstream out_;
  bool committed_ = false;
};

// Writes `target` atomically with `write`; any exception from `write` leaves the target untouched and is
// rethrown as std::runtime_error naming the target (InputError passes through unchanged).
void write_atomically(const std::filesystem::path& target, const std::function<void(std::ostream&)>& write);

}  // namespace shoremesh::io
