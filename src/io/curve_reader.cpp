// The `linearcurve` shape: round linear curves from a Mitsuba curve file, control points placed by
// `to_world` and radii kept as written (as Mitsuba does); one primitive per segment.
#include <filesystem>
#include "io/curve_io.h"
#include "io/json_params.h"
#include "io/loader.h"

namespace caustica::scene_loading {

namespace fs = std::filesystem;

bool Loader::read_linearcurve(const json& j, const std::string& p, std::vector<Primitive>& shapes) {
  if (!emission_[material_ref(j, p)].is_black()) r.fail(child(p, "material"), "a curve cannot emit light here");
  const std::string file = r.string(r.require(j, p, "file"), child(p, "file"));
  const fs::path path = fs::path(file).is_absolute() ? fs::path(file) : fs::path(base_dir) / file;
  std::vector<std::vector<glm::vec4>> curves;
  try {
    curves = read_curve_file(path.string(), 2);
  } catch (const InputError& e) {
    r.fail(child(p, "file"), e.what());
  }
  const glm::mat4 to_world = j.contains("to_world") ? read_affine(r, j["to_world"], child(p, "to_world")) : glm::mat4(1.0f);
  size_t segments = 0;
  for (const auto& c : curves) segments += c.size() - 1;
  uint32_t segment = 0;
  for (const auto& c : curves) {
    for (size_t i = 0; i + 1 < c.size(); ++i, ++segment) {
      const Vec3 a(to_world * glm::vec4(Vec3(c[i]), 1.0f)), b(to_world * glm::vec4(Vec3(c[i + 1]), 1.0f));
      check_reach(a, p);
      check_reach(b, p);
      shapes.push_back(Primitive::linear_curve(a, c[i].w, b, c[i + 1].w, segment, uint32_t(segments)));
    }
  }
  return false;
}

}  // namespace caustica::scene_loading
