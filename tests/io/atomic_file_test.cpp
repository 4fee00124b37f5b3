// Files written all or nothing (io/atomic_file.h): the target appears whole or stays as it was,
// no temporary is left, a full disk is an error (simulated with RLIMIT_FSIZE: writes past the
// limit fail as on a full disk), and a set of files appears together or not at all.
#include <catch2/catch.hpp>
#include "support/tiers.h"
#include <csignal>
#include <filesystem>
#include <sys/resource.h>
#include <sys/stat.h>
#include "io/atomic_file.h"
#include "io/image_io.h"
#include "support/errors.h"
#include "support/temp_dir.h"

using namespace caustica;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {
size_t entries(const fs::path& dir) {
  size_t n = 0;
  for (auto it = fs::directory_iterator(dir); it != fs::directory_iterator(); ++it) ++n;
  return n;
}

// Files larger than `bytes` cannot be written while it lives (as on a nearly full disk).
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    previous_handler_ = std::signal(SIGXFSZ, SIG_IGN);
    getrlimit(RLIMIT_FSIZE, &previous_);
    rlimit limited = previous_;
    limited.rlim_cur = bytes;
    setrlimit(RLIMIT_FSIZE, &limited);
  }
  ~FileSizeLimit() {
    setrlimit(RLIMIT_FSIZE, &previous_);
    std::signal(SIGXFSZ, previous_handler_);
  }

 private:
  rlimit previous_{};
  void (*previous_handler_)(int) = nullptr;
};

// Noise, so that no format compresses it below a few kilobytes.
Image noise(int w, int h) {
  Image img(w, h);
  uint32_t s = 12345;
  auto next = [&] {
    s = s * 1664525u + 1013904223u;
    return float(s >> 8) / float(1u << 24);
  };
  for (Color& c : img.pixels) c = Color(next(), next(), next());
  return img;
}
}  // namespace

TEST_CASE("atomic files: the content appears under the name, and no temporary is left", "[io][atomic]" TIER_UNIT) {
  test::TempDir dir;
  write_file_atomically(dir.file("a.txt"), "hello", "text");
  CHECK(test::read_text(dir.file("a.txt")) == "hello");
  write_file_atomically(dir.file("a.txt"), "replaced", "text");
  CHECK(test::read_text(dir.file("a.txt")) == "replaced");
  CHECK(entries(dir.path()) == 1);
  // A name of 250 bytes works: the temporary's own name is short.
  const std::string long_name(246, 'n');
  write_file_atomically(dir.file(long_name + ".png"), "x", "text");
  CHECK(fs::exists(dir.file(long_name + ".png")));
  // Past the file system's limit the name is refused before anything is written.
  const std::string too_long(260, 'n');
  CHECK_THAT(test::error_of([&] { write_file_atomically(dir.file(too_long), "x", "text"); }),
             Contains("the file name is longer than 255 bytes"));
  // A missing folder: the error names the target, and says why.
  CHECK_THAT(test::error_of([&] { write_file_atomically(dir.file("no/such/b.txt"), "x", "text"); }),
             Contains("no/such/b.txt: ") && Contains("No such file or directory"));
  // The file gets the permissions of any new file (not the temporary's private 0600).
  const mode_t mask = ::umask(0);
  ::umask(mask);
  CHECK((fs::status(dir.file("a.txt")).permissions() & fs::perms::all) == fs::perms(0666 & ~mask));
  CHECK(entries(dir.path()) == 2);
}

TEST_CASE("atomic files: a full disk is an error and the old file stays whole", "[io][atomic]" TIER_UNIT) {
  test::TempDir dir;
  const std::string good(5000, 'g');
  write_file_atomically(dir.file("out.txt"), good, "text");
  {
    FileSizeLimit limit(1000);
    CHECK_THAT(test::error_of([&] { write_file_atomically(dir.file("out.txt"), std::string(4000, 'b'), "text"); }),
               Contains("out.txt: cannot write the text: File too large"));
  }
  CHECK(test::read_text(dir.file("out.txt")) == good);
  CHECK(entries(dir.path()) == 1);
}

TEST_CASE("atomic files: images of every format fail whole on a full disk", "[io][atomic][image]" TIER_UNIT) {
  test::TempDir dir;
  const Image img = noise(64, 48);
  for (const char* ext : {".png", ".hdr", ".exr", ".pfm"}) {
    INFO(ext);
    const std::string path = dir.file(std::string("img") + ext);
    write_image(path, img);
    const std::string before = test::read_text(path);
    REQUIRE(before.size() > 1000);
    {
      FileSizeLimit limit(512);
      CHECK_THAT(test::error_of([&] { write_image(path, noise(64, 48)); }), Contains("cannot write the image"));
    }
    // The good image is still there, byte for byte, and nothing else.
    CHECK(test::read_text(path) == before);
  }
  CHECK(entries(dir.path()) == 4);
}

TEST_CASE("atomic files: a set appears together or not at all", "[io][atomic]" TIER_UNIT) {
  test::TempDir dir;
  {
    AtomicFileSet set;
    set.add(dir.file("one.txt")).write("1", "text");
    set.add(dir.file("two.txt")).write("2", "text");
    set.commit("text");
  }
  CHECK(test::read_text(dir.file("one.txt")) == "1");
  CHECK(test::read_text(dir.file("two.txt")) == "2");
  // The second member cannot be written (its name is too long): the first does not appear.
  {
    AtomicFileSet set;
    set.add(dir.file("three.txt")).write("3", "text");
    CHECK_FALSE(test::error_of([&] { set.add(dir.file(std::string(300, 'x'))); }).empty());
  }
  // A member whose write fails (a full disk) keeps every member of the set from appearing.
  {
    AtomicFileSet set;
    set.add(dir.file("four.txt")).write("4", "text");
    FileSizeLimit limit(100);
    CHECK_FALSE(test::error_of([&] { set.add(dir.file("five.txt")).write(std::string(1000, '5'), "text"); }).empty());
  }
  // A folder under the second member's name: found before any rename, so the first stays out.
  fs::create_directory(dir.file("seven.txt"));
  {
    AtomicFileSet set;
    set.add(dir.file("six.txt")).write("6", "text");
    set.add(dir.file("seven.txt")).write("7", "text");
    CHECK_THAT(test::error_of([&] { set.commit("text"); }), Contains("seven.txt: cannot write the text: is a directory"));
  }
  CHECK_FALSE(fs::exists(dir.file("six.txt")));
  fs::remove(dir.file("seven.txt"));
  CHECK_FALSE(fs::exists(dir.file("three.txt")));
  CHECK_FALSE(fs::exists(dir.file("four.txt")));
  CHECK_FALSE(fs::exists(dir.file("five.txt")));
  CHECK(entries(dir.path()) == 2);
}
