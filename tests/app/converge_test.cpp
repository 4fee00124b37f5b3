// `caustica converge`: checkpoints, the CSV, and a short end-to-end run.
#include <catch2/catch.hpp>
#include "support/tiers.h"
#include <chrono>
#include <filesystem>
#include <sstream>
#include <nlohmann/json.hpp>
#include "app/converge_command.h"
#include "io/image_io.h"
#include "support/run.h"

using namespace caustica;
namespace fs = std::filesystem;

namespace {
const std::string kTiny = std::string(CAUSTICA_SOURCE_DIR) + "/tests/data/tiny.json";

// tiny.json rendered with `spp` samples per pixel into DIR/ref.exr, the reference to converge to.
void render_reference(const test::TempDir& dir, int spp) {
  const test::RunResult r = test::run_caustica("render '" + kTiny + "' --spp " + std::to_string(spp) + " -o ref.exr -q", dir);
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
}
}  // namespace

TEST_CASE("converge: default checkpoints are powers of two up to the budget", "[app][converge]" TIER_UNIT) {
  CHECK(default_checkpoints(10) == std::vector<double>{1, 2, 4, 8, 10});
  CHECK(default_checkpoints(8) == std::vector<double>{1, 2, 4, 8});
  CHECK(default_checkpoints(0.5) == std::vector<double>{0.5});
}

TEST_CASE("converge: the CSV has a header and one line per row", "[app][converge]" TIER_UNIT) {
  const std::vector<ConvergeRow> rows = {{"photon", 1.5, 3, 0.25, 0.125}, {"path", 2, 40, 0.5, 0.0625}};
  const std::string csv = convergence_csv(rows);
  CHECK(csv == "integrator,seconds,passes,rmse,relmse\nphoton,1.5,3,0.25,0.125\npath,2,40,0.5,0.0625\n");
}

TEST_CASE("converge: a short run writes the CSV, images, error maps and the report", "[app][converge]" TIER_PROCESS) {
  test::TempDir dir;
  render_reference(dir, 64);
  test::RunResult r = test::run_caustica("converge '" + kTiny + "' --reference ref.exr --integrators path,photon --time 1.5 "
                         "--checkpoints 0.5,1 --photons 5000 --out report -q",
                         dir);
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  for (const char* f : {"convergence.csv", "index.html", "reference.png", "path.exr", "path.png", "path-error.png",
                        "photon.exr", "photon.png", "photon-error.png"}) {
    CHECK(fs::exists(dir.path() / "report" / f));
  }
  std::istringstream csv(test::read_text(dir.file("report/convergence.csv")));
  std::string line;
  std::getline(csv, line);
  CHECK(line == "integrator,seconds,passes,rmse,relmse");
  int path_rows = 0, photon_rows = 0;
  double last_path_relmse = 1e30, last_seconds = 0;
  std::string last_name;
  long last_passes = 0;
  while (std::getline(csv, line)) {
    std::istringstream fields(line);
    std::string name, seconds, passes, rmse, relmse;
    std::getline(fields, name, ',');
    std::getline(fields, seconds, ',');
    std::getline(fields, passes, ',');
    std::getline(fields, rmse, ',');
    std::getline(fields, relmse, ',');
    CHECK(std::stod(seconds) > 0);
    CHECK(std::stol(passes) >= 1);
    CHECK(std::stod(rmse) > 0);
    // No bound on the seconds themselves (a shared machine stalls a run past any bound; the
    // sanitizer run once took 3.2 s for this 1.5 s budget): each integrator's rows follow its
    // clock and its passes, one row per checkpoint passed and one at the end.
    if (name == last_name) {
      CHECK(std::stod(seconds) > last_seconds);
      CHECK(std::stol(passes) > last_passes);
    }
    last_name = name;
    last_seconds = std::stod(seconds);
    last_passes = std::stol(passes);
    if (name == "path") {
      ++path_rows;
      CHECK(std::stod(relmse) <= last_path_relmse * 1.05);  // the error falls as passes add up
      last_path_relmse = std::stod(relmse);
    }
    photon_rows += name == "photon";
  }
  CHECK(path_rows >= 2);
  CHECK(path_rows <= 3);
  CHECK(photon_rows >= 1);
  CHECK(photon_rows <= 3);
}

TEST_CASE("converge: the CSV has a floor-free column when the reference is several renders", "[app][converge]" TIER_UNIT) {
  const std::vector<ConvergeRow> rows = {{"photon", 1.5, 3, 0.25, 0.125}, {"path", 2, 40, 0.5, 0.0625}};
  CHECK(convergence_csv(rows).find("floor") == std::string::npos);
  CHECK(convergence_csv(rows, 0.025) ==
        "integrator,seconds,passes,rmse,relmse,relmse_floor_free\nphoton,1.5,3,0.25,0.125,0.1\n"
        "path,2,40,0.5,0.0625,0.0375\n");
}

