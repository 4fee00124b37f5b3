// The photon pass: shoot photons from the lights, store them at diffuse surfaces.
#pragma once
#include <atomic>
#include <string>
#include <vector>
#include "core/scene.h"
#include "photon/photon.h"

namespace caustica {

struct PhotonPassSettings {
  size_t global_photons = 200000;   // stored photons wanted in the global map
  size_t caustic_photons = 200000;  // stored photons wanted in the caustic map (0: no caustic map)
  int max_depth = 16;               // bounces per photon path
  float glossy_threshold = 0.3f;    // photons are stored on glossy lobes at least this rough
  // Caustic photons pass only surfaces with a delta lobe or glossy ones smoother than this
  // (is_caustic_surface); the default keeps every surface that is not a gather surface.
  float caustic_threshold = 1e30f;
  // In media: the caustic emission stores only the first scattering point of L S+ V paths (the
  // volume caustic map), and counts those towards caustic_photons.
  bool caustic_volume_only = false;
  // In media: the global photons' first scattering point straight from a light is stored too
  // (photon-direct takes single scattering from the map; `photon` and sppm by shadow rays).
  bool volume_direct = false;
  // In media, a pass stops once its volume photons number this times global_photons.
  static constexpr size_t kVolumeShare = 8;
  // In media, once the global map is full the emission goes on for volume photons alone until
  // they number global_photons / volume_min_divisor (0: it does not), or it has emitted
  // kVolumeEmission times what filled the global map: a small medium in a large scene
  // (Mitsuba's media test scenes: 168 volume photons beside 10000 surface ones) would otherwise
  // take a first radius a third of its size, and its estimate the bias of such a blur.
  size_t volume_min_divisor = 4;
  static constexpr uint64_t kVolumeEmission = 4;
  uint64_t seed = 0;
  const std::atomic<bool>* cancel = nullptr;  // once set, the pass stops within a chunk and keeps no photons
};

struct PhotonPassResult {
  std::vector<Photon> global, caustic;
  uint64_t global_emitted = 0, caustic_emitted = 0;
  float global_scale = 1, caustic_scale = 1;  // a photon's flux is record.power() * scale
  // In media: the points where global photons scattered (VolumePhoton), and caustic photons
  // where they first scattered after specular surfaces alone (L S+ V).
  std::vector<Photon> volume, volume_caustic;
  float volume_scale = 1, volume_caustic_scale = 1;
  // In media: the share of the global volume photons' flux on L S+ V paths, which decides how
  // far the caustic pass may go (caustic_cap in photon_tracer.cpp).
  double volume_caustic_share = 0;
  double seconds = 0;
  uint64_t rays = 0;  // rays traced, both maps (kept photons or not): the pass's cost in rays
  std::vector<std::string> warnings;
};

// Global map: photons emitted in proportion to light power (area lights: uniform point,
// cosine direction; point lights: uniform sphere), stored at every gather surface (a diffuse
// lobe, or a glossy one at least glossy_threshold rough: is_gather_surface), Russian roulette
// by the sampled reflectance there. Caustic map: a separate emission aimed at the bounding
// spheres of the other (specular and near-specular) objects, stored only at the first gather
// surface of an L S+ D path.
// Emission continues until the wanted counts are stored (or a cap is reached, with a warning);
// in media, for the volume photons, as far as volume_min_divisor and kVolumeEmission say
// (each map's flux divided by the photons emitted while it was filled).
// Photon i is seeded from hash(i, seed): the maps are the same for any thread count.
PhotonPassResult trace_photons(const Scene& scene, const PhotonPassSettings& settings);

// Throws InputError when maps of this many photons would not fit in this machine's memory.
void check_photon_memory(size_t photons);

}  // namespace caustica
