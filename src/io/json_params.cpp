// A plugin's JSON block as core's Params.
#include "io/json_params.h"
#include <filesystem>
#include "core/media/registry.h"
#include "io/bsdf_reader.h"
#include "io/volume_io.h"
#include "io/image_io.h"
#include "io/texture_reader.h"

namespace caustica {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {
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

// A rotation given as a 3x3 or 4x4 row-major matrix (the translation of a 4x4 is ignored).
glm::mat3 read_rotation(const JsonReader& r, const json& m, const std::string& p) {
  if (!m.is_array() || (m.size() != 3 && m.size() != 4)) r.fail(p, "expected a 3x3 or 4x4 matrix (an array of rows)");
  glm::mat3 out(1.0f);
  for (size_t row = 0; row < 3; ++row) {
    const json& rw = m[row];
    if (!rw.is_array() || rw.size() != m.size()) r.fail(child(p, row), "expected a row of " + std::to_string(m.size()) + " numbers");
    for (size_t col = 0; col < 3; ++col) out[int(col)][int(row)] = float(r.number(rw[col], child(child(p, row), col)));
  }
  const glm::mat3 check = glm::transpose(out) * out;
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b) {
      if (std::abs(check[a][b] - (a == b ? 1.0f : 0.0f)) > 1e-3f) r.fail(p, "to_world must be a rotation (orthonormal)");
    }
  }
  return out;
}
}  // namespace

double JsonParams::number(const std::string& key, double fallback) const {
  return has(key) ? r_.number(m_[key], at(key)) : fallback;
}

double JsonParams::number_in(const std::string& key, double fallback, double lo, double hi) const {
  return has(key) ? r_.number_in(m_[key], at(key), lo, hi) : fallback;
}

int64_t JsonParams::integer(const std::string& key, int64_t fallback, int64_t lo, int64_t hi) const {
  return has(key) ? r_.integer(m_[key], at(key), lo, hi) : fallback;
}

bool JsonParams::boolean(const std::string& key, bool fallback) const {
  return has(key) ? r_.boolean(m_[key], at(key)) : fallback;
}

std::string JsonParams::string(const std::string& key, const std::string& fallback) const {
  return has(key) ? r_.string(m_[key], at(key)) : fallback;
}

Color JsonParams::color(const std::string& key, const Color& fallback) const {
  return has(key) ? r_.color(m_[key], at(key)) : fallback;
}

Color JsonParams::color(const std::string& key) const { return r_.color(r_.require(m_, p_, key.c_str()), at(key)); }

Vec3 JsonParams::vec3(const std::string& key) const { return r_.vec3(r_.require(m_, p_, key.c_str()), at(key)); }
Vec3 JsonParams::point(const std::string& key) const { return r_.point(r_.require(m_, p_, key.c_str()), at(key)); }

Image JsonParams::image(const std::string& key, const std::string& what) const {
  const std::string path = file(key, what);
  try {
    return read_image(path);
  } catch (const std::exception& e) {
    r_.fail(at(key), "cannot read the " + what + ": " + e.what());
  }
}

glm::mat3 JsonParams::rotation(const std::string& key) const {
  return has(key) ? read_rotation(r_, m_[key], at(key)) : glm::mat3(1.0f);
}

glm::mat4 read_affine(const JsonReader& r, const json& m, const std::string& p) {
  if (!m.is_array() || (m.size() != 3 && m.size() != 4)) r.fail(p, "expected a 4x4 matrix (an array of 4 rows of 4 numbers)");
  glm::mat4 out(1.0f);
  for (size_t row = 0; row < m.size(); ++row) {
    const json& rw = m[row];
    if (!rw.is_array() || rw.size() != 4) r.fail(child(p, row), "expected a row of 4 numbers");
    for (size_t col = 0; col < 4; ++col) out[int(col)][int(row)] = float(r.number(rw[col], child(child(p, row), col)));
  }
  if (out[0][3] != 0.0f || out[1][3] != 0.0f || out[2][3] != 0.0f || out[3][3] != 1.0f) {
    r.fail(p, "the last row must be [0, 0, 0, 1] (projective transforms are not supported)");
  }
  // Singular relative to the columns' lengths, so that small (and large) scales are fine.
  const glm::mat3 l(out);
  const float scale = glm::length(l[0]) * glm::length(l[1]) * glm::length(l[2]);
  if (!(std::abs(glm::determinant(l)) > 1e-6f * scale)) r.fail(p, "the transform is singular (it flattens the shape)");
  return out;
}

