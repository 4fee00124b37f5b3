// Mitsuba's `bitmap` texture: an image file read and filtered through OpenImageIO's
// TextureSystem (tiled, cached, MIP-mapped on demand), shared by every bitmap of a process.
#pragma once
#include <memory>
#include <string>
#include "core/params.h"
#include "core/textures/texture.h"

namespace caustica {

enum class TextureFilter { Nearest, Bilinear };
enum class TextureWrap { Repeat, Mirror, Clamp };

class BitmapTexture final : public Texture {
 public:
  // Throws InputError when OpenImageIO cannot open the file. `raw`: the pixels are linear
  // data; otherwise 8-bit images are sRGB-decoded (Mitsuba's default for colour textures).
  BitmapTexture(const std::string& path, TextureFilter filter, TextureWrap wrap, const UvTransform& to_uv, bool raw);
  // filename, filter_type (bilinear, nearest), wrap_mode (repeat, mirror, clamp), raw, to_uv.
  static std::unique_ptr<Texture> create(const Params& p);
  Color eval(const Vec2& uv) const override;
  int channels() const override { return channels_; }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  std::string path_;
  void* handle_ = nullptr;  // OIIO::TextureSystem::TextureHandle
  TextureFilter filter_;
  TextureWrap wrap_;
  UvTransform to_uv_;
  bool srgb_ = false;
  int width_ = 0, height_ = 0, channels_ = 3;  // colour channels, alpha not counted
};

}  // namespace caustica
