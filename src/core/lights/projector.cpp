// Projector lights.
#include "core/lights/projector.h"
#include "core/lights/point.h"
#include "core/lights/read.h"
#include "core/textures/bitmap.h"

namespace caustica {

ProjectorProfile::ProjectorProfile(const Frame& frame, float tan_half_x, float aspect, const ColorParam& image, float scale)
    : frame_(frame), tan_half_x_(tan_half_x), aspect_(aspect), scale_(scale), image_(image) {
  area_ = 4.0f * tan_half_x_ * tan_half_x_ / aspect_;
  // The integral of the intensity over directions is pi scale area mean(E) (d omega =
  // cos^3 theta area du dv); the mean by the midpoint rule over the image.
  glm::dvec3 mean(0.0);
  const int n = image_.texture ? 256 : 1;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) mean += glm::dvec3(image_.at(Vec2((i + 0.5f) / n, (j + 0.5f) / n)));
  mean /= double(n) * n;
  integral_ = Color(mean) * (kPi * scale_ * area_);
}

Color ProjectorProfile::value(const Vec3& dir) const {
  const Vec3 d = frame_.to_local(dir);
  if (!(d.z > 0.0f)) return Color(0.0f);
  const float u = 0.5f - 0.5f * (d.x / d.z) / tan_half_x_;
  const float v = 0.5f - 0.5f * aspect_ * (d.y / d.z) / tan_half_x_;
  if (!(u >= 0.0f && u <= 1.0f && v >= 0.0f && v <= 1.0f)) return Color(0.0f);
  const float c = d.z / glm::length(d);
  return image_.at(Vec2(u, v)) * (kPi * scale_ / (c * c * c));
}

DirectionCone ProjectorProfile::cone() const {
  // Around the axis, out to the image's corners (a hair wider: rounding at the edge).
  const float tx = tan_half_x_, ty = tan_half_x_ / aspect_;
  const float theta = std::atan(std::sqrt(tx * tx + ty * ty));
  return {frame_.n, std::cos(std::min(kPi, theta + 1e-3f))};
}

Vec3 ProjectorProfile::sample(const Vec2& u, float& pdf) const {
  const Vec3 local = glm::normalize(Vec3((1.0f - 2.0f * u.x) * tan_half_x_, (1.0f - 2.0f * u.y) * tan_half_x_ / aspect_, 1.0f));
  pdf = 1.0f / (area_ * local.z * local.z * local.z);
  return frame_.to_world(local);
}

std::unique_ptr<Light> create_projector_light(const Params& p) {
  const Vec3 pos = p.point("position");
  const Vec3 dir = read_aim(p, pos);
  const Vec3 up = p.has("up") ? read_direction(p, "up") : Vec3(0, 1, 0);
  const ColorParam image = p.texture("irradiance", Color(1.0f));
  if (image.is_black()) p.fail("irradiance", "a projector with zero irradiance emits nothing");
  float aspect = 1.0f;
  if (const auto* bitmap = dynamic_cast<const BitmapTexture*>(image.texture)) aspect = float(bitmap->width()) / float(bitmap->height());
  // fov along fov_axis (as the camera's; default: Mitsuba's 50 mm lens, measured diagonally).
  const double fov = p.number_in("fov", 46.7911, 0.01, 179.0);
  const std::string axis = p.string("fov_axis", p.has("fov") ? "x" : "diagonal");
  const double t = std::tan(0.5 * fov * 3.14159265358979323846 / 180.0);
  double tan_x = t;
  if (axis == "y" || (axis == "smaller" && aspect > 1.0f) || (axis == "larger" && aspect <= 1.0f)) tan_x = t * aspect;
  else if (axis == "diagonal") tan_x = t / std::sqrt(1.0 + 1.0 / (double(aspect) * aspect));
  else if (axis != "x" && axis != "smaller" && axis != "larger") {
    p.fail("fov_axis", "unknown fov_axis \"" + axis + "\" (known: x, y, smaller, larger, diagonal)");
  }
  const float scale = float(p.number_in("scale", 1.0, 0.0, 1e9));
  if (!(scale > 0.0f)) p.fail("scale", "a projector with scale 0 emits nothing");
  return std::make_unique<PointLight>(pos, Color(1.0f),
                                      std::make_shared<ProjectorProfile>(oriented_frame(dir, up), float(tan_x), aspect, image, scale));
}

}  // namespace caustica
