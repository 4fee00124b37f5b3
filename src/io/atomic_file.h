// Files written all or nothing. The content goes to a temporary file in the target's folder,
// named short (".caustica-PID-N.EXT", so any legal target name works) with the target's
// extension (OpenImageIO picks the format by it); it is flushed to the disk (fsync) and only
// then renamed over the target. A failure at any step (a full disk, a vanished folder) removes
// the temporary and throws InputError naming the target, which is then as it was.
#pragma once
#include <memory>
#include <string>
#include <vector>

namespace caustica {

// Fails (InputError) unless `path` can be written: its folder exists and is writable, it is not
// a folder itself, and its name fits NAME_MAX. Called before long work, so that a render is not
// lost to a name that cannot be written.
void check_output_file(const std::string& path);

class AtomicFile {
 public:
  explicit AtomicFile(std::string target);
  ~AtomicFile();  // removes the temporary unless committed
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  const std::string& target() const { return target_; }
  // Where to write: the temporary's path (for writers that open files themselves).
  const std::string& path() const { return temp_; }
  // Writes `bytes` to the temporary (replacing what was there); throws on a short write.
  void write(const void* bytes, size_t size, const std::string& what);
  void write(const std::string& text, const std::string& what) { write(text.data(), text.size(), what); }
  // fsync, then rename over the target; throws (what: "image", "report", ...).
  void commit(const std::string& what);
  // The first half of commit: the temporary flushed to the disk, ready to be renamed.
  void sync(const std::string& what);
  // The second half: the rename (after sync).
  void rename(const std::string& what);
  // Gives up: the temporary is removed, the target left as it was.
  void abandon();

 private:
  [[noreturn]] void fail(const std::string& what, const std::string& reason);
  std::string target_, temp_;
  bool done_ = false;
};

// Writes `text` to `target` all or nothing (`what` names it in errors: "report", "CSV").
void write_file_atomically(const std::string& target, const std::string& text, const std::string& what);

// A set of files that appear together or not at all (a render's image and its AOVs): each is
// written to its temporary and flushed first, and every target checked; only then does any get
// its name, the first member last.
class AtomicFileSet {
 public:
  AtomicFile& add(const std::string& target);
  void commit(const std::string& what);

 private:
  std::vector<std::unique_ptr<AtomicFile>> files_;
};

}  // namespace caustica