TEST_CASE("converge: two references give the floor and the error without it", "[app][converge]" TIER_PROCESS) {
  test::TempDir dir;
  for (const char* seed : {"1", "2"}) {
    auto r = test::run_caustica("render '" + kTiny + "' --spp 16 --seed " + seed + " -o ref" + seed + ".exr -q", dir);
    REQUIRE(r.exit_code == 0);
  }
  // The floor, as compare computes it from the same two references.
  auto r = test::run_caustica("compare ref1.exr ref1.exr ref2.exr --json", dir);
  REQUIRE(r.exit_code == 0);
  const double floor = nlohmann::json::parse(r.out)["reference_floor"].get<double>();
  REQUIRE(floor > 0);
  // The references before the scene: each --reference takes one file, not the scene after it.
  r = test::run_caustica("converge --reference ref1.exr --reference ref2.exr '" + kTiny + "' --integrators path "
                         "--time 1 --checkpoints 0.5 --out report",
                         dir);
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  CHECK(r.err.find("reference floor: ") != std::string::npos);
  CHECK(r.err.find("without the floor") != std::string::npos);
  std::istringstream csv(test::read_text(dir.file("report/convergence.csv")));
  std::string line;
  std::getline(csv, line);
  CHECK(line == "integrator,seconds,passes,rmse,relmse,relmse_floor_free");
  int rows = 0;
  while (std::getline(csv, line)) {
    std::vector<std::string> f;
    std::istringstream fields(line);
    for (std::string v; std::getline(fields, v, ',');) f.push_back(v);
    REQUIRE(f.size() == 6);
    CHECK(std::stod(f[5]) == Approx(std::stod(f[4]) - floor).margin(1e-7));
    ++rows;
  }
  CHECK(rows >= 1);
  const std::string html = test::read_text(dir.file("report/index.html"));
  CHECK(html.find("reference floor") != std::string::npos);
  CHECK(html.find("mean of ref1.exr, ref2.exr") != std::string::npos);
}

TEST_CASE("converge: bad input is a clear error", "[app][converge]" TIER_PROCESS) {
  test::TempDir dir;
  write_image(dir.file("small.exr"), Image(8, 8));
  auto r = test::run_caustica("converge '" + kTiny + "' --reference small.exr --integrators path --time 1 --width 16 --out o", dir);
  CHECK(r.exit_code == 1);
  CHECK(r.err.find("small.exr: reference is 8x8") != std::string::npos);
  r = test::run_caustica("converge '" + kTiny + "' --reference small.exr --integrators path,pathx --time 1 --out o", dir);
  CHECK(r.exit_code == 1);
  CHECK(r.err.find("unknown integrator \"pathx\"") != std::string::npos);
}

TEST_CASE("converge: Ctrl-C or SIGTERM ends the run with the figures so far written", "[app][converge][interrupt]" TIER_PROCESS) {
  // Issue 23: converge had no handler, so a signal killed it and its report was lost.
  for (const auto& [signal, code] : {std::pair<std::string, int>{"INT", 130}, std::pair<std::string, int>{"TERM", 143}}) {
    INFO("SIG" << signal);
    test::TempDir dir;
    render_reference(dir, 16);
    // 60 s for path, then photon: the signal comes 3 s into path's run.
    const auto t0 = std::chrono::steady_clock::now();
    const test::RunResult r = test::run_caustica("converge '" + kTiny + "' --reference ref.exr --integrators path,photon --time 60 "
                           "--checkpoints 0.5,1 --out report -q",
                           dir, "timeout --preserve-status -s " + signal + " 3 ");
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    INFO(r.err);
    CHECK(r.exit_code == code);
    CHECK(seconds < 3.0 + 4.0);
    // path's figures and images are there; photon, never started, is named in the report.
    const std::string csv = test::read_text(dir.file("report/convergence.csv"));
    CHECK(csv.find("\npath,") != std::string::npos);
    CHECK(csv.find("photon") == std::string::npos);
    CHECK(fs::exists(dir.file("report/path.exr")));
    CHECK_FALSE(fs::exists(dir.file("report/photon.exr")));
    const std::string html = test::read_text(dir.file("report/index.html"));
    CHECK(html.find("interrupted") != std::string::npos);
    CHECK(html.find("not run: photon") != std::string::npos);
    CHECK(test::temporaries(dir.path()).empty());
  }
}

TEST_CASE("converge: variants of an integrator pass the name check", "[app][converge]" TIER_PROCESS) {
  // --integrators checks the name before any ':' (the settings after it are checked when the
  // integrator is made): photon:photons=2000 is photon with 2000 photons.
  test::TempDir dir;
  render_reference(dir, 4);
  test::RunResult r = test::run_caustica("converge '" + kTiny + "' --reference ref.exr --integrators photon:photons=2000,path --time 0.3 "
                         "--out report -q",
                         dir);
  INFO(r.err);
  CHECK(r.exit_code == 0);
  CHECK(fs::exists(dir.file("report/photon_photons_2000.exr")));
  r = test::run_caustica("converge '" + kTiny + "' --reference ref.exr --integrators phton:photons=2000 --time 0.3 --out report",
                         dir);
  CHECK(r.exit_code == 1);
  CHECK(r.err.find("--integrators: unknown integrator \"phton\"") != std::string::npos);
}
