// The command line of progressive photon mapping and sppm: flags, integrator specs, renders.
#include <catch2/catch.hpp>
#include "support/tiers.h"
#include <filesystem>
#include "io/image_io.h"
#include "support/run.h"

using namespace caustica;
using test::run_caustica;
namespace fs = std::filesystem;

TEST_CASE("cli: progressive and sppm flags that conflict or do not apply fail with a message and no image",
          "[app][progressive]" TIER_PROCESS) {
  test::TempDir dir;
  dir.write("scene.json", test::kLitFloorScene);
  struct Case {
    std::string name, args, expect;
  };
  const std::vector<Case> cases = {
      {"--progressive with --no-progressive", "--integrator photon --progressive --no-progressive", "excludes"},
      {"unknown key in the integrator spec", "--integrator \"photon:progressive=true:foo=1\"", "unknown key \"foo\""},
      {"spec item without a value", "--integrator \"photon:progressive\"", "expected TYPE:KEY=VALUE"},
      {"--gather-rays with sppm", "--integrator sppm --gather-rays 3",
       "--gather-rays does not apply to integrator \"sppm\""},
      {"--progressive with sppm", "--integrator sppm --progressive", "--progressive does not apply to integrator \"sppm\""},
      {"--radius with photon", "--integrator photon --radius 0.1", "--radius does not apply to integrator \"photon\""},
      {"--alpha out of range", "--integrator sppm --alpha 1.5", "alpha"},
  };
  for (const Case& c : cases) {
    SECTION(c.name) {
      const auto r = run_caustica("render scene.json -o out.png " + c.args, dir);
      INFO("stderr: " << r.err);
      CHECK(r.exit_code != 0);
      CHECK(r.exit_code < 128);  // not killed by a signal
      CHECK(r.err.find(c.expect) != std::string::npos);
      CHECK(test::no_images_left(dir));
    }
  }
}

TEST_CASE("cli: --integrator sppm and photon --progressive render valid images", "[app][progressive]" TIER_PROCESS) {
  test::TempDir dir;
  dir.write("scene.json", test::kLitFloorScene);
  auto r = run_caustica("render scene.json -o sppm.exr --integrator sppm --photons 5000 --spp 4 --threads 2", dir);
  INFO("stderr: " << r.err);
  REQUIRE(r.exit_code == 0);
  CHECK(r.out.find("integrator: sppm") != std::string::npos);
  CHECK(r.out.find("passes: 4") != std::string::npos);
  CHECK(r.out.find("passes (spp): 4") != std::string::npos);
  const Image sppm = read_image(dir.file("sppm.exr"));
  CHECK(sppm.width == 16);
  CHECK(sppm.height == 16);
  bool finite = true;
  for (const Color& c : sppm.pixels) finite = finite && is_finite(c) && c.r >= 0 && c.g >= 0 && c.b >= 0;
  CHECK(finite);
  CHECK(sppm.mean().x > 0.05f);

  r = run_caustica("render scene.json -o ppm.exr --integrator \"photon:progressive=true:photons=5000\" "
                   "--caustic-photons 1000 --spp 3 --threads 2",
                   dir);
  REQUIRE(r.exit_code == 0);
  CHECK(r.out.find("progressive: 3 photon passes") != std::string::npos);
  const Image ppm = read_image(dir.file("ppm.exr"));
  CHECK(ppm.mean().x > 0.05f);
  // The same light: the two consistent methods agree on the mean within their noise.
  CHECK(ppm.mean().x == Approx(sppm.mean().x).epsilon(0.15));

  // The flag form.
  r = run_caustica("render scene.json -o flag.exr --integrator photon --progressive --photons 5000 "
                   "--caustic-photons 1000 --spp 2 --threads 2",
                   dir);
  REQUIRE(r.exit_code == 0);
  CHECK(r.out.find("progressive: 2 photon passes") != std::string::npos);
}
