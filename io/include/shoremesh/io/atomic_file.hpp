#pragma once
// Atomic file output: everything is written to a temporary file in the target's folder and renamed over
// the target only when complete, so a reader never sees a half-written file and a failed write leaves an
// existing file untouched. (Atomic, not durable: there is no fsync, a power cut may lose the new file.)
#include <filesystem>
#include <fstream>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

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

// All the outputs of one run, written or none: each target is checked before any work (its folder exists
// and is writable, it is not a folder, it is not one of the inputs, through any path), written to a
// temporary file next to it, and the temporaries are renamed over the targets together at the end. A run
// that fails before commit() leaves every existing file as it was (the destructor removes the temporaries).
class OutputBatch {
 public:
  // `inputs`: the files the run reads; a target that is one of them is refused.
  explicit OutputBatch(std::vector<std::filesystem::path> inputs);
  ~OutputBatch();
  OutputBatch(const OutputBatch&) = delete;
  OutputBatch& operator=(const OutputBatch&) = delete;

  // Checks `target` (InputError naming it and the reason) and returns the temporary path to write it to
  // (same folder, extension kept). `option` names the option it came from, for the message ("-o").
  std::filesystem::path add(const std::filesystem::path& target, const std::string& option = {});
  // A target written alongside another one's temporary (Triangle's .ele next to its .node): `staging`
  // is the path the writer will use.
  void add_written_as(const std::filesystem::path& target, const std::filesystem::path& staging,
                      const std::string& option = {});
  // Renames every temporary over its target. InputError naming the target (with the system's reason)
  // when a temporary is missing or a rename fails.
  void commit();

 private:
  void check(const std::filesystem::path& target, const std::string& option) const;
  struct Entry {
    std::filesystem::path target, staging;
  };
  std::vector<std::filesystem::path> inputs_;
  std::vector<Entry> entries_;
  bool committed_ = false;
};

}  // namespace shoremesh::io
