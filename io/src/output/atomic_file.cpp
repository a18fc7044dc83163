#include "shoremesh/io/atomic_file.hpp"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>

#include "shoremesh/error.hpp"

namespace shoremesh::io {

namespace fs = std::filesystem;

namespace {
std::atomic<unsigned> counter{0};

fs::path temporary_next_to(const fs::path& target) {
  const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
  // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string&& at -O2 and up.
  std::string name = ".";
  name.append(target.filename().string()).append(".tmp-").append(std::to_string(::getpid()));
  name.append("-").append(std::to_string(counter++)).append(target.extension().string());
  return folder / name;
}
}  // namespace

AtomicFile::AtomicFile(fs::path target, bool open_stream) : target_(std::move(target)) {
  const fs::path folder = target_.has_parent_path() ? target_.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) throw InputError("the folder does not exist", target_.string());
  if (fs::is_directory(target_, ec)) throw InputError("is a folder, not a file", target_.string());
  temporary_ = temporary_next_to(target_);
  if (open_stream) {
    out_.open(temporary_, std::ios::binary | std::ios::trunc);
    if (!out_) throw InputError(std::string("cannot write here: ") + std::strerror(errno), target_.string());
  }
}

AtomicFile::~AtomicFile() {
  if (committed_) return;
  if (out_.is_open()) out_.close();
  std::error_code ec;
  fs::remove(temporary_, ec);
}

void AtomicFile::commit() {
  if (out_.is_open()) {
    out_.flush();
    const bool good = out_.good();
    out_.close();
    if (!good || out_.fail()) throw std::runtime_error("writing " + target_.string() + " failed (disk full?)");
  }
  std::error_code ec;
  if (!fs::is_regular_file(temporary_, ec)) throw std::runtime_error("writing " + target_.string() + " produced no file");
  fs::rename(temporary_, target_, ec);
  if (ec) throw InputError(std::string("cannot replace the file: ").append(ec.message()), target_.string());
  committed_ = true;
}

void write_atomically(const fs::path& target, const std::function<void(std::ostream&)>& write) {
  AtomicFile file(target);
  try {
    write(file.stream());
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw std::runtime_error("writing " + target.string() + ": " + e.what());
  }
  file.commit();
}

OutputBatch::OutputBatch(std::vector<fs::path> inputs) : inputs_(std::move(inputs)) {}

OutputBatch::~OutputBatch() {
  if (committed_) return;
  std::error_code ec;
  for (const Entry& e : entries_) fs::remove(e.staging, ec);
}

void OutputBatch::check(const fs::path& target, const std::string& option) const {
  const std::string name = option.empty() ? target.string() : option + " " + target.string();
  if (target.empty()) throw InputError("an empty output path", option);
  const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) throw InputError(std::string("the folder ").append(folder.string()) + " does not exist", name);
  if (fs::is_directory(target, ec)) throw InputError("is a folder, not a file", name);
  if (::access(folder.c_str(), W_OK) != 0)
    throw InputError(std::string("cannot write in ").append(folder.string()).append(": ") + std::strerror(errno), name);
  if (fs::exists(target, ec) && ::access(target.c_str(), W_OK) != 0)
    throw InputError(std::string("cannot replace it: ") + std::strerror(errno), name);
  for (const fs::path& in : inputs_) {
    std::error_code e1;
    if (fs::exists(target, e1) && fs::exists(in, e1) && fs::equivalent(target, in, e1))
      throw InputError("is also an input: an output may not replace an input file", name);
  }
  for (const Entry& e : entries_) {
    std::error_code e1;
    if (fs::weakly_canonical(e.target, e1) == fs::weakly_canonical(target, e1))
      throw InputError("is named twice as an output", name);
  }
}

fs::path OutputBatch::add(const fs::path& target, const std::string& option) {
  check(target, option);
  // Created now, empty: whether the folder takes a new file is known before any work (root passes
  // access(), but not every file system lets it write: /proc, a read-only mount, a full disk).
  const fs::path staging = temporary_next_to(target);
  {
    std::ofstream probe(staging, std::ios::binary | std::ios::trunc);
    if (!probe) {
      const std::string name = option.empty() ? target.string() : option + " " + target.string();
      throw InputError(std::string("cannot write here: ") + std::strerror(errno), name);
    }
  }
  entries_.push_back({target, staging});
  return staging;
}

void OutputBatch::add_written_as(const fs::path& target, const fs::path& staging, const std::string& option) {
  check(target, option);
  entries_.push_back({target, staging});
}

void OutputBatch::commit() {
  std::error_code ec;
  for (const Entry& e : entries_)
    if (!fs::is_regular_file(e.staging, ec)) throw InputError("writing it produced no file", e.target.string());
  for (const Entry& e : entries_) {
    fs::rename(e.staging, e.target, ec);
    if (ec) throw InputError(std::string("cannot replace the file: ").append(ec.message()), e.target.string());
  }
  committed_ = true;
}

}  // namespace shoremesh::io
