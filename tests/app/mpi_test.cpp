// `mpirun -np 2 caustica render`: the ranks' image is the one-process image of the same passes,
// bit for bit, and a failing rank fails the run without an image. Skipped, with a message, when
// this build has no MPI or mpirun is not installed (scripts/setup.sh installs it).
#include <catch2/catch.hpp>
#include "support/tiers.h"
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <regex>
#include <string>
#include "support/run.h"
#include "trace/cluster.h"

using namespace caustica;
using test::run_caustica;

namespace {

const std::string kMpirun = "mpirun --allow-run-as-root --oversubscribe ";

bool mpi_available() {
  if (!Cluster::built_with_mpi()) {
    WARN("skipped: this build has no MPI (CAUSTICA_MPI is off)");
    return false;
  }
  if (std::system("command -v mpirun >/dev/null 2>&1") != 0) {
    WARN("skipped: mpirun is not installed (Debian: openmpi-bin)");
    return false;
  }
  return true;
}

std::string scene_path() { return std::string(CAUSTICA_SOURCE_DIR) + "/scenes/cornell-spheres.json"; }

int passes_reported(const std::string& out) {
  std::smatch m;
  if (!std::regex_search(out, m, std::regex("passes \\(spp\\): (\\d+)"))) return -1;
  return std::stoi(m[1]);
}

}  // namespace

TEST_CASE("mpi: two ranks render the one-process image of the same passes, bit for bit", "[app][mpi]" TIER_PROCESS) {
  if (!mpi_available()) return;
  test::TempDir dir;
  // 5 passes: rank 0 renders 0, 2, 4 and rank 1 renders 1, 3. Progressive photon passes trace
  // their own maps; path passes their own samples.
  // In media too: the volume maps' first radii come from pass 0's maps on every rank.
  for (const std::string integrator : {"path", "photon", "photon:progressive=false", "photon in fog"}) {
    SECTION(integrator) {
      const bool fog = integrator == "photon in fog";
      const std::string scene = fog ? std::string(CAUSTICA_SOURCE_DIR) + "/scenes/fog-cornell.json" : scene_path();
      const std::string args = "render '" + scene + "' --width 40 --height 32 --spp 5 --integrator " +
                               (fog ? std::string("photon --photons 5000") : integrator) + " -q --threads 1 -o ";
      const auto alone = run_caustica(args + "alone.pfm", dir);
      REQUIRE(alone.exit_code == 0);
      const auto ranks = run_caustica(args + "ranks.pfm", dir, kMpirun + "-np 2 ");
      INFO("stderr: " << ranks.err);
      REQUIRE(ranks.exit_code == 0);
      const std::string a = test::read_text(dir.file("alone.pfm")), b = test::read_text(dir.file("ranks.pfm"));
      REQUIRE(a.size() > 40 * 32 * 12);
      CHECK(a == b);
      // Not a black image: the comparison means something.
      CHECK(a.find_first_not_of('\0', a.size() - 40 * 32 * 12) != std::string::npos);
    }
  }
}

TEST_CASE("mpi: --time stops all ranks after the same round, and the image is that many passes'", "[app][mpi]" TIER_PROCESS) {
  if (!mpi_available()) return;
  test::TempDir dir;
  const std::string base = "render '" + scene_path() + "' --width 24 --height 24 --threads 1 --integrator path ";
  const auto ranks = run_caustica(base + "--time 1.5 -o ranks.pfm", dir, kMpirun + "-np 2 ");
  INFO("stdout: " << ranks.out << "\nstderr: " << ranks.err);
  REQUIRE(ranks.exit_code == 0);
  // Rounds of one pass per rank: an even count, all of them in the image.
  const int passes = passes_reported(ranks.out);
  REQUIRE(passes >= 2);
  CHECK(passes % 2 == 0);
  CHECK(ranks.out.find("MPI ranks: 2") != std::string::npos);
  const auto alone = run_caustica(base + "-q --spp " + std::to_string(passes) + " -o alone.pfm", dir);
  REQUIRE(alone.exit_code == 0);
  CHECK(test::read_text(dir.file("alone.pfm")) == test::read_text(dir.file("ranks.pfm")));
}

