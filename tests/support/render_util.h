// Renders scene text with a named integrator for tests.
#pragma once
#include <string>
#include <tbb/global_control.h>
#include "io/scene_loader.h"
#include "support/temp_dir.h"
#include "support/tiers.h"
#include "trace/render.h"

namespace caustica::test {

struct TestRender {
  Image image;
  RenderStats stats;
};

// settings_json: the integrator's settings (without "type"); spp and size override the scene's.
// In a figure-tier test of a reduced build, spp and the photon counts are cut (support/tiers.h).
inline TestRender render_text(const std::string& scene_text, const std::string& integrator,
                              const std::string& settings_json, int spp, int width, int height, uint64_t seed = 1,
                              int threads = 0, const std::string& base_dir = ".") {
  LoadedScene loaded = parse_scene(scene_text, "test.json", base_dir);
  Scene& scene = *loaded.scene;
  scene.render.width = width;
  scene.render.height = height;
  scene.camera.set_resolution(width, height);
  JsonSource settings;
  settings.file = "test.json";
  settings.pointer = "/integrator";
  settings.value = nlohmann::json::parse(figure_settings(settings_json));
  auto make = [&] {
    auto integ = create_integrator(integrator, settings, scene.render);
    integ->preprocess(scene, {seed, true});
    RenderOptions options;
    options.job.passes = figure_spp(spp);
    options.job.seed = seed;
    options.quiet = true;
    TestRender r;
    r.image = render_image(scene, *integ, options, r.stats);
    return r;
  };
  if (threads > 0) {
    tbb::global_control control(tbb::global_control::max_allowed_parallelism, size_t(threads));
    return make();
  }
  return make();
}

inline std::string read_scene_file(const std::string& relative) {
  return read_text(std::string(CAUSTICA_SOURCE_DIR) + "/" + relative);
}

// Mean of a rectangle of pixels.
inline glm::dvec3 region_mean(const Image& img, int x0, int y0, int x1, int y1) {
  glm::dvec3 sum(0.0);
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) sum += glm::dvec3(img.at(x, y));
  return sum / double((x1 - x0) * (y1 - y0));
}

}  // namespace caustica::test
