// Mitsuba's analytic shapes other than the sphere, as triangle meshes in their object space:
// rectangle [-1, 1]^2 at z = 0 facing +z; cube [-1, 1]^3; disk of radius 1 at z = 0 facing +z;
// cylinder of radius 1 from z = 0 to z = 1 without caps. UVs as Mitsuba 3 gives them.
#pragma once
#include <nlohmann/json.hpp>

namespace caustica {

// {"vertices": [...], "indices": [...], "uvs": [...], and "normals" for the cylinder}.
nlohmann::json rectangle_mesh();
nlohmann::json cube_mesh();
// `segments` around the rim: the area is segments/(2 pi) sin(2 pi/segments) of the disk's.
nlohmann::json disk_mesh(int segments);
nlohmann::json cylinder_mesh(int segments);

}  // namespace caustica
