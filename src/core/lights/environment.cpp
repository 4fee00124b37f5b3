// Environment lights.
#include "core/lights/environment.h"
#include "core/error.h"
#include "core/lights/read.h"

namespace caustica {

EnvironmentLight::EnvironmentLight(Image image, float scale, const glm::mat3& to_world)
    : image_(std::move(image)), to_world_(to_world), to_local_(glm::transpose(to_world)) {
  for (Color& c : image_.pixels) c *= scale;
  const int w = image_.width, h = image_.height;
  std::vector<float> weights(size_t(w) * size_t(h));
  double sum[3] = {0, 0, 0};
  for (int y = 0; y < h; ++y) {
    // Each pixel row spans theta in [y, y + 1] * pi / h; its solid angle per pixel is
    // (2 pi / w) (cos theta0 - cos theta1).
    const double t0 = double(y) / h * 3.14159265358979323846, t1 = double(y + 1) / h * 3.14159265358979323846;
    const double omega = 2.0 * 3.14159265358979323846 / w * (std::cos(t0) - std::cos(t1));
    const float sin_mid = float(std::sin(0.5 * (t0 + t1)));
    for (int x = 0; x < w; ++x) {
      const Color& c = image_.at(x, y);
      weights[size_t(y) * size_t(w) + size_t(x)] = luminance(c) * sin_mid;
      for (int k = 0; k < 3; ++k) sum[k] += double(c[k]) * omega;
    }
  }
  distribution_ = Distribution2D(weights.data(), w, h);
  power_per_area_ = Color(float(sum[0]), float(sum[1]), float(sum[2]));
}

std::unique_ptr<EnvironmentLight> EnvironmentLight::constant(const Color& radiance) {
  Image flat(64, 32);  // enough rows for sin(theta) to make the sampling nearly uniform
  for (Color& c : flat.pixels) c = radiance;
  return std::make_unique<EnvironmentLight>(std::move(flat), 1.0f, glm::mat3(1.0f));
}

Vec2 EnvironmentLight::to_uv(const Vec3& world_dir) const {
  const Vec3 v = to_local_ * world_dir;
  float u = std::atan2(v.x, -v.z) * (0.5f * kInvPi);
  u -= std::floor(u);
  const float t = std::acos(std::clamp(v.y, -1.0f, 1.0f)) * kInvPi;
  return Vec2(u, std::min(t, 0x1.fffffep-1f));
}

Vec3 EnvironmentLight::from_uv(const Vec2& uv) const {
  const float phi = 2.0f * kPi * uv.x, theta = kPi * uv.y;
  const float s = std::sin(theta);
  const Vec3 local(s * std::sin(phi), std::cos(theta), -s * std::cos(phi));
  return to_world_ * local;
}

Color EnvironmentLight::lookup(const Vec2& uv) const {
  const int x = std::clamp(int(uv.x * float(image_.width)), 0, image_.width - 1);
  const int y = std::clamp(int(uv.y * float(image_.height)), 0, image_.height - 1);
  return image_.at(x, y);
}

Color EnvironmentLight::escaped(const Vec3& dir) const { return lookup(to_uv(dir)); }

float EnvironmentLight::pdf_escaped(const Vec3& dir) const {
  const Vec2 uv = to_uv(dir);
  const float s = std::sin(kPi * uv.y);
  return s > 0.0f ? distribution_.pdf(uv) / (2.0f * kPi * kPi * s) : 0.0f;
}

Vec3 EnvironmentLight::sample_direction(const Vec2& u, float& pdf) const {
  const Vec3 dir = from_uv(distribution_.sample(u, nullptr));
  // The density and radiance are read back from the direction, so that a sample on a pixel's
  // edge agrees with pdf_escaped and escaped, as MIS needs.
  pdf = pdf_escaped(dir);
  return dir;
}

bool EnvironmentLight::sample_li(const Vec3& x, const Vec2& u, LightSample& s) const {
  s.wi = sample_direction(u, s.pdf);
  if (!(s.pdf > 0.0f)) return false;
  s.dist = 2.0f * (radius_ + glm::length(x - centre_));
  s.p = x + s.dist * s.wi;
  s.n = Vec3(0.0f);
  s.weight = escaped(s.wi) / s.pdf;
  return !is_black(s.weight);
}

bool EnvironmentLight::sample_travel(const Vec2& u, Vec3& dir, Color& value) const {
  float pdf = 0.0f;
  const Vec3 towards = sample_direction(u, pdf);
  if (!(pdf > 0.0f)) return false;
  dir = -towards;
  value = escaped(towards) / pdf;
  return true;
}

LightPoint EnvironmentLight::sample_origin(const Vec2&) const {
  // An environment has no origin of its own: its photons start on a disc chosen together
  // with their direction (sample_emission, and sample_travel for aimed caustic photons).
  return {centre_, Vec3(0.0f), 0.0f, Vec2(0.0f)};
}

EmittedPhoton EnvironmentLight::sample_emission(const Vec2& u_pos, const Vec2& u_dir) const {
  EmittedPhoton e;
  Color value;
  if (!sample_travel(u_dir, e.dir, value)) return {centre_, Vec3(0.0f), Vec3(0, -1, 0), Color(0.0f)};
  // From a disc of the sphere's radius, perpendicular to the travel, behind the sphere.
  e.origin = point_on_disc(centre_ - e.dir * (1.001f * radius_), e.dir, radius_, u_pos);
  e.normal = Vec3(0.0f);
  e.flux = value * (kPi * radius_ * radius_);
  return e;
}

std::unique_ptr<Light> EnvironmentLight::create(const Params& p) {
  const std::string path = p.file("filename", "environment map");
  Image image = p.image("filename", "environment map");
  float brightest = 0.0f;
  for (const Color& c : image.pixels) {
    if (!is_finite(c) || c.x < 0 || c.y < 0 || c.z < 0) p.fail("filename", "environment map " + path + " has negative or non-finite pixels");
    brightest = std::max(brightest, max_component(c));
  }
  const float scale = float(p.number_in("scale", 1.0, 0.0, kMaxColor));
  if (double(brightest) * scale > kMaxColor) {
    p.fail("filename", "environment map " + path + " is too bright: its brightest pixel" +
                           (scale == 1.0f ? std::string() : " times its scale") + " is " + format_number(double(brightest) * scale) +
                           ", the most a scene may emit is 1e9");
  }
  auto env = std::make_unique<EnvironmentLight>(std::move(image), scale, p.rotation("to_world"));
  if (is_black(env->power())) p.fail("filename", "the environment map is black: it emits nothing");
  return env;
}

std::unique_ptr<Light> EnvironmentLight::create_constant(const Params& p) { return constant(read_nonzero(p, "radiance")); }

}  // namespace caustica
