// Voxel grid files: Mitsuba's binary .vol ("VOL", version 3, float32 voxels, 1 or 3 channels,
// the bounding box, then the voxels x fastest). Every way a file can be wrong is an error
// naming the file and what is wrong: truncated, a header that lies about the size, voxels that
// are not finite or are negative.
#pragma once
#include <string>
#include "core/media/volume.h"

namespace caustica {

// `signed_values`: negative values are allowed (an SDF grid's); otherwise refused (densities).
VolumeGrid read_vol_file(const std::string& path, bool signed_values = false);
// A grid file of either kind, told by its first bytes: an OpenVDB file (io/vdb_io.h; its grid
// `grid_name`, empty for the default) or a .vol.
VolumeGrid read_grid_file(const std::string& path, const std::string& grid_name);
// The same from bytes in memory (`name` for messages), for the fuzz tests.
VolumeGrid parse_vol(const std::string& bytes, const std::string& name, bool signed_values = false);
// A .vol file's bytes for a grid (the tests' and scripts' writer).
std::string format_vol(const VolumeGrid& grid);

}  // namespace caustica
