// `caustica photons`.
#include "app/photons_command.h"
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <tbb/global_control.h>
#include <unistd.h>
#include "app/stop_signals.h"
#include "core/metrics.h"
#include "io/atomic_file.h"
#include "io/image_io.h"
#include "trace/integrator.h"
#include "trace/render.h"

namespace caustica {
namespace fs = std::filesystem;

namespace {
// Photon colour: its flux's hue at full brightness (fluxes differ by orders of magnitude).
Color flux_colour(const Color& power) {
  const float m = max_component(power);
  return m > 0 ? power / m : Color(0.0f);
}

bool visible_from_camera(const Scene& scene, const Photon& ph, bool volume) {
  const Vec3 eye = scene.camera.eye_for(ph.position);
  const Vec3 n = volume ? Vec3(0.0f) : ph.surface_normal();
  if (!volume && glm::dot(n, eye - ph.position) <= 0) return false;  // seen from behind its surface
  Ray ray = spawn_ray_to(eye, Vec3(0.0f), ph.position, n);
  if (!scene.has_media()) return !scene.occluded(ray);
  // Through media boundaries (null surfaces), not through other surfaces; the media's own
  // attenuation aside.
  for (int crossing = 0; crossing < 256; ++crossing) {
    SurfaceHit hit;
    if (!scene.intersect(ray, hit)) return true;
    if (!Scene::is_medium_boundary(hit)) return false;
    ray = Scene::continued(ray, hit);
    if (!(ray.tmax > 0.0f)) return true;
  }
  return false;
}
}  // namespace

Image splat_photons(const Scene& scene, const std::vector<const PhotonMap*>& maps, const Image& background,
                    bool heatmap, size_t* visible, const std::vector<const PhotonMap*>& volume_maps) {
  const int w = background.width, h = background.height;
  Image colour(w, h);
  std::vector<float> count(size_t(w) * h, 0.0f);
  size_t seen = 0;
  std::vector<std::pair<const PhotonMap*, bool>> all;
  for (const PhotonMap* map : maps) all.push_back({map, false});
  for (const PhotonMap* map : volume_maps) all.push_back({map, true});
  for (const auto& [map, volume] : all) {
    for (uint32_t i = 0; i < map->size(); ++i) {
      const Photon& ph = (*map)[i];
      float x, y;
      if (!scene.camera.project(ph.position, x, y) || !visible_from_camera(scene, ph, volume)) continue;
      const size_t p = size_t(int(y)) * w + size_t(int(x));
      colour.pixels[p] += flux_colour(map->power(i));
      count[p] += 1.0f;
      ++seen;
    }
  }
  if (visible) *visible = seen;
  float max_count = 0;
  for (float c : count) max_count = std::max(max_count, c);
  Image out = background;
  for (size_t p = 0; p < out.pixels.size(); ++p) {
    if (count[p] == 0) continue;
    if (heatmap) {
      out.pixels[p] = false_colour(std::log1p(count[p]) / std::log1p(std::max(max_count, 1.0f)));
    } else {
      out.pixels[p] = glm::min(colour.pixels[p] / count[p] * std::min(1.0f, 0.35f + 0.15f * count[p]), Color(1.0f));
    }
  }
  return out;
}

void write_ply(const std::string& path, const std::vector<const PhotonMap*>& maps) {
  fs::path dir = fs::path(path).parent_path();
  if (dir.empty()) dir = ".";
  if (!fs::is_directory(dir)) throw InputError(path + ": output folder " + dir.string() + " does not exist");
  size_t n = 0;
  for (const PhotonMap* m : maps) n += m->size();
  std::string bytes = "ply\nformat binary_little_endian 1.0\ncomment caustica photon map\nelement vertex " +
                      std::to_string(n) +
                      "\nproperty float x\nproperty float y\nproperty float z\n"
                      "property float nx\nproperty float ny\nproperty float nz\n"
                      "property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n";
  constexpr size_t kRecord = 27;
  bytes.reserve(bytes.size() + n * kRecord);
  for (const PhotonMap* m : maps) {
    for (uint32_t i = 0; i < m->size(); ++i) {
      const Photon& ph = (*m)[i];
      const Vec3 nrm = ph.surface_normal();
      const Color c = flux_colour(m->power(i));
      unsigned char record[kRecord];
      const float floats[6] = {ph.position.x, ph.position.y, ph.position.z, nrm.x, nrm.y, nrm.z};
      std::memcpy(record, floats, 24);
      for (int k = 0; k < 3; ++k) record[24 + k] = static_cast<unsigned char>(std::lround(255.0f * std::clamp(c[k], 0.0f, 1.0f)));
      bytes.append(reinterpret_cast<const char*>(record), kRecord);
    }
  }
  write_file_atomically(path, bytes, "point cloud");
}

int run_photons(const PhotonsArgs& args) {
  const std::string ext = fs::path(args.output).extension().string();
  if (ext != ".png" && ext != ".ply") throw InputError(args.output + ": output must be .png or .ply");
  check_output_file(args.output);
  LoadedScene loaded = load_scene_with(args.common);
  Scene& scene = *loaded.scene;
  const int threads = thread_count(args.common);
  tbb::global_control control(tbb::global_control::max_allowed_parallelism, size_t(threads));

  // Ctrl-C or SIGTERM stops the photon pass and the picture's background at once (nothing is
  // written then); during the write it waits for the file to be complete.
  StopSignals stop_signals;
  auto stopped = [&] {
    if (!StopSignals::stopped()) return false;
    std::cerr << "interrupted: " << args.output << " not written\n";
    return true;
  };
  auto integrator = integrator_for(loaded, "photon", args.common);
  integrator->preprocess(scene, {scene.render.seed, args.common.quiet, &StopSignals::flag()});
  if (stopped()) return StopSignals::exit_code();
  // Surface maps (global, caustic, both) and in media the volume maps (volume: global and
  // caustic), or all of them.
  std::vector<const PhotonMap*> maps, volume_maps;
  const bool all = args.map == "all";
  if (all || args.map == "global" || args.map == "both") maps.push_back(integrator->global_map());
  if (all || args.map == "caustic" || args.map == "both") maps.push_back(integrator->caustic_map());
  if (all || args.map == "volume") volume_maps = integrator->volume_maps();
  if (args.map == "volume" && volume_maps.empty())
    throw InputError(args.common.scene + ": --map volume: the scene has no participating media, so no volume photons");

  size_t visible = 0, total = 0;
  for (const PhotonMap* m : maps) total += m->size();
  for (const PhotonMap* m : volume_maps) total += m->size();
  if (ext == ".ply") {
    std::vector<const PhotonMap*> every = maps;
    every.insert(every.end(), volume_maps.begin(), volume_maps.end());
    write_ply(args.output, every);
  } else {
    // The scene dimmed: direct light and mirrors only, at a quarter of its brightness.
    auto whitted = create_integrator("whitted", JsonSource{}, scene.render);
    RenderOptions options;
    options.job = {scene.render.seed, 4, 0.0};
    options.quiet = true;
    options.cancel = &StopSignals::flag();
    RenderStats stats;
    Image background = render_image(scene, *whitted, options, stats);
    if (stopped()) return StopSignals::exit_code();
    for (Color& c : background.pixels) c = Color(luminance(c) * 0.25f);
    write_image(args.output, splat_photons(scene, maps, background, args.heatmap, &visible, volume_maps));
  }
  stop_signals.restore();
  // A signal during the write: the file is complete, and the exit says it was stopped.
  if (StopSignals::stopped()) return StopSignals::exit_code();
  if (!args.common.quiet) {
    std::cout << "photons: " << total << " in " << args.map << " map" << (args.map == "global" || args.map == "caustic" ? "" : "s") << "\n"
              << integrator->describe();
    if (ext == ".png") std::cout << "visible from the camera: " << visible << "\n";
    std::cout << "wrote " << args.output << "\n";
  }
  return 0;
}

}  // namespace caustica
