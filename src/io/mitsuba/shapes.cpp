// Mesh versions of Mitsuba's rectangle, cube, disk and cylinder.
#include "io/mitsuba/shapes.h"
#include <cmath>

namespace caustica {
using nlohmann::json;

namespace {
constexpr double kTwoPi = 6.283185307179586;
json v3(double x, double y, double z) { return json::array({x, y, z}); }
json v2(double u, double v) { return json::array({u, v}); }
json tri(int a, int b, int c) { return json::array({a, b, c}); }
}  // namespace

json rectangle_mesh() {
  return {{"vertices", {v3(-1, -1, 0), v3(1, -1, 0), v3(1, 1, 0), v3(-1, 1, 0)}},
          {"indices", {tri(0, 1, 2), tri(0, 2, 3)}},
          {"uvs", {v2(0, 0), v2(1, 0), v2(1, 1), v2(0, 1)}}};
}

json cube_mesh() {
  json verts = json::array(), idx = json::array(), uvs = json::array();
  // Each face: its normal axis and sign; the corners counter-clockwise seen from outside.
  for (int axis = 0; axis < 3; ++axis) {
    for (int sign : {-1, 1}) {
      const int u_axis = (axis + 1) % 3, v_axis = (axis + 2) % 3;
      const int base = int(verts.size());
      const double corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
      for (const auto& c : corners) {
        double p[3];
        p[axis] = sign;
        p[u_axis] = c[0];
        p[v_axis] = sign > 0 ? c[1] : -c[1];  // keep the winding outward on the negative face
        verts.push_back(v3(p[0], p[1], p[2]));
        uvs.push_back(v2(0.5 * (c[0] + 1), 0.5 * (c[1] + 1)));
      }
      idx.push_back(tri(base, base + 1, base + 2));
      idx.push_back(tri(base, base + 2, base + 3));
    }
  }
  return {{"vertices", verts}, {"indices", idx}, {"uvs", uvs}};
}

json disk_mesh(int segments) {
  json verts = json::array({v3(0, 0, 0)}), idx = json::array(), uvs = json::array({v2(0, 0)});
  for (int i = 0; i <= segments; ++i) {
    const double phi = kTwoPi * i / segments;
    verts.push_back(v3(i == segments ? 1.0 : std::cos(phi), i == segments ? 0.0 : std::sin(phi), 0));
    uvs.push_back(v2(1, double(i) / segments));
    if (i > 0) idx.push_back(tri(0, i, i + 1));
  }
  return {{"vertices", verts}, {"indices", idx}, {"uvs", uvs}};
}

json cylinder_mesh(int segments) {
  json verts = json::array(), idx = json::array(), uvs = json::array(), normals = json::array();
  for (int i = 0; i <= segments; ++i) {
    const double phi = kTwoPi * i / segments;
    const double x = i == segments ? 1.0 : std::cos(phi), y = i == segments ? 0.0 : std::sin(phi);
    for (int z = 0; z < 2; ++z) {
      verts.push_back(v3(x, y, z));
      normals.push_back(v3(x, y, 0));
      uvs.push_back(v2(double(i) / segments, z));
    }
    if (i > 0) {
      const int a = 2 * (i - 1), b = 2 * i;  // a, a+1 at the previous angle
      idx.push_back(tri(a, b, b + 1));
      idx.push_back(tri(a, b + 1, a + 1));
    }
  }
  return {{"vertices", verts}, {"indices", idx}, {"uvs", uvs}, {"normals", normals}};
}

}  // namespace caustica