glm::mat4 JsonParams::affine(const std::string& key) const {
  return has(key) ? read_affine(r_, m_[key], at(key)) : glm::mat4(1.0f);
}

ColorParam JsonParams::texture(const std::string& key, const Color& fallback) const {
  if (!has(key)) return fallback;
  if (!m_[key].is_object()) return r_.color(m_[key], at(key));
  ctx_.textures.push_back(read_texture(ctx_, m_[key], at(key)));
  if (ctx_.texture_places) (*ctx_.texture_places)[ctx_.textures.back().get()] = at(key);
  return ColorParam(ctx_.textures.back().get());
}

std::string JsonParams::file(const std::string& key, const std::string& what) const {
  return r_.input_file(r_.require(m_, p_, key.c_str()), at(key), ctx_.base_dir, what);
}

UvTransform JsonParams::uv_transform(const std::string& key) const {
  return has(key) ? read_to_uv(r_, m_[key], at(key)) : UvTransform{};
}

std::vector<const Bsdf*> JsonParams::bsdfs(const std::string& key, bool allow_pair) const {
  const json& inner = r_.require(m_, p_, key.c_str());
  const std::string ip = at(key);
  std::vector<json const*> blocks;
  std::vector<std::string> pointers;
  if (allow_pair && inner.is_array()) {
    if (inner.size() != 1 && inner.size() != 2) r_.fail(ip, "expected one BSDF, or two (front and back)");
    for (size_t i = 0; i < inner.size(); ++i) blocks.push_back(&inner[i]), pointers.push_back(child(ip, i));
  } else {
    blocks.push_back(&inner), pointers.push_back(ip);
  }
  std::vector<const Bsdf*> out;
  for (size_t i = 0; i < blocks.size(); ++i) {
    std::unique_ptr<Bsdf> b = read_bsdf(ctx_, *blocks[i], pointers[i], true);
    ctx_.nested.push_back(std::move(b));
    out.push_back(ctx_.nested.back().get());
  }
  return out;
}

std::unique_ptr<PhaseFunction> JsonParams::phase(const std::string& key) const {
  if (!has(key)) return std::make_unique<IsotropicPhase>();
  const std::string ip = at(key);
  const PhasePlugin& row = plugin_row(r_, m_[key], ip, phase_plugins(), "phase function");
  return row.create(JsonParams(ctx_, m_[key], ip));
}

std::unique_ptr<Volume> JsonParams::volume(const std::string& key, const Color& fallback) const {
  if (!has(key)) return std::make_unique<ConstVolume>(fallback);
  const std::string ip = at(key);
  if (!m_[key].is_object()) return std::make_unique<ConstVolume>(r_.color(m_[key], ip));
  const VolumePlugin& row = plugin_row(r_, m_[key], ip, volume_plugins(), "volume");
  return row.create(JsonParams(ctx_, m_[key], ip));
}

VolumeGrid JsonParams::volume_grid(const std::string& key) const {
  const std::string path = file(key, "grid volume file");
  try {
    return read_grid_file(path, string("grid", ""));
  } catch (const std::exception& e) {
    r_.fail(at(key), e.what());
  }
}

void JsonParams::fail(const std::string& key, const std::string& message) const {
  r_.fail(key.empty() ? p_ : at(key), message);
}

void JsonParams::warn(const std::string& key, const std::string& message) const {
  r_.warn(key.empty() ? p_ : at(key), message, ctx_.warnings);
}

}  // namespace caustica
