// The command line on Mitsuba scenes: -D, --ignore-unsupported, and --accel.
#include <catch2/catch.hpp>
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

TEST_CASE("cli: a Mitsuba scene renders with -D parameters, and a bad -D is an error", "[app][mitsuba]") {
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

TEST_CASE("cli: an unsupported plugin fails naming the line, and --ignore-unsupported skips it", "[app][mitsuba]") {
  test::TempDir dir;
  dir.write("scene.xml", scene_with(R"(<shape type="bsplinecurve"/>)"));
  const test::RunResult r = test::run_caustica("render scene.xml -D spp=1 -o out.exr", dir);
  CHECK(r.exit_code == 1);
  CHECK(r.err.find("scene.xml:16:4: <shape type=\"bsplinecurve\">: unsupported shape plugin \"bsplinecurve\"") !=
        std::string::npos);
  CHECK_FALSE(std::filesystem::exists(dir.file("out.exr")));
  const test::RunResult ok = test::run_caustica("render scene.xml -D spp=1 --ignore-unsupported -o out.exr", dir);
  INFO(ok.err);
  CHECK(ok.exit_code == 0);
  CHECK(ok.err.find("warning: scene.xml:16:4: <shape type=\"bsplinecurve\">: unsupported shape plugin") != std::string::npos);
  CHECK(ok.err.find(": skipped") != std::string::npos);
  CHECK(std::filesystem::exists(dir.file("out.exr")));
}

TEST_CASE("cli: --accel bvh and embree render the same scene alike and name the backend", "[app][accel]") {
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
