// A plugin's block of parameters as a scene reader hands it over. Each plugin reads its own
// values through it in its create() (pbrt-v4's ParameterDictionary, Mitsuba 3's Properties);
// the reader behind it (src/io) knows the file format, names the file and the place in every
// error, and has refused keys that the plugin's registry row does not list before create() runs.
#pragma once
#include <memory>
#include <string>
#include <vector>
#include "core/image.h"
#include "core/math.h"
#include "core/textures/texture.h"

namespace caustica {

class Bsdf;
class PhaseFunction;
class Volume;
struct VolumeGrid;

class Params {
 public:
  virtual ~Params() = default;
  virtual bool has(const std::string& key) const = 0;
  virtual bool is_string(const std::string& key) const = 0;
  // Each getter with a fallback returns it when the key is absent.
  virtual double number(const std::string& key, double fallback) const = 0;  // finite, fits a float
  virtual double number_in(const std::string& key, double fallback, double lo, double hi) const = 0;
  virtual int64_t integer(const std::string& key, int64_t fallback, int64_t lo, int64_t hi) const = 0;
  virtual bool boolean(const std::string& key, bool fallback) const = 0;
  virtual std::string string(const std::string& key, const std::string& fallback) const = 0;
  virtual Color color(const std::string& key, const Color& fallback) const = 0;  // non-negative
  virtual Color color(const std::string& key) const = 0;                         // required
  virtual Vec3 vec3(const std::string& key) const = 0;                           // required
  // A position (required), each coordinate within kMaxCoordinate of the origin's.
  virtual Vec3 point(const std::string& key) const = 0;
  // A colour or a texture block (the texture is kept alive by the scene).
  virtual ColorParam texture(const std::string& key, const Color& fallback) const = 0;
  // A file named by `key` (required), relative to the scene's folder; an error when it is not
  // there or not a regular file (`what` names it: "texture file").
  virtual std::string file(const std::string& key, const std::string& what) const = 0;
  // An image file named by `key` (required; `what` names it in errors: "environment map").
  virtual Image image(const std::string& key, const std::string& what) const = 0;
  // A rotation (3x3, or the rotation part of a 4x4; identity when absent).
  virtual glm::mat3 rotation(const std::string& key) const = 0;
  // An affine transform (4x4; identity when absent).
  virtual glm::mat4 affine(const std::string& key) const = 0;
  // Texture coordinates' transform (identity when absent).
  virtual UvTransform uv_transform(const std::string& key) const = 0;
  // Nested BSDF blocks (kept alive by the scene): one, or with `allow_pair` an array of one or
  // two (front and back). The key is required.
  virtual std::vector<const Bsdf*> bsdfs(const std::string& key, bool allow_pair) const = 0;
  // A nested phase-function block (a medium's); isotropic when the key is absent.
  virtual std::unique_ptr<PhaseFunction> phase(const std::string& key) const = 0;
  // A volume (a medium's coefficient): a number, a colour or a volume block; `fallback` when
  // the key is absent.
  virtual std::unique_ptr<Volume> volume(const std::string& key, const Color& fallback) const = 0;
  // A voxel grid file named by `key` (required): Mitsuba's binary .vol or an OpenVDB .vdb.
  virtual VolumeGrid volume_grid(const std::string& key) const = 0;
  // An error at `key` (empty: the block itself), naming the file and the place in it.
  [[noreturn]] virtual void fail(const std::string& key, const std::string& message) const = 0;
  virtual void warn(const std::string& key, const std::string& message) const = 0;
};

}  // namespace caustica