TEST_CASE("mpi: a rank that fails ends the run with its error and no image", "[app][mpi]" TIER_PROCESS) {
  if (!mpi_available()) return;
  test::TempDir dir;
  dir.write("bad.json", "{\"camera\": {\"position\": [0, 1, 3], \"look_at\": [0, 1, 0]},\n  \"objects\": [\n");
  const std::string good = "render '" + scene_path() + "' --width 24 --height 24 --spp 64 -o out.png";
  SECTION("rank 1 reads a broken scene file (mpirun's MPMD form: rank 0 has a good one)") {
    const auto r = run_caustica(good + " : -np 1 '" + CAUSTICA_EXE + "' render bad.json -o out.png", dir,
                                kMpirun + "-np 1 ");
    INFO("stderr: " << r.err);
    CHECK(r.exit_code != 0);
    CHECK(r.err.find("bad.json") != std::string::npos);
    CHECK(r.err.find("(rank 1 of 2)") != std::string::npos);
    CHECK(test::no_images_left(dir));
  }
  SECTION("the ranks were given different settings") {
    const auto r = run_caustica(good + " : -np 1 '" + CAUSTICA_EXE + "' render '" + scene_path() +
                                    "' --width 24 --height 24 --spp 32 -o out.png",
                                dir, kMpirun + "-np 1 ");
    INFO("stderr: " << r.err);
    CHECK(r.exit_code != 0);
    CHECK(r.err.find("different scene files or settings") != std::string::npos);
    CHECK(test::no_images_left(dir));
  }
  SECTION("the ranks read scene files of the same name that differ (machines without a shared file system)") {
    std::filesystem::create_directories(dir.path() / "node1");
    std::filesystem::create_directories(dir.path() / "node2");
    std::string other = test::kLitFloorScene;
    other.replace(other.find("[5, 5, 5]"), 9, "[6, 6, 6]");
    dir.write("node1/scene.json", test::kLitFloorScene);
    dir.write("node2/scene.json", other);
    const std::string exe = std::string("'") + CAUSTICA_EXE + "'";
    const std::string args = " render scene.json --spp 4 -o '" + dir.file("out.png") + "'";
    const auto r = run_caustica(args + " : -np 1 -wdir node2 " + exe + args, dir, kMpirun + "-np 1 -wdir node1 ");
    INFO("stderr: " << r.err);
    CHECK(r.exit_code != 0);
    CHECK(r.err.find("different scene files or settings") != std::string::npos);
    CHECK_FALSE(std::filesystem::exists(dir.file("out.png")));
  }
  SECTION("sppm, whose passes depend on one another") {
    const auto r = run_caustica(good + " --integrator sppm", dir, kMpirun + "-np 2 ");
    INFO("stderr: " << r.err);
    CHECK(r.exit_code != 0);
    CHECK(r.err.find("run it on one rank") != std::string::npos);
    CHECK(test::no_images_left(dir));
  }
  SECTION("rank 1 is killed in the middle of the render") {
    // Rank 1's shell arms a kill of itself (then caustica, by exec) after 2 s of a long render.
    dir.write("kill-rank-1.sh",
              "if [ \"$OMPI_COMM_WORLD_RANK\" = 1 ]; then (sleep 2; kill -9 $$) & fi\nexec \"$@\"\n");
    const auto r = run_caustica("render '" + scene_path() + "' --width 64 --height 64 --spp 100000 -o out.png", dir,
                                kMpirun + "-np 2 sh kill-rank-1.sh ");
    INFO("stderr: " << r.err);
    CHECK(r.exit_code != 0);
    CHECK(test::no_images_left(dir));
  }
}

