// The render block (size, samples, seed, depth, crop, backend, filter, light sampler), the command line's
// overrides over it, and the camera.
#include "io/loader.h"

namespace caustica::scene_loading {

void Loader::read_render(const json& j, const std::string& p) {
  r.check_object(j, p, {"width", "height", "spp", "seed", "max_depth", "crop", "accel", "filter", "light_sampler"});
  RenderSettings& rs = scene().render;
  if (j.contains("width")) rs.width = int(r.integer(j["width"], child(p, "width"), 1, 16384));
  if (j.contains("height")) rs.height = int(r.integer(j["height"], child(p, "height"), 1, 16384));
  if (j.contains("spp")) rs.spp = int(r.integer(j["spp"], child(p, "spp"), 1, 1 << 24));
  if (j.contains("seed")) rs.seed = r.unsigned_integer(j["seed"], child(p, "seed"));
  if (j.contains("max_depth")) rs.max_depth = int(r.integer(j["max_depth"], child(p, "max_depth"), 0, 1024));
  if (j.contains("filter")) read_filter(j["filter"], child(p, "filter"));
  if (j.contains("accel")) {
    const std::string a = r.string(j["accel"], child(p, "accel"));
    AccelKind kind;
    if (!parse_accel(a, kind)) r.fail(child(p, "accel"), "unknown accel \"" + a + "\" (known: bvh, embree)");
    bool fell_back = false;
    rs.accel = choose_accel(kind, &fell_back);
    if (fell_back) r.warn(child(p, "accel"), "this build has no Embree: our BVH casts the rays", out.warnings);
  }
  if (j.contains("light_sampler")) {
    const std::string name = r.string(j["light_sampler"], child(p, "light_sampler"));
    if (!parse_light_sampler(name, rs.light_sampler)) {
      r.fail(child(p, "light_sampler"), "unknown light_sampler \"" + name + "\" (known: tree, power)");
    }
  }
  if (j.contains("crop")) {
    const json& c = j["crop"];
    const std::string cp = child(p, "crop");
    if (!c.is_array() || c.size() != 4) r.fail(cp, "expected [x, y, width, height] in pixels of the film");
    for (size_t i = 0; i < 4; ++i) crop_[i] = int(r.integer(c[i], child(cp, i), i < 2 ? 0 : 1, 16384));
    if (crop_[0] + crop_[2] > rs.width || crop_[1] + crop_[3] > rs.height) {
      r.fail(cp, "the crop window reaches outside the " + std::to_string(rs.width) + "x" + std::to_string(rs.height) + " film");
    }
  }
}

void Loader::apply_overrides() {
  RenderSettings& rs = scene().render;
  if (overrides.width || overrides.height) {
    rs.width = overrides.width.value_or(rs.width);
    rs.height = overrides.height.value_or(rs.height);
    crop_[2] = crop_[3] = 0;
  }
  if (overrides.spp) rs.spp = *overrides.spp;
  if (overrides.seed) rs.seed = *overrides.seed;
  if (overrides.max_depth) rs.max_depth = *overrides.max_depth;
  if (overrides.accel) rs.accel = choose_accel(overrides.accel);
  if (overrides.light_sampler) rs.light_sampler = *overrides.light_sampler;
}

void Loader::read_filter(const json& j, const std::string& p) {
  PixelFilter& f = scene().render.filter;
  static const char* kKnown = "box, gaussian, tent, mitchell, catmullrom, lanczos";
  auto number_or = [&](const char* key, double fallback, double lo, double hi) {
    return j.is_object() && j.contains(key) ? r.number_in(j[key], child(p, key), lo, hi) : fallback;
  };
  std::string t;
  if (j.is_string()) {
    t = r.string(j, p);
  } else {
    t = r.string(r.require(j, p, "type"), child(p, "type"));
  }
  const std::string where = j.is_string() ? p : child(p, "type");
  if (t == "box") {
    if (j.is_object()) r.check_object(j, p, {"type"});
    f = PixelFilter::box();
  } else if (t == "gaussian") {
    if (j.is_object()) r.check_object(j, p, {"type", "stddev"});
    f = PixelFilter::gaussian(float(number_or("stddev", 0.5, 0.05, 16.0)));
  } else if (t == "tent") {
    if (j.is_object()) r.check_object(j, p, {"type", "radius"});
    f = PixelFilter::tent(float(number_or("radius", 1.0, 0.05, 16.0)));
  } else if (t == "mitchell") {
    if (j.is_object()) r.check_object(j, p, {"type", "B", "C"});
    f = PixelFilter::mitchell(float(number_or("B", 1.0 / 3.0, -2.0, 2.0)), float(number_or("C", 1.0 / 3.0, -2.0, 2.0)));
  } else if (t == "catmullrom") {
    if (j.is_object()) r.check_object(j, p, {"type"});
    f = PixelFilter::mitchell(0.0f, 0.5f, "catmullrom");
  } else if (t == "lanczos") {
    if (j.is_object()) r.check_object(j, p, {"type", "lobes"});
    f = PixelFilter::lanczos(int(j.is_object() && j.contains("lobes") ? r.integer(j["lobes"], child(p, "lobes"), 1, 16) : 3));
  } else {
    r.fail(where, "unknown filter \"" + t + "\" (known: " + kKnown + ")");
  }
}

void Loader::read_camera(const json& j, const std::string& p) {
  r.check_object(j, p, {"type", "position", "look_at", "up", "fov", "fov_axis", "mirror", "aperture_radius", "focus_distance",
                        "view_width", "view_height", "medium"});
  const std::string type = j.contains("type") ? r.string(j["type"], child(p, "type")) : "perspective";
  if (type != "perspective" && type != "orthographic") {
    r.fail(child(p, "type"), "unknown camera type \"" + type + "\" (known: perspective, orthographic)");
  }
  const bool ortho = type == "orthographic";
  for (const char* key : {"fov", "fov_axis", "aperture_radius", "focus_distance"}) {
    if (ortho && j.contains(key)) r.fail(child(p, key), std::string(key) + " does not apply to an orthographic camera");
  }
  for (const char* key : {"view_width", "view_height"}) {
    if (!ortho && j.contains(key)) r.fail(child(p, key), std::string(key) + " applies to an orthographic camera only (\"type\": \"orthographic\")");
  }
  const Vec3 pos = r.point(r.require(j, p, "position"), child(p, "position"));
  const Vec3 at = r.point(r.require(j, p, "look_at"), child(p, "look_at"));
  const Vec3 up = scaled_to_unit_max(j.contains("up") ? r.vec3(j["up"], child(p, "up")) : Vec3(0, 1, 0));
  const float fov = j.contains("fov") ? float(r.number_in(j["fov"], child(p, "fov"), 0.1, 179.0)) : 45.0f;
  if (glm::length(at - pos) <= 0.0f) r.fail(child(p, "look_at"), "look_at equals position");
  if (glm::length(glm::cross(glm::normalize(at - pos), up)) < 1e-6f) {
    r.fail(child(p, "up"), "up is parallel to the viewing direction (or zero)");
  }
  RenderSettings& rs = scene().render;
  Camera& camera = scene().camera;
  camera = Camera(pos, at, up, fov, rs.width, rs.height);
  if (j.contains("fov_axis")) {
    static const std::map<std::string, FovAxis> axes = {{"x", FovAxis::X}, {"y", FovAxis::Y}, {"smaller", FovAxis::Smaller},
                                                        {"larger", FovAxis::Larger}, {"diagonal", FovAxis::Diagonal}};
    const std::string a = r.string(j["fov_axis"], child(p, "fov_axis"));
    const auto it = axes.find(a);
    if (it == axes.end()) r.fail(child(p, "fov_axis"), "unknown fov_axis \"" + a + "\" (known: x, y, smaller, larger, diagonal)");
    camera.set_fov(fov, it->second);
  }
  if (j.contains("mirror")) camera.set_mirror(r.boolean(j["mirror"], child(p, "mirror")));
  if (ortho) {
    const double vw = r.number_in(r.require(j, p, "view_width"), child(p, "view_width"), 0.0, kMaxCoordinate);
    const double vh = j.contains("view_height") ? r.number_in(j["view_height"], child(p, "view_height"), 0.0, kMaxCoordinate) : 0.0;
    if (!(float(vw) > 0.0f)) r.fail(child(p, "view_width"), "view_width must be positive");
    if (j.contains("view_height") && !(float(vh) > 0.0f)) r.fail(child(p, "view_height"), "view_height must be positive");
    camera.set_orthographic(float(vw), float(vh));
  }
  if (j.contains("aperture_radius") || j.contains("focus_distance")) {
    const float radius = float(r.number_in(r.require(j, p, "aperture_radius"), child(p, "aperture_radius"), 0.0, kMaxCoordinate));
    const double focus = r.number_in(r.require(j, p, "focus_distance"), child(p, "focus_distance"), 0.0, kMaxCoordinate);
    if (!(float(focus) > 0.0f)) r.fail(child(p, "focus_distance"), "focus_distance must be positive");
    camera.set_lens(radius, float(focus));
  }
  if (crop_[2] > 0) {
    camera.set_crop(crop_[0], crop_[1], crop_[2], crop_[3]);
    rs.width = crop_[2];
    rs.height = crop_[3];
  }
}

}  // namespace caustica::scene_loading
