// The `sdfgrid` shape: a signed distance grid from a Mitsuba .vol file (one channel, negative
// inside) over the unit cube under `to_world`; one primitive per voxel the surface may cross.
#include <filesystem>
#include "io/json_params.h"
#include "io/loader.h"
#include "io/volume_io.h"

namespace caustica::scene_loading {

namespace fs = std::filesystem;

bool Loader::read_sdfgrid(const json& j, const std::string& p, std::vector<Primitive>& shapes) {
  refuse_emission(j, p, "an sdfgrid");
  const fs::path path = r.input_file(r.require(j, p, "file"), child(p, "file"), base_dir, "SDF grid file");
  VolumeGrid grid;
  try {
    grid = read_vol_file(path.string(), true);
  } catch (const InputError& e) {
    r.fail(child(p, "file"), e.what());
  }
  if (grid.channels != 1) r.fail(child(p, "file"), path.string() + ": an SDF grid has 1 channel, not " + std::to_string(grid.channels));
  if (grid.nx < 2 || grid.ny < 2 || grid.nz < 2) {
    r.fail(child(p, "file"), path.string() + ": an SDF grid needs at least 2 x 2 x 2 values, not " + std::to_string(grid.nx) +
                                 " x " + std::to_string(grid.ny) + " x " + std::to_string(grid.nz));
  }
  SdfGrid::Normals normals = SdfGrid::Normals::Smooth;
  if (j.contains("normals")) {
    const std::string n = r.string(j["normals"], child(p, "normals"));
    if (n == "analytic") normals = SdfGrid::Normals::Analytic;
    else if (n != "smooth") r.fail(child(p, "normals"), "expected \"smooth\" or \"analytic\", not \"" + n + "\"");
  }
  const glm::mat4 to_world = j.contains("to_world") ? read_affine(r, j["to_world"], child(p, "to_world")) : glm::mat4(1.0f);
  scene().sdf_grids.push_back(std::make_unique<SdfGrid>(grid.nx, grid.ny, grid.nz, std::move(grid.values), to_world, normals));
  const SdfGrid* sdf = scene().sdf_grids.back().get();
  const std::vector<uint32_t> voxels = sdf->surface_voxels();
  if (voxels.empty()) r.fail(child(p, "file"), path.string() + ": no voxel of the grid holds both signs: it has no surface");
  for (uint32_t v : voxels) shapes.push_back(Primitive::sdf_voxel(sdf, v));
  return false;
}

}  // namespace caustica::scene_loading
