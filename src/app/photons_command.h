// `caustica photons`: the photon maps after the photon pass, as a picture or a point cloud.
#pragma once
#include <string>
#include "app/scene_setup.h"
#include "core/image.h"
#include "photon/photon_map.h"

namespace caustica {

struct PhotonsArgs {
  SceneOptions common;
  std::string map = "both";  // global, caustic or both
  std::string output;        // .png or .ply
  bool heatmap = false;
};

int run_photons(const PhotonsArgs& args);

// Every photon visible from the camera, splatted as a point coloured by its flux (or, with
// heatmap, the count of visible photons per pixel in false colour), over `background`. Photons
// of `volume_maps` scattered in media: no surface hides them from behind, and media boundaries
// (null surfaces) do not hide them.
Image splat_photons(const Scene& scene, const std::vector<const PhotonMap*>& maps, const Image& background,
                    bool heatmap, size_t* visible = nullptr, const std::vector<const PhotonMap*>& volume_maps = {});

// Binary little-endian PLY: x y z nx ny nz (float) red green blue (uchar, flux colour),
// written through a temporary file.
void write_ply(const std::string& path, const std::vector<const PhotonMap*>& maps);

}  // namespace caustica
