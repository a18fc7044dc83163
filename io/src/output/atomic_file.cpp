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
}

AtomicFile::AtomicFile(fs::path target, bool open_stream) : target_(std::move(target)) {
  const fs::path folder = target_.has_parent_path() ? target_.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) throw InputError("the folder does not exist", target_.string());
  if (fs::is_directory(target_, ec)) throw InputError("is a folder, not a file", target_.string());
  std::string name = ".";
  name += target_.filename().string();
  name += ".tmp-" + std::to_string(::getpid());
  name += "-" + std::to_string(counter++);
  name += target_.extension().string();
  temporary_ = folder / name;
  if (open_stream) {
    out_.open(temporary_, std::ios::binary | std::ios::trunc);
    if (!out_) throw std::runtime_error("cannot write " + target_.string() + ": " + std::strerror(errno));
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
  if (ec) throw std::runtime_error("cannot replace " + target_.string() + ": " + ec.message());
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

}  // namespace shoremesh::io
