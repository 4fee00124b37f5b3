// Files written all or nothing: temporary, fsync, rename.
#include "io/atomic_file.h"
#include <cerrno>
#include <csignal>
#include <climits>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <mutex>
#include <sys/stat.h>
#include <stdlib.h>
#include <unistd.h>
#include "core/error.h"

namespace caustica {
namespace fs = std::filesystem;

namespace {
// Flushes the file at `path` (or a folder) to the disk; false with errno set on failure.
bool fsync_path(const std::string& path, bool directory) {
  const int fd = ::open(path.c_str(), directory ? O_RDONLY | O_DIRECTORY : O_WRONLY);
  if (fd < 0) return false;
  const bool ok = ::fsync(fd) == 0;
  const int saved = errno;
  ::close(fd);
  errno = saved;
  return ok;
}

std::string folder_of(const std::string& target) {
  const fs::path dir = fs::path(target).parent_path();
  return dir.empty() ? std::string(".") : dir.string();
}
}  // namespace

namespace {
void check_name_length(const std::string& path) {
  if (fs::path(path).filename().string().size() > NAME_MAX) {
    throw InputError(path + ": the file name is longer than " + std::to_string(NAME_MAX) + " bytes");
  }
}
}  // namespace

void check_output_file(const std::string& path) {
  check_name_length(path);
  const std::string dir = folder_of(path);
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw InputError(path + ": output folder " + dir + " does not exist");
  if (access(dir.c_str(), W_OK) != 0) throw InputError(path + ": output folder " + dir + " is not writable");
  if (fs::is_directory(path, ec)) throw InputError(path + ": is a directory");
}

AtomicFile::AtomicFile(std::string target) : target_(std::move(target)) {
  // Refused before anything is written, so that a set of files fails as a whole.
  check_name_length(target_);
  // Created here, exclusively (mkstemps), so that no other process, even on another machine
  // sharing the folder, can pick the same name; the writers then replace its empty content.
  const std::string ext = fs::path(target_).extension().string().substr(0, 16);
  std::string name = (fs::path(folder_of(target_)) / (".caustica-XXXXXX" + ext)).string();
  const int fd = ::mkstemps(name.data(), int(ext.size()));
  if (fd < 0) {
    done_ = true;
    throw InputError(target_ + ": cannot create a file in " + folder_of(target_) + ": " + std::strerror(errno));
  }
  // mkstemps makes it private (0600); the target gets what any new file would (0666 less umask).
  static std::mutex umask_mutex;
  mode_t mask;
  {
    std::lock_guard<std::mutex> lock(umask_mutex);
    mask = ::umask(0);
    ::umask(mask);
  }
  ::fchmod(fd, 0666 & ~mask);
  ::close(fd);
  temp_ = name;
  // For tests: a signal that arrives while the file is being written, at a known moment
  // (CAUSTICA_TEST_SIGNAL_WHILE_WRITING=15 raises SIGTERM here).
  if (const char* sig = std::getenv("CAUSTICA_TEST_SIGNAL_WHILE_WRITING")) std::raise(std::atoi(sig));
}

AtomicFile::~AtomicFile() {
  if (done_) return;
  std::error_code ec;
  fs::remove(temp_, ec);
}

void AtomicFile::fail(const std::string& what, const std::string& reason) {
  std::error_code ec;
  fs::remove(temp_, ec);
  done_ = true;
  throw InputError(target_ + ": cannot write the " + what + ": " + reason);
}

void AtomicFile::abandon() {
  if (done_) return;
  std::error_code ec;
  fs::remove(temp_, ec);
  done_ = true;
}

void AtomicFile::write(const void* bytes, size_t size, const std::string& what) {
  std::FILE* f = std::fopen(temp_.c_str(), "wb");
  if (!f) fail(what, std::strerror(errno));
  const bool wrote = std::fwrite(bytes, 1, size, f) == size;
  const int write_errno = errno;
  const bool closed = std::fclose(f) == 0;
  if (!wrote) fail(what, std::strerror(write_errno));
  if (!closed) fail(what, std::strerror(errno));
}

void AtomicFile::sync(const std::string& what) {
  if (!fsync_path(temp_, false)) fail(what, std::strerror(errno));
}

void AtomicFile::rename(const std::string& what) {
  std::error_code ec;
  fs::rename(temp_, target_, ec);
  // The message is taken before the temporary's removal can overwrite the error.
  if (ec) fail(what, "cannot rename it into place: " + ec.message());
  done_ = true;
  fsync_path(folder_of(target_), true);  // the new name on the disk too; best effort
}

void AtomicFile::commit(const std::string& what) {
  sync(what);
  rename(what);
}

void write_file_atomically(const std::string& target, const std::string& text, const std::string& what) {
  AtomicFile file(target);
  file.write(text, what);
  file.commit(what);
}

AtomicFile& AtomicFileSet::add(const std::string& target) {
  files_.push_back(std::make_unique<AtomicFile>(target));
  return *files_.back();
}

void AtomicFileSet::commit(const std::string& what) {
  for (auto& f : files_) f->sync(what);
  // What would stop a rename is refused before the first: a folder under a member's name.
  for (auto& f : files_) {
    std::error_code ec;
    if (fs::is_directory(f->target(), ec)) {
      for (auto& g : files_) g->abandon();
      throw InputError(f->target() + ": cannot write the " + what + ": is a directory");
    }
  }
  // The first member (a render's image) last: if a rename still fails, the image stays as it was.
  for (auto it = files_.rbegin(); it != files_.rend(); ++it) (*it)->rename(what);
}

}  // namespace caustica
