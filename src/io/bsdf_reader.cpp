// BSDF blocks: the registry's row checks the keys, the plugin's create() reads the values
// through JsonParams, which names the file and the JSON pointer in every error.
#include "io/bsdf_reader.h"
#include "core/bsdf/registry.h"
#include "core/params.h"
#include "io/texture_reader.h"

namespace caustica {
namespace {
using nlohmann::json;

std::unique_ptr<Bsdf> read_block(const MaterialContext& ctx, const json& m, const std::string& p, bool nested);

class JsonParams final : public Params {
 public:
  JsonParams(const MaterialContext& ctx, const json& m, const std::string& p) : ctx_(ctx), r_(ctx.r), m_(m), p_(p) {}
  bool has(const std::string& key) const override { return m_.contains(key); }
  bool is_string(const std::string& key) const override { return has(key) && m_[key].is_string(); }
  double number(const std::string& key, double fallback) const override {
    return has(key) ? r_.number(m_[key], at(key)) : fallback;
  }
  double number_in(const std::string& key, double fallback, double lo, double hi) const override {
    return has(key) ? r_.number_in(m_[key], at(key), lo, hi) : fallback;
  }
  bool boolean(const std::string& key, bool fallback) const override {
    return has(key) ? r_.boolean(m_[key], at(key)) : fallback;
  }
  std::string string(const std::string& key, const std::string& fallback) const override {
    return has(key) ? r_.string(m_[key], at(key)) : fallback;
  }
  Color color(const std::string& key, const Color& fallback) const override {
    return has(key) ? r_.color(m_[key], at(key)) : fallback;
  }
  ColorParam texture(const std::string& key, const Color& fallback) const override {
    if (!has(key)) return fallback;
    if (!m_[key].is_object()) return r_.color(m_[key], at(key));
    ctx_.textures.push_back(read_texture(ctx_, m_[key], at(key)));
    return ColorParam(ctx_.textures.back().get());
  }
  std::vector<const Bsdf*> bsdfs(const std::string& key, bool allow_pair) const override {
    const json& inner = r_.require(m_, p_, key.c_str());
    const std::string ip = at(key);
    std::vector<const Bsdf*> out;
    if (allow_pair && inner.is_array()) {
      if (inner.size() != 1 && inner.size() != 2) r_.fail(ip, "expected one BSDF, or two (front and back)");
      for (size_t i = 0; i < inner.size(); ++i) out.push_back(keep(read_block(ctx_, inner[i], child(ip, i), true)));
    } else {
      out.push_back(keep(read_block(ctx_, inner, ip, true)));
    }
    return out;
  }
  [[noreturn]] void fail(const std::string& key, const std::string& message) const override {
    r_.fail(key.empty() ? p_ : at(key), message);
  }
  void warn(const std::string& key, const std::string& message) const override {
    r_.warn(key.empty() ? p_ : at(key), message, ctx_.warnings);
  }

 private:
  std::string at(const std::string& key) const { return child(p_, key); }
  const Bsdf* keep(std::unique_ptr<Bsdf> b) const {
    ctx_.nested.push_back(std::move(b));
    return ctx_.nested.back().get();
  }
  const MaterialContext& ctx_;
  const JsonReader& r_;
  const json& m_;
  const std::string& p_;
};

std::unique_ptr<Bsdf> read_block(const MaterialContext& ctx, const json& m, const std::string& p, bool nested) {
  const JsonReader& r = ctx.r;
  if (!m.is_object()) r.fail(p, "expected an object");
  const std::string type = r.string(r.require(m, p, "type"), child(p, "type"));
  const BsdfPlugin* plugin = find_bsdf_plugin(type);
  if (!plugin) r.fail(child(p, "type"), "unknown material type \"" + type + "\" (known: " + known_bsdfs() + ")");
  if (m.contains("emission")) {
    if (nested) r.fail(child(p, "emission"), "emission belongs on the outermost material, not inside it");
    if (!plugin->can_emit) r.fail(child(p, "emission"), "a " + type + " material cannot emit light");
  }
  std::vector<const char*> keys = {"type"};
  keys.insert(keys.end(), plugin->keys.begin(), plugin->keys.end());
  if (plugin->can_emit && !nested) keys.push_back("emission");
  r.check_object(m, p, keys);
  return plugin->create(JsonParams(ctx, m, p));
}

}  // namespace

std::unique_ptr<Bsdf> read_bsdf(const MaterialContext& ctx, const json& m, const std::string& p) {
  return read_block(ctx, m, p, false);
}

}  // namespace caustica
