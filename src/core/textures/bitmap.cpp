// Bitmap textures through OpenImageIO's TextureSystem.
#include "core/textures/bitmap.h"
#include <OpenImageIO/imageio.h>
#include <OpenImageIO/texture.h>
#include <algorithm>
#include <cmath>
#include <vector>
#include "core/image.h"
#include "core/error.h"

namespace caustica {
namespace {
OIIO::TextureSystem* texture_system() {
  static OIIO::TextureSystem* ts = [] {
    OIIO::TextureSystem* t = OIIO::TextureSystem::create(/*shared=*/true);
    t->attribute("automip", 1);         // untiled, un-MIP-mapped files are fine
    t->attribute("autotile", 64);
    t->attribute("max_memory_MB", 512.0f);
    // Colour as stored, not multiplied by alpha (which OpenImageIO does to PNGs by default):
    // Mitsuba drops the alpha channel of a texture and keeps the colour as it is.
    t->attribute("unassociatedalpha", 1);
    return t;
  }();
  return ts;
}

// Decodes the whole file once, a band of rows at a time (memory O(width)): a file that does not
// decode, or holds NaN or infinite texels, is an error here at load, not black texels at every
// lookup (each of which would try to decode it again).
void check_texels(const std::string& path, const OIIO::ImageSpec& spec) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw InputError(path + ": cannot decode the texture: " + OIIO::geterror());
  const int w = spec.width, h = spec.height, n = spec.nchannels;
  const int band = std::max(1, std::min(h, int((size_t(1) << 22) / (size_t(w) * size_t(n)))));
  std::vector<float> rows(size_t(band) * size_t(w) * size_t(n));
  for (int y0 = 0; y0 < h; y0 += band) {
    const int y1 = std::min(h, y0 + band);
    if (!in->read_scanlines(0, 0, y0 + spec.y, y1 + spec.y, 0, 0, n, OIIO::TypeDesc::FLOAT, rows.data())) {
      throw InputError(path + ": cannot decode the texture: " + in->geterror());
    }
    for (size_t i = 0; i < size_t(y1 - y0) * size_t(w) * size_t(n); ++i) {
      if (!std::isfinite(rows[i])) {
        const size_t texel = i / size_t(n);
        throw InputError(path + ": NaN or infinite texel at (" + std::to_string(texel % size_t(w)) + ", " +
                         std::to_string(size_t(y0) + texel / size_t(w)) + ")");
      }
    }
  }
}

// d srgb_to_linear / dc.
float srgb_to_linear_slope(float c) {
  return c <= 0.04045f ? 1.0f / 12.92f : 2.4f / 1.055f * std::pow((c + 0.055f) / 1.055f, 1.4f);
}
}  // namespace

BitmapTexture::BitmapTexture(const std::string& path, TextureFilter filter, TextureWrap wrap, const UvTransform& to_uv,
                             bool raw)
    : path_(path), filter_(filter), wrap_(wrap), to_uv_(to_uv) {
  OIIO::TextureSystem* ts = texture_system();
  const OIIO::ustring name(path);
  OIIO::ImageSpec spec;
  if (!ts->get_imagespec(name, 0, spec)) {
    const std::string err = ts->geterror();
    throw InputError(path + ": cannot read the texture" + (err.empty() ? std::string() : ": " + err));
  }
  width_ = spec.width;
  height_ = spec.height;
  // The colour channels: all but alpha, as Mitsuba's bitmap (grey-alpha is grey, RGBA is RGB).
  channels_ = spec.nchannels - (spec.alpha_channel >= 0 && spec.nchannels > 1 ? 1 : 0);
  if (width_ <= 0 || height_ <= 0 || channels_ <= 0) throw InputError(path + ": the texture has no pixels");
  if (spec.alpha_channel >= 0 && spec.alpha_channel < channels_) {
    throw InputError(path + ": the texture's alpha channel comes before its colour channels");
  }
  check_texels(path, spec);
  // 8- and 16-bit images hold display-referred sRGB values unless declared raw.
  srgb_ = !raw && (spec.format == OIIO::TypeDesc::UINT8 || spec.format == OIIO::TypeDesc::UINT16);
  handle_ = ts->get_texture_handle(name);
}

bool BitmapTexture::lookup(const Vec2& st, TextureFilter filter, Color& c, Color* ds, Color* dt) const {
  OIIO::TextureOpt opt;
  opt.interpmode = filter == TextureFilter::Nearest ? OIIO::TextureOpt::InterpClosest : OIIO::TextureOpt::InterpBilinear;
  opt.mipmode = OIIO::TextureOpt::MipModeNoMIP;
  const OIIO::TextureOpt::Wrap w = wrap_ == TextureWrap::Repeat  ? OIIO::TextureOpt::WrapPeriodic
                                   : wrap_ == TextureWrap::Mirror ? OIIO::TextureOpt::WrapMirror
                                                                  : OIIO::TextureOpt::WrapClamp;
  opt.swrap = opt.twrap = w;
  float v[3] = {0, 0, 0}, vs[3] = {0, 0, 0}, vt[3] = {0, 0, 0};
  const int n = std::min(channels_, 3);
  OIIO::TextureSystem* ts = texture_system();
  if (!ts->texture(static_cast<OIIO::TextureSystem::TextureHandle*>(handle_), nullptr, opt, st.x, st.y, 0, 0, 0, 0, n, v,
                   ds ? vs : nullptr, ds ? vt : nullptr)) {
    return false;
  }
  if (n == 1) v[1] = v[2] = v[0], vs[1] = vs[2] = vs[0], vt[1] = vt[2] = vt[0];
  for (int i = 0; i < 3; ++i) {
    // Through the sRGB decoding by the chain rule.
    const float slope = srgb_ ? srgb_to_linear_slope(v[i]) : 1.0f;
    if (srgb_) v[i] = srgb_to_linear(v[i]);
    vs[i] *= slope;
    vt[i] *= slope;
  }
  c = Color(v[0], v[1], v[2]);
  if (ds) *ds = Color(vs[0], vs[1], vs[2]);
  if (dt) *dt = Color(vt[0], vt[1], vt[2]);
  return true;
}

Color BitmapTexture::eval(const TexturePoint& p) const {
  Color c(0.0f);
  return lookup(to_uv_.apply(p.uv), filter_, c, nullptr, nullptr) ? c : Color(0.0f);
}

bool BitmapTexture::gradient(const Vec2& uv, Vec2& grad) const {
  grad = Vec2(0.0f);
  if (filter_ == TextureFilter::Nearest) return true;
  Color c(0.0f), ds(0.0f), dt(0.0f);
  if (!lookup(to_uv_.apply(uv), filter_, c, &ds, &dt)) return true;
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
