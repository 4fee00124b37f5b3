// The `linearcurve` and `bsplinecurve` shapes: round curves from a Mitsuba curve file, control
// points placed by `to_world` and radii kept as written (as Mitsuba does); one primitive per
// segment (a B-spline curve of n points has n - 3).
#include <filesystem>
#include "io/curve_io.h"
#include "io/json_params.h"
#include "io/loader.h"

namespace caustica::scene_loading {

namespace fs = std::filesystem;

bool Loader::read_linearcurve(const json& j, const std::string& p, std::vector<Primitive>& shapes) {
  read_curves(j, p, shapes, false);
  return false;
}

bool Loader::read_bsplinecurve(const json& j, const std::string& p, std::vector<Primitive>& shapes) {
  read_curves(j, p, shapes, true);
  return false;
}

void Loader::read_curves(const json& j, const std::string& p, std::vector<Primitive>& shapes, bool bspline) {
  refuse_emission(j, p, "a curve");
  const fs::path path = r.input_file(r.require(j, p, "file"), child(p, "file"), base_dir, "curve file");
  const size_t degree = bspline ? 3 : 1;
  std::vector<std::vector<glm::vec4>> curves;
  try {
    curves = read_curve_file(path.string(), degree + 1);
  } catch (const InputError& e) {
    r.fail(child(p, "file"), e.what());
  }
  const glm::mat4 to_world = j.contains("to_world") ? read_affine(r, j["to_world"], child(p, "to_world")) : glm::mat4(1.0f);
  size_t segments = 0;
  for (auto& c : curves) {
    segments += c.size() - degree;
    for (glm::vec4& cp : c) {
      const Vec3 x(to_world * glm::vec4(Vec3(cp), 1.0f));
      check_reach(x, p);
      cp = glm::vec4(x, cp.w);
    }
  }
  std::vector<glm::vec4>* points = nullptr;
  if (bspline) {
    scene().curve_points.push_back(std::make_unique<std::vector<glm::vec4>>());
    points = scene().curve_points.back().get();
    points->reserve(4 * segments);  // (the primitives point into it: no reallocation after)
  }
  uint32_t segment = 0;
  for (const auto& c : curves) {
    for (size_t i = 0; i + degree < c.size(); ++i, ++segment) {
      if (!bspline) {
        shapes.push_back(Primitive::linear_curve(Vec3(c[i]), c[i].w, Vec3(c[i + 1]), c[i + 1].w, segment, uint32_t(segments)));
        continue;
      }
      points->insert(points->end(), c.begin() + long(i), c.begin() + long(i) + 4);
      shapes.push_back(Primitive::bspline_curve(points->data() + 4 * size_t(segment), segment, uint32_t(segments)));
    }
  }
}

}  // namespace caustica::scene_loading
