// Mitsuba's `bitmap` texture: an image file (any format OpenImageIO reads) decoded once at load
// into linear texels, looked up nearest or bilinear on the base level with Mitsuba's wrap
// modes, as Mitsuba's bitmap does (no MIP levels).
#pragma once
#include <memory>
#include <string>
#include <vector>
#include "core/params.h"
#include "core/textures/texture.h"

namespace caustica {

enum class TextureFilter { Nearest, Bilinear };
enum class TextureWrap { Repeat, Mirror, Clamp };

class BitmapTexture final : public Texture {
 public:
  // Throws InputError when OpenImageIO cannot read the file, or a texel is not finite or
  // beyond kMaxColor. `raw`: the pixels are linear data; otherwise 8- and 16-bit images are
  // sRGB-decoded (Mitsuba's default for colour textures).
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
  struct Texels;
  // Whether two bitmaps share one decoded image (bitmaps of one file do).
  bool shares_texels_with(const BitmapTexture& other) const { return texels_ == other.texels_; }

 private:
  // The linear colour at image coordinates st (after to_uv), and with ds and dt its
  // derivatives along the image's s and t axes.
  void lookup(const Vec2& st, Color& c, Color* ds, Color* dt) const;
  // The texel at (x, y), wrapped.
  Color texel(int x, int y) const;
  std::string path_;
  std::shared_ptr<const Texels> texels_;  // decoded once, shared by the bitmaps of one file
  int stored_ = 3;                        // the colour channels kept (at most 3)
  TextureFilter filter_;
  TextureWrap wrap_;
  UvTransform to_uv_;
  int width_ = 0, height_ = 0, channels_ = 3;  // colour channels, alpha not counted
};

}  // namespace caustica
