// Every output of the command line on a disk that is really full: a small tmpfs, filled with dd
// (issue 23). Where mounting is not allowed (not root, no CAP_SYS_ADMIN) the tests say so and
// skip; tests/io/atomic_file_test.cpp simulates the same with RLIMIT_FSIZE everywhere.
#include <catch2/catch.hpp>
#include "support/tiers.h"
#include <cstdlib>
#include <filesystem>
#include <set>
#include "io/image_io.h"
#include "support/run.h"

using namespace caustica;
using test::run_caustica;
namespace fs = std::filesystem;

namespace {

// A tmpfs of `kib` KiB mounted at DIR/disk for the object's life.
class SmallDisk {
 public:
  SmallDisk(const test::TempDir& dir, size_t kib) : path_(dir.path() / "disk") {
    fs::create_directories(path_);
    const std::string cmd = "mount -t tmpfs -o size=" + std::to_string(kib) + "k caustica-test '" + path_.string() + "' 2>/dev/null";
    mounted_ = std::system(cmd.c_str()) == 0;
  }
  ~SmallDisk() {
    if (mounted_) std::system(("umount '" + path_.string() + "'").c_str());
  }
  SmallDisk(const SmallDisk&) = delete;
  SmallDisk& operator=(const SmallDisk&) = delete;

  bool mounted() const { return mounted_; }
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  // Fills what is left with one file, as `dd` does until "No space left on device".
  void fill() const { std::system(("dd if=/dev/zero of='" + file("filler") + "' bs=4k 2>/dev/null").c_str()); }
  void empty() const { fs::remove(file("filler")); }
  // The names on the disk, the filler's aside.
  std::set<std::string> names() const {
    std::set<std::string> out;
    for (const auto& e : fs::directory_iterator(path_)) {
      if (e.path().filename() != "filler") out.insert(e.path().filename().string());
    }
    return out;
  }

 private:
  fs::path path_;
  bool mounted_ = false;
};

#define REQUIRE_MOUNTED(disk)                                                                       \
  if (!(disk).mounted()) {                                                                          \
    WARN("skipped: cannot mount a tmpfs here (needs root or CAP_SYS_ADMIN); see atomic_file_test"); \
    return;                                                                                         \
  }

}  // namespace

TEST_CASE("full disk: every image format fails with exit 1 and keeps the image that was there", "[app][full_disk]" TIER_PROCESS) {
  test::TempDir dir;
  SmallDisk disk(dir, 256);
  REQUIRE_MOUNTED(disk);
  dir.write("scene.json", test::kLitFloorScene);
  for (const std::string ext : {"png", "hdr", "exr", "pfm"}) {
    INFO(ext);
    const std::string out = disk.file("out." + ext);
    auto r = run_caustica("render scene.json -q -o '" + out + "'", dir);
    REQUIRE(r.exit_code == 0);
    const std::string before = test::read_text(out);
    REQUIRE(before.size() > 100);
    disk.fill();
    // Another seed: a different image, which must not replace the good one in part.
    r = run_caustica("render scene.json -q --seed 9 -o '" + out + "'", dir);
    CHECK(r.exit_code == 1);
    CHECK(r.err.find("No space left on device") != std::string::npos);
    CHECK(test::read_text(out) == before);
    CHECK(disk.names() == std::set<std::string>{"out." + ext});
    disk.empty();
    fs::remove(out);
  }
}

TEST_CASE("full disk: compare --diff, the photons' PLY and an image with its AOVs fail whole", "[app][full_disk]" TIER_PROCESS) {
  test::TempDir dir;
  SmallDisk disk(dir, 256);
  REQUIRE_MOUNTED(disk);
  dir.write("scene.json", test::kLitFloorScene);
  REQUIRE(run_caustica("render scene.json -q -o a.pfm", dir).exit_code == 0);
  REQUIRE(run_caustica("render scene.json -q --seed 3 -o b.pfm", dir).exit_code == 0);
  disk.fill();
  auto r = run_caustica("compare a.pfm b.pfm --diff '" + disk.file("d.png") + "'", dir);
  CHECK(r.exit_code == 1);
  CHECK(r.err.find("No space left on device") != std::string::npos);
  r = run_caustica("photons scene.json --photons 2000 -o '" + disk.file("p.ply") + "'", dir);
  CHECK(r.exit_code == 1);
  CHECK(r.err.find("No space left on device") != std::string::npos);
  r = run_caustica("render scene.json -q --integrator photon --aov -o '" + disk.file("out.exr") + "'", dir);
  CHECK(r.exit_code == 1);
  CHECK(r.err.find("No space left on device") != std::string::npos);
  CHECK(disk.names().empty());
  // With room again, all of them are written.
  disk.empty();
  CHECK(run_caustica("compare a.pfm b.pfm --diff '" + disk.file("d.png") + "'", dir).exit_code == 0);
  CHECK(run_caustica("photons scene.json --photons 2000 -o '" + disk.file("p.ply") + "'", dir).exit_code == 0);
  CHECK(run_caustica("render scene.json -q --integrator photon --aov -o '" + disk.file("out.exr") + "'", dir).exit_code == 0);
  CHECK(disk.names() == std::set<std::string>{"d.png", "p.ply", "out.exr", "out.photons.exr", "out.radius.exr"});
}
