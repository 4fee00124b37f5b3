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
  Color eval(const TexturePoint& p) const override;
  int channels() const override { return channels_; }
  // The exact derivative of the bilinear lookup (Mitsuba's eval_1_grad), through to_uv; zero
  // for nearest lookups, which are constant between texels.
  bool gradient(const Vec2& uv, Vec2& grad) const override;
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  // The linear colour at uv (through to_uv), and with ds and dt its derivatives along the
  // image's s and t axes; false when OpenImageIO fails.
  bool lookup(const Vec2& st, TextureFilter filter, Color& c, Color* ds, Color* dt) const;
  std::string path_;
  void* handle_ = nullptr;  // OIIO::TextureSystem::TextureHandle
  TextureFilter filter_;
  TextureWrap wrap_;
  UvTransform to_uv_;
  bool srgb_ = false;
  int width_ = 0, height_ = 0, channels_ = 3;  // colour channels, alpha not counted
};

}  // namespace caustica
