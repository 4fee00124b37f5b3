// The command line on Mitsuba scenes: -D, --ignore-unsupported, and --accel.
#include <catch2/catch.hpp>
#include "support/tiers.h"
#include "core/accel.h"
#include "io/image_io.h"
#include "support/run.h"
#include "support/temp_dir.h"

using namespace caustica;

namespace {

const char* kScene = R"(<?xml version="1.0"?>
<scene version="3.0.0">
  <default name="spp" value="64"/>
  <default name="res" value="24"/>
  <sensor type="perspective">
    <float name="fov" value="40"/>
    <transform name="to_world"><lookat origin="0, 1, 4" target="0, 1, 0" up="0, 1, 0"/></transform>
    <sampler type="independent"><integer name="sample_count" value="$spp"/></sampler>
    <film type="hdrfilm"><integer name="width" value="$res"/><integer name="height" value="$res"/></film>
  </sensor>
  <shape type="rectangle">
    <transform name="to_world"><scale value="3"/><rotate x="1" angle="-90"/></transform>
  </shape>
  <shape type="sphere"><point name="center" x="0" y="1" z="0"/><float name="radius" value="0.5"/></shape>
  <emitter type="point"><point name="position" value="0, 3, 2"/><rgb name="intensity" value="10"/></emitter>
  $extra
</scene>
)";

std::string scene_with(const std::string& extra) {
  std::string s = kScene;
  s.replace(s.find("$extra"), 6, extra);
  return s;
}

}  // namespace

TEST_CASE("cli: a Mitsuba scene renders with -D parameters, and a bad -D is an error", "[app][mitsuba]" TIER_PROCESS) {
  test::TempDir dir;
  dir.write("scene.xml", scene_with(""));
  const test::RunResult r = test::run_caustica("render scene.xml -D spp=2 -D res=16 -o out.exr", dir);
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const Image img = read_image(dir.file("out.exr"));
  CHECK(img.width == 16);
  CHECK(img.height == 16);
  CHECK(img.mean().x > 0.01f);
  CHECK(r.out.find("passes (spp): 2") != std::string::npos);
  const test::RunResult bad = test::run_caustica("render scene.xml -D spp -o bad.exr", dir);
  CHECK(bad.exit_code == 1);
  CHECK(bad.err.find("-D spp: expected name=value") != std::string::npos);
}

TEST_CASE("cli: an unsupported plugin fails naming the line, and --ignore-unsupported skips it", "[app][mitsuba]" TIER_PROCESS) {
  test::TempDir dir;
  dir.write("scene.xml", scene_with(R"(<shape type="ellipsoids"/>)"));
  const test::RunResult r = test::run_caustica("render scene.xml -D spp=1 -o out.exr", dir);
  CHECK(r.exit_code == 1);
  CHECK(r.err.find("scene.xml:16:4: <shape type=\"ellipsoids\">: unsupported shape plugin \"ellipsoids\"") !=
        std::string::npos);
  CHECK_FALSE(std::filesystem::exists(dir.file("out.exr")));
  const test::RunResult ok = test::run_caustica("render scene.xml -D spp=1 --ignore-unsupported -o out.exr", dir);
  INFO(ok.err);
  CHECK(ok.exit_code == 0);
  CHECK(ok.err.find("warning: scene.xml:16:4: <shape type=\"ellipsoids\">: unsupported shape plugin") != std::string::npos);
  CHECK(ok.err.find(": skipped") != std::string::npos);
  CHECK(std::filesystem::exists(dir.file("out.exr")));
}

TEST_CASE("cli: --accel bvh and embree render the same scene alike and name the backend", "[app][accel]" TIER_PROCESS) {
  test::TempDir dir;
  dir.write("scene.xml", scene_with(""));
  const test::RunResult a = test::run_caustica("render scene.xml --accel bvh -o bvh.exr", dir);
  REQUIRE(a.exit_code == 0);
  CHECK(a.out.find("ray casting: bvh") != std::string::npos);
  if (!embree_available()) {
    const test::RunResult e = test::run_caustica("render scene.xml --accel embree -o e.exr", dir);
    CHECK(e.exit_code == 1);
    CHECK(e.err.find("no Embree") != std::string::npos);
    return;
  }
  const test::RunResult b = test::run_caustica("render scene.xml --accel embree -o embree.exr", dir);
  REQUIRE(b.exit_code == 0);
  CHECK(b.out.find("ray casting: embree") != std::string::npos);
  // The same rays find the same surfaces: the means agree far closer than the noise of 64 spp.
  const float ma = read_image(dir.file("bvh.exr")).mean().x, mb = read_image(dir.file("embree.exr")).mean().x;
  CHECK(mb == Approx(ma).epsilon(0.01));
  const test::RunResult bad = test::run_caustica("render scene.xml --accel optix -o x.exr", dir);
  CHECK(bad.exit_code != 0);
}

TEST_CASE("cli: a scene's unknown integrator is not interpreted when the command line names one", "[app][mitsuba]" TIER_PROCESS) {
  // Issue 24: 8 public scenes (bdpt, irrcache, guided_path, ...) stopped here even with --integrator.
  test::TempDir dir;
  dir.write("bdpt.xml", scene_with(R"(<integrator type="bdpt"><integer name="max_depth" value="3"/>
    <boolean name="light_image" value="true"/></integrator>)"));
  auto r = test::run_caustica("render bdpt.xml -o out.pfm --spp 2", dir);
  CHECK(r.exit_code == 1);
  CHECK(r.err.find("bdpt.xml:16:4: <integrator type=\"bdpt\">: unsupported integrator plugin \"bdpt\" (supported: ") !=
        std::string::npos);
  CHECK(r.err.find("render the scene with --integrator path or --integrator photon instead") != std::string::npos);
  // Named on the command line: replaced, with a note, and its max_depth (3 segments: 2 bounces) kept.
  r = test::run_caustica("render bdpt.xml -o out.pfm --spp 2 --integrator photon", dir);
  INFO(r.err);
  CHECK(r.exit_code == 0);
  CHECK(r.err.find("warning: bdpt.xml:16:4: <integrator type=\"bdpt\">: the scene's integrator \"bdpt\" is replaced by "
                   "--integrator photon; its max_depth 3 is kept") != std::string::npos);
  CHECK(r.out.find("max_depth: 2\n") != std::string::npos);
  CHECK(read_image(dir.file("out.pfm")).mean().x > 0.01f);
  // converge naming every integrator replaces it too.
  REQUIRE(test::run_caustica("render bdpt.xml -o ref.exr --spp 4 --integrator path -q", dir).exit_code == 0);
  r = test::run_caustica("converge bdpt.xml --reference ref.exr --integrators path --time 0.3 --out report -q", dir);
  INFO(r.err);
  CHECK(r.exit_code == 0);
  CHECK(r.err.find("is replaced by --integrators path") != std::string::npos);
}
