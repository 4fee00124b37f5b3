// Bitmap textures: read through OpenImageIO once, filtered here.
#include "core/textures/bitmap.h"
#include <OpenImageIO/imageio.h>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <mutex>
#include "core/error.h"
#include "core/image.h"
#include "core/memory.h"

namespace caustica {
namespace {

// A texel index along an axis of n texels, by the wrap mode (Mitsuba's: mirror reflects
// every other period).
int wrap_index(int i, int n, TextureWrap wrap) {
  switch (wrap) {
    case TextureWrap::Clamp:
      return std::clamp(i, 0, n - 1);
    case TextureWrap::Mirror: {
      int m = i % (2 * n);
      if (m < 0) m += 2 * n;
      return m < n ? m : 2 * n - 1 - m;
    }
    case TextureWrap::Repeat:
    default: {
      const int m = i % n;
      return m < 0 ? m + n : m;
    }
  }
}

// A texture coordinate times the resolution, as an int-safe value: coordinates far outside
// [0, 1] wrap (or clamp) the same way, and NaN becomes 0.
double texel_coordinate(float st, int n, TextureWrap wrap) {
  const double x = double(st) * double(n);
  if (!std::isfinite(x)) return 0.0;
  if (wrap == TextureWrap::Clamp) return std::clamp(x, -1.0, double(n) + 1.0);
  // Beyond 2^30 texels the position is kept within one period of 2n (mirror's period).
  constexpr double kLimit = 1073741824.0;
  return std::abs(x) < kLimit ? x : std::fmod(x, 2.0 * double(n));
}

}  // namespace

// The decoded image: linear texels, row by row from the top, `stored` channels each.
struct BitmapTexture::Texels {
  int width = 0, height = 0, channels = 0, stored = 0;
  std::vector<float> data;
};

namespace {

std::shared_ptr<const BitmapTexture::Texels> decode_texels(const std::string& path, bool raw) {
  // Colour as stored, not multiplied by alpha (which OpenImageIO does to PNGs by default):
  // Mitsuba drops the alpha channel of a texture and keeps the colour as it is.
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  auto in = OIIO::ImageInput::open(path, &config);
  if (!in) throw InputError(path + ": cannot read the texture: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  auto t = std::make_shared<BitmapTexture::Texels>();
  t->width = spec.width;
  t->height = spec.height;
  // The colour channels: all but alpha, as Mitsuba's bitmap (grey-alpha is grey, RGBA is RGB).
  t->channels = spec.nchannels - (spec.alpha_channel >= 0 && spec.nchannels > 1 ? 1 : 0);
  if (t->width <= 0 || t->height <= 0 || t->channels <= 0) throw InputError(path + ": the texture has no pixels");
  if (t->width > (1 << 30) || t->height > (1 << 30)) throw InputError(path + ": the texture is wider or taller than 2^30 texels");
  if (spec.alpha_channel >= 0 && spec.alpha_channel < t->channels) {
    throw InputError(path + ": the texture's alpha channel comes before its colour channels");
  }
  t->stored = std::min(t->channels, 3);
  const double texels = double(t->width) * double(t->height);
  check_memory(texels * t->stored * sizeof(float),
               path + " (" + std::to_string(t->width) + " x " + std::to_string(t->height) + " texels)");
  // Decoded once, here: a file that does not decode, or holds NaN, infinite or too bright
  // texels, is an error at load; lookups read memory and never the file again.
  t->data.resize(size_t(texels) * size_t(t->stored));
  if (!in->read_image(0, 0, 0, t->stored, OIIO::TypeDesc::FLOAT, t->data.data())) {
    throw InputError(path + ": cannot decode the texture: " + in->geterror());
  }
  // 8- and 16-bit images hold display-referred sRGB values unless declared raw; they are
  // decoded to linear here, so that filtering interpolates linear values, as Mitsuba's does.
  const bool srgb = !raw && (spec.format == OIIO::TypeDesc::UINT8 || spec.format == OIIO::TypeDesc::UINT16);
  for (size_t i = 0; i < t->data.size(); ++i) {
    float& v = t->data[i];
    if (!std::isfinite(v) || std::abs(v) > kMaxColor) {
      const size_t texel = i / size_t(t->stored);
      const std::string at =
          "(" + std::to_string(texel % size_t(t->width)) + ", " + std::to_string(texel / size_t(t->width)) + ")";
      if (!std::isfinite(v)) throw InputError(path + ": NaN or infinite texel at " + at);
      throw InputError(path + ": the texel at " + at + " is " + format_number(v) + ", beyond the " +
                       format_number(kMaxColor) + " a colour may hold");
    }
    if (srgb) v = srgb_to_linear(v);
  }
  return t;
}

// Bitmaps of one file share its texels while any of them lives (an OBJ's materials often name
// one texture atlas): keyed by the path, raw, and the file's size and time, so that a file
// rewritten between loads is read again.
std::shared_ptr<const BitmapTexture::Texels> shared_texels(const std::string& path, bool raw) {
  static std::mutex mutex;
  static std::map<std::string, std::weak_ptr<const BitmapTexture::Texels>> cache;
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  const auto time = std::filesystem::last_write_time(path, ec).time_since_epoch().count();
  const std::string key = path + '\n' + (raw ? "raw" : "srgb") + '\n' + std::to_string(size) + '\n' + std::to_string(time);
  std::lock_guard<std::mutex> lock(mutex);
  if (auto t = cache[key].lock()) return t;
  auto t = decode_texels(path, raw);
  cache[key] = t;
  return t;
}

}  // namespace

BitmapTexture::BitmapTexture(const std::string& path, TextureFilter filter, TextureWrap wrap, const UvTransform& to_uv,
                             bool raw)
    : path_(path), texels_(shared_texels(path, raw)), filter_(filter), wrap_(wrap), to_uv_(to_uv) {
  width_ = texels_->width;
  height_ = texels_->height;
  channels_ = texels_->channels;
  stored_ = texels_->stored;
}

Color BitmapTexture::texel(int x, int y) const {
  const float* t = &texels_->data[(size_t(wrap_index(y, height_, wrap_)) * size_t(width_) + size_t(wrap_index(x, width_, wrap_))) *
                            size_t(stored_)];
  return stored_ == 1 ? Color(t[0]) : stored_ == 2 ? Color(t[0], t[1], 0.0f) : Color(t[0], t[1], t[2]);
}

void BitmapTexture::lookup(const Vec2& st, Color& c, Color* ds, Color* dt) const {
  const double x = texel_coordinate(st.x, width_, wrap_), y = texel_coordinate(st.y, height_, wrap_);
  if (filter_ == TextureFilter::Nearest) {
    c = texel(int(std::floor(x)), int(std::floor(y)));
    if (ds) *ds = *dt = Color(0.0f);
    return;
  }
  // Texel centres at (i + 1/2) / n.
  const double fx0 = std::floor(x - 0.5), fy0 = std::floor(y - 0.5);
  const float fx = float(x - 0.5 - fx0), fy = float(y - 0.5 - fy0);
  const int x0 = int(fx0), y0 = int(fy0);
  const Color c00 = texel(x0, y0), c10 = texel(x0 + 1, y0), c01 = texel(x0, y0 + 1), c11 = texel(x0 + 1, y0 + 1);
  c = (1.0f - fy) * ((1.0f - fx) * c00 + fx * c10) + fy * ((1.0f - fx) * c01 + fx * c11);
  if (ds) {
    *ds = float(width_) * ((1.0f - fy) * (c10 - c00) + fy * (c11 - c01));
    *dt = float(height_) * ((1.0f - fx) * (c01 - c00) + fx * (c11 - c10));
  }
}

Color BitmapTexture::eval(const TexturePoint& p) const {
  Color c(0.0f);
  lookup(to_uv_.apply(p.uv), c, nullptr, nullptr);
  return c;
}

bool BitmapTexture::gradient(const Vec2& uv, Vec2& grad) const {
  grad = Vec2(0.0f);
  if (filter_ == TextureFilter::Nearest) return true;
  Color c(0.0f), ds(0.0f), dt(0.0f);
  lookup(to_uv_.apply(uv), c, &ds, &dt);
  const float gs = luminance(ds), gt = luminance(dt);
  // s = m00 u + m01 v + tx, t = m10 u + m11 v + ty.
  grad = Vec2(to_uv_.m00 * gs + to_uv_.m10 * gt, to_uv_.m01 * gs + to_uv_.m11 * gt);
  return true;
}

std::unique_ptr<Texture> BitmapTexture::create(const Params& p) {
  const std::string path = p.file("filename", "texture file");
  TextureFilter filter = TextureFilter::Bilinear;
  const std::string f = p.string("filter_type", "bilinear");
  if (f == "nearest") filter = TextureFilter::Nearest;
  else if (f != "bilinear") p.fail("filter_type", "unknown filter_type \"" + f + "\" (known: bilinear, nearest)");
  TextureWrap wrap = TextureWrap::Repeat;
  const std::string w = p.string("wrap_mode", "repeat");
  if (w == "mirror") wrap = TextureWrap::Mirror;
  else if (w == "clamp") wrap = TextureWrap::Clamp;
  else if (w != "repeat") p.fail("wrap_mode", "unknown wrap_mode \"" + w + "\" (known: repeat, mirror, clamp)");
  const bool raw = p.boolean("raw", false);
  const UvTransform to_uv = p.uv_transform("to_uv");
  try {
    return std::make_unique<BitmapTexture>(path, filter, wrap, to_uv, raw);
  } catch (const InputError& e) {
    p.fail("filename", e.what());
  }
  return nullptr;  // not reached: fail() throws
}

}  // namespace caustica
