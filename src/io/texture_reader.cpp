// Texture blocks with Mitsuba 3's names: bitmap (filename, filter_type, wrap_mode, raw,
// to_uv) and checkerboard (color0, color1, to_uv).
#include "io/texture_reader.h"
#include <filesystem>
#include "core/textures/bitmap.h"

namespace caustica {
namespace {
namespace fs = std::filesystem;
using nlohmann::json;

// to_uv: {"scale": s or [su, sv], "rotate": degrees, "translate": [tu, tv]}, applied in that order,
// or a 2D affine matrix [[a, b, tu], [c, d, tv]] (u' = a u + b v + tu, v' = c u + d v + tv).
UvTransform read_to_uv(const JsonReader& r, const json& j, const std::string& p) {
  if (j.is_array()) {
    if (j.size() != 2) r.fail(p, "expected {\"scale\", \"rotate\", \"translate\"} or 2 rows [[a, b, tu], [c, d, tv]]");
    float m[2][3];
    for (size_t row = 0; row < 2; ++row) {
      if (!j[row].is_array() || j[row].size() != 3) r.fail(child(p, row), "expected a row of 3 numbers");
      for (size_t col = 0; col < 3; ++col) m[row][col] = float(r.number(j[row][col], child(child(p, row), col)));
    }
    return UvTransform{m[0][0], m[0][1], m[1][0], m[1][1], m[0][2], m[1][2]};
  }
  r.check_object(j, p, {"scale", "rotate", "translate"});
  Vec2 scale(1.0f), translate(0.0f);
  if (j.contains("scale")) {
    const std::string sp = child(p, "scale");
    if (j["scale"].is_number()) {
      scale = Vec2(float(r.number(j["scale"], sp)));
    } else {
      scale = r.vec2(j["scale"], sp, "a number or [su, sv]");
    }
  }
  if (j.contains("translate")) translate = r.vec2(j["translate"], child(p, "translate"), "[tu, tv]");
  const float a = j.contains("rotate") ? float(r.number(j["rotate"], child(p, "rotate"))) * kPi / 180.0f : 0.0f;
  const float c = std::cos(a), s = std::sin(a);
  UvTransform t;
  t.m00 = c * scale.x;
  t.m01 = -s * scale.y;
  t.m10 = s * scale.x;
  t.m11 = c * scale.y;
  t.tx = translate.x;
  t.ty = translate.y;
  return t;
}
}  // namespace

std::unique_ptr<Texture> read_texture(const MaterialContext& ctx, const json& t, const std::string& p) {
  const JsonReader& r = ctx.r;
  const std::string type = r.string(r.require(t, p, "type"), child(p, "type"));
  const UvTransform to_uv = t.contains("to_uv") ? read_to_uv(r, t["to_uv"], child(p, "to_uv")) : UvTransform{};
  if (type == "checkerboard") {
    r.check_object(t, p, {"type", "color0", "color1", "to_uv"});
    const Color c0 = t.contains("color0") ? r.color(t["color0"], child(p, "color0")) : Color(0.4f);
    const Color c1 = t.contains("color1") ? r.color(t["color1"], child(p, "color1")) : Color(0.2f);
    return std::make_unique<CheckerboardTexture>(c0, c1, to_uv);
  }
  if (type == "bitmap") {
    r.check_object(t, p, {"type", "filename", "filter_type", "wrap_mode", "raw", "to_uv"});
    const std::string file = r.string(r.require(t, p, "filename"), child(p, "filename"));
    const fs::path path = fs::path(file).is_absolute() ? fs::path(file) : fs::path(ctx.base_dir) / file;
    std::error_code ec;
    if (!fs::exists(path, ec)) r.fail(child(p, "filename"), "texture file not found: tried " + path.string());
    if (!fs::is_regular_file(path, ec)) r.fail(child(p, "filename"), "texture path is not a regular file: " + path.string());
    TextureFilter filter = TextureFilter::Bilinear;
    if (t.contains("filter_type")) {
      const std::string f = r.string(t["filter_type"], child(p, "filter_type"));
      if (f == "nearest") filter = TextureFilter::Nearest;
      else if (f != "bilinear") r.fail(child(p, "filter_type"), "unknown filter_type \"" + f + "\" (known: bilinear, nearest)");
    }
    TextureWrap wrap = TextureWrap::Repeat;
    if (t.contains("wrap_mode")) {
      const std::string w = r.string(t["wrap_mode"], child(p, "wrap_mode"));
      if (w == "mirror") wrap = TextureWrap::Mirror;
      else if (w == "clamp") wrap = TextureWrap::Clamp;
      else if (w != "repeat") r.fail(child(p, "wrap_mode"), "unknown wrap_mode \"" + w + "\" (known: repeat, mirror, clamp)");
    }
    const bool raw = t.contains("raw") && r.boolean(t["raw"], child(p, "raw"));
    try {
      return std::make_unique<BitmapTexture>(path.string(), filter, wrap, to_uv, raw);
    } catch (const InputError& e) {
      r.fail(child(p, "filename"), e.what());
    }
  }
  r.fail(child(p, "type"), "unknown texture type \"" + type + "\" (known: bitmap, checkerboard)");
}

}  // namespace caustica
