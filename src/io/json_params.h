// A plugin's JSON block as core's Params (core/params.h), and the check of a block against its
// family's registry row: every error names the file and the JSON pointer.
#pragma once
#include <map>
#include <memory>
#include <string>
#include <vector>
#include <nlohmann/json.hpp>
#include "core/bsdf/bsdf.h"
#include "core/params.h"
#include "core/registry.h"
#include "core/textures/texture.h"
#include "io/json_reader.h"

namespace caustica {

// What reading a plugin needs besides its block: BSDFs nested inside another (twosided's `bsdf`)
// and textures go to `nested` and `textures`, which the scene keeps alive; files are found
// relative to `base_dir`; warnings (e.g. energy-creating albedos) go to `warnings`.
struct PluginContext {
  const JsonReader& r;
  std::string base_dir;
  std::vector<std::unique_ptr<Bsdf>>& nested;
  std::vector<std::unique_ptr<Texture>>& textures;
  std::vector<std::string>& warnings;
  // Where each texture block was read (for errors found after reading), when given.
  std::map<const Texture*, std::string>* texture_places = nullptr;
};

// An affine transform as 3 or 4 rows of 4 numbers (the last row, if given, must be 0 0 0 1),
// not singular.
glm::mat4 read_affine(const JsonReader& r, const nlohmann::json& m, const std::string& p);

class JsonParams final : public Params {
 public:
  JsonParams(const PluginContext& ctx, const nlohmann::json& m, const std::string& p) : ctx_(ctx), r_(ctx.r), m_(m), p_(p) {}
  bool has(const std::string& key) const override { return m_.contains(key); }
  bool is_string(const std::string& key) const override { return has(key) && m_[key].is_string(); }
  double number(const std::string& key, double fallback) const override;
  double number_in(const std::string& key, double fallback, double lo, double hi) const override;
  int64_t integer(const std::string& key, int64_t fallback, int64_t lo, int64_t hi) const override;
  bool boolean(const std::string& key, bool fallback) const override;
  std::string string(const std::string& key, const std::string& fallback) const override;
  Color color(const std::string& key, const Color& fallback) const override;
  Color color(const std::string& key) const override;
  Vec3 vec3(const std::string& key) const override;
  Vec3 point(const std::string& key) const override;
  Image image(const std::string& key, const std::string& what) const override;
  glm::mat3 rotation(const std::string& key) const override;
  glm::mat4 affine(const std::string& key) const override;
  ColorParam texture(const std::string& key, const Color& fallback) const override;
  std::string file(const std::string& key, const std::string& what) const override;
  UvTransform uv_transform(const std::string& key) const override;
  std::vector<const Bsdf*> bsdfs(const std::string& key, bool allow_pair) const override;
  std::unique_ptr<PhaseFunction> phase(const std::string& key) const override;
  std::unique_ptr<Volume> volume(const std::string& key, const Color& fallback) const override;
  VolumeGrid volume_grid(const std::string& key) const override;
  [[noreturn]] void fail(const std::string& key, const std::string& message) const override;
  void warn(const std::string& key, const std::string& message) const override;

 private:
  std::string at(const std::string& key) const { return child(p_, key); }
  const PluginContext& ctx_;
  const JsonReader& r_;
  const nlohmann::json& m_;
  const std::string& p_;
};

// A block that stands alone, such as an integrator's settings (src.value at src.pointer), as
// Params: its own reader, no textures or nested BSDFs. `src` must outlive it.
class SourceParams {
 public:
  explicit SourceParams(const JsonSource& src)
      : reader_(src.file, src.sources), ctx_{reader_, ".", nested_, textures_, warnings_}, pointer_(src.pointer),
        params_(ctx_, src.value, pointer_) {}
  SourceParams(const SourceParams&) = delete;
  SourceParams& operator=(const SourceParams&) = delete;
  const JsonReader& reader() const { return reader_; }
  const Params& params() const { return params_; }

 private:
  JsonReader reader_;
  std::vector<std::unique_ptr<Bsdf>> nested_;
  std::vector<std::unique_ptr<Texture>> textures_;
  std::vector<std::string> warnings_;
  PluginContext ctx_;
  std::string pointer_;
  JsonParams params_;
};

// The registry row that block `m` (at pointer `p`) names by its "type", after checking that it
// is an object and has no key but "type", the row's keys and `extra`. An unknown type is an
// error listing the family's names (`family`: "material", "texture", ...; `note` follows the list).
template <class Plugin>
const Plugin& plugin_row(const JsonReader& r, const nlohmann::json& m, const std::string& p,
                         const std::vector<Plugin>& table, const std::string& family,
                         const std::vector<const char*>& extra = {}, const std::string& note = "") {
  if (!m.is_object()) r.fail(p, "expected an object");
  const std::string type = r.string(r.require(m, p, "type"), child(p, "type"));
  const Plugin* row = find_plugin(table, type);
  if (!row) r.fail(child(p, "type"), "unknown " + family + " type \"" + type + "\" (known: " + plugin_names(table) + note + ")");
  std::vector<const char*> keys = {"type"};
  keys.insert(keys.end(), row->keys.begin(), row->keys.end());
  keys.insert(keys.end(), extra.begin(), extra.end());
  r.check_object(m, p, keys);
  return *row;
}

}  // namespace caustica
