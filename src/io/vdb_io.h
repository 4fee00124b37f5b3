// OpenVDB grids (.vdb) as voxel grids: one float or vector grid of a file (a fog volume: a
// density, or three channels), copied densely over its active voxels with one voxel of its
// background around them, its index-to-world transform kept (VolumeGrid::to_world). Needs the
// build with OpenVDB (CAUSTICA_OPENVDB); without it, reading one is an error saying so.
#pragma once
#include <string>
#include "core/media/volume.h"

namespace caustica {

// The structure OpenVDB's reader trusts, checked against the file's bytes: the header, the
// file's metadata and the grid descriptors, each grid's data within the file (a truncated file
// is an error here, not an endless allocation there). Needs no OpenVDB.
void check_vdb_structure(const std::string& bytes, const std::string& name);
// Whether this build reads .vdb files.
bool vdb_supported();
// The grid named `grid_name` (empty: "density" when the file has it, else its first float or
// vector grid). Errors (not a .vdb, truncated, no such grid, a level set, a non-linear
// transform, values not finite or negative, too many voxels) name the file and what is wrong.
VolumeGrid read_vdb_file(const std::string& path, const std::string& grid_name);
// A .vdb file holding `grid` as a float grid named `name` (voxel (i, j, k) at index (i, j, k);
// the transform maps the box corner to corner), for the tests and scripts.
void write_vdb_file(const std::string& path, const VolumeGrid& grid, const std::string& name);

}  // namespace caustica