TEST_CASE("mpi: SIGTERM (a scheduler's time limit) writes the passes completed by all ranks", "[app][mpi]" TIER_PROCESS) {
  if (!mpi_available()) return;
  test::TempDir dir;
  const std::string args =
      "render '" + scene_path() + "' --width 32 --height 32 --spp 1000000 --threads 1 -o out.pfm";
  // The signal must come after the first round of passes, which on a loaded machine took
  // longer than 3 s: wait three times as long as a 4-pass run of two ranks takes, at least 3 s.
  const auto t0 = std::chrono::steady_clock::now();
  REQUIRE(run_caustica("render '" + scene_path() + "' --width 32 --height 32 --spp 4 --threads 1 -q -o warm.pfm", dir,
                       kMpirun + "-np 2 ").exit_code == 0);
  const double delay = std::max(3.0, 3.0 * std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  std::filesystem::remove(dir.file("warm.pfm"));
  INFO("signal after " << delay << " s");
  std::string prefix;
  SECTION("to mpirun, which passes it on to the ranks") {
    // --foreground: timeout signals mpirun alone. Without it, it signals its whole process group
    // as well, mpirun receives SIGTERM twice, and Open MPI takes a second signal as "kill now".
    prefix = "timeout --foreground -s TERM " + std::to_string(delay + 1.0) + " " + kMpirun + "-np 2 ";
  }
  SECTION("to every rank, as Slurm sends it") {
    dir.write("term-after.sh", "(sleep " + std::to_string(delay) + "; kill -TERM $$) &\nexec \"$@\"\n");
    prefix = kMpirun + "-np 2 sh term-after.sh ";
  }
  const auto r = run_caustica(args, dir, prefix);
  INFO("stdout: " << r.out << "\nstderr: " << r.err);
  CHECK(r.exit_code != 0);
  CHECK(r.out.find("interrupted: passes completed so far") != std::string::npos);
  CHECK(passes_reported(r.out) > 0);
  const std::string image = test::read_text(dir.file("out.pfm"));
  CHECK(image.size() > 32 * 32 * 12);
}

TEST_CASE("mpi: a build without MPI started by mpirun says that each process renders alone", "[app][mpi]" TIER_PROCESS) {
  if (Cluster::built_with_mpi() || std::system("command -v mpirun >/dev/null 2>&1") != 0) {
    WARN("skipped: for builds without MPI (CAUSTICA_MPI off) on a machine with mpirun");
    return;
  }
  test::TempDir dir;
  const auto r = run_caustica("render '" + scene_path() + "' --width 8 --height 8 --spp 1 -q -o out.png", dir,
                              kMpirun + "-np 2 ");
  INFO("stderr: " << r.err);
  CHECK(r.exit_code == 0);
  CHECK(r.err.find("built without MPI") != std::string::npos);
}

TEST_CASE("mpi: converge on two ranks records whole rounds of passes and writes its report", "[app][mpi]" TIER_PROCESS) {
  if (!mpi_available()) return;
  test::TempDir dir;
  dir.write("scene.json", test::kLitFloorScene);
  const auto ref = run_caustica("render scene.json --integrator path --spp 64 -q -o ref.exr", dir);
  REQUIRE(ref.exit_code == 0);
  const std::string args = "converge scene.json --reference ref.exr --integrators path,photon --time 1.5 "
                           "--checkpoints 0.5,1.5 --threads 1 --seed 3 --out ";
  const auto ranks = run_caustica(args + "ranks", dir, kMpirun + "-np 2 ");
  INFO("stderr: " << ranks.err);
  REQUIRE(ranks.exit_code == 0);
  const std::string csv = test::read_text(dir.file("ranks/convergence.csv"));
  INFO("csv: " << csv);
  // Rows for both integrators; the passes of each row are whole rounds of 2.
  std::regex row("(path|photon),([0-9.e+-]+),([0-9]+),([0-9.e+-]+),([0-9.e+-]+)");
  int rows = 0;
  for (auto it = std::sregex_iterator(csv.begin(), csv.end(), row); it != std::sregex_iterator(); ++it) {
    ++rows;
    const int passes = std::stoi((*it)[3]);
    CHECK(passes % 2 == 0);
    CHECK(passes >= 2);
    CHECK(std::stod((*it)[5]) > 0);
  }
  CHECK(rows >= 2);
  CHECK(std::filesystem::exists(dir.file("ranks/index.html")));
  CHECK(std::filesystem::exists(dir.file("ranks/photon.exr")));
  // The final images estimate the reference's image: path tracing with many passes on a 16x16
  // image is within a few percent of the 64-spp reference (its own noise dominates).
  const auto cmp = run_caustica("compare ranks/path.exr ref.exr --json", dir);
  REQUIRE(cmp.exit_code == 0);
  std::smatch m;
  REQUIRE(std::regex_search(cmp.out, m, std::regex("\"relmse\":([0-9.e+-]+)")));
  CHECK(std::stod(m[1]) < 0.02);
}
