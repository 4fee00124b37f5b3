// Image comparison (OpenImageIO's ImageBufAlgo::compare for RMSE, MAE and PSNR; relMSE here).
#include "core/metrics.h"
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <cmath>
#include <limits>
#include "core/error.h"

namespace caustica {

static OIIO::ImageBuf wrap(const Image& img) {
  const OIIO::ImageSpec spec(img.width, img.height, 3, OIIO::TypeDesc::FLOAT);
  return OIIO::ImageBuf(spec, const_cast<Color*>(img.pixels.data()));
}

namespace {
// Error figures of an image with NaN or infinite pixels mean nothing (OpenImageIO's compare skips
// them and reports a perfect match): say where the first one is.
void check_finite(const Image& image, const std::string& name) {
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    if (is_finite(image.pixels[i])) continue;
    size_t bad = 0;
    for (const Color& c : image.pixels) bad += !is_finite(c);
    throw InputError(name + ": " + std::to_string(bad) + " pixel" + (bad == 1 ? " is" : "s are") +
                     " NaN or infinite, the first at (" + std::to_string(i % size_t(image.width)) + ", " +
                     std::to_string(i / size_t(image.width)) + "): no error figures for such an image");
  }
}
}  // namespace

ErrorMetrics compare_images(const Image& image, const Image& reference, const std::string& image_name,
                            const std::string& reference_name) {
  check_finite(image, image_name);
  check_finite(reference, reference_name);
  if (image.width != reference.width || image.height != reference.height) {
    throw InputError("image sizes differ: " + image_name + " is " + std::to_string(image.width) + "x" +
                     std::to_string(image.height) + ", " + reference_name + " is " + std::to_string(reference.width) +
                     "x" + std::to_string(reference.height));
  }
  ErrorMetrics m;
  const OIIO::ImageBuf a = wrap(image), b = wrap(reference);
  const auto cr = OIIO::ImageBufAlgo::compare(a, b, 1e30f, 1e30f);
  m.mae = cr.meanerror;
  m.rmse = cr.rms_error;
  m.max_error = cr.maxerror;
  m.psnr = m.rmse > 0 ? 20.0 * std::log10(1.0 / m.rmse) : std::numeric_limits<double>::infinity();
  double rel = 0;
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      const double d = double(image.pixels[i][c]) - double(reference.pixels[i][c]);
      const double r = reference.pixels[i][c];
      rel += d * d / (r * r + 0.01);
    }
  }
  m.relmse = image.pixels.empty() ? 0.0 : rel / (3.0 * double(image.pixels.size()));
  m.mean_image = image.mean();
  m.mean_reference = reference.mean();
  return m;
}

Reference combine_references(const std::vector<Image>& renders, const std::vector<std::string>& names) {
  if (renders.empty()) throw InputError("no reference image");
  for (size_t k = 0; k < renders.size(); ++k) check_finite(renders[k], names[k]);
  const Image& first = renders[0];
  for (size_t k = 1; k < renders.size(); ++k) {
    if (renders[k].width != first.width || renders[k].height != first.height) {
      throw InputError("reference sizes differ: " + names[k] + " is " + std::to_string(renders[k].width) + "x" +
                       std::to_string(renders[k].height) + ", " + names[0] + " is " + std::to_string(first.width) +
                       "x" + std::to_string(first.height));
    }
  }
  const size_t K = renders.size();
  Reference ref;
  ref.renders = K;
  ref.mean = Image(first.width, first.height);
  double floor = 0;
  for (size_t i = 0; i < first.pixels.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      double sum = 0;
      for (const Image& r : renders) sum += double(r.pixels[i][c]);
      const double m = sum / double(K);
      ref.mean.pixels[i][c] = float(m);
      if (K < 2) continue;
      // The unbiased sample variance of one render, over K for the variance of their mean.
      double ss = 0;
      for (const Image& r : renders) ss += (double(r.pixels[i][c]) - m) * (double(r.pixels[i][c]) - m);
      // As compare_images divides: by the (float) reference value's square.
      const double mf = ref.mean.pixels[i][c];
      floor += ss / double(K * (K - 1)) / (mf * mf + 0.01);
    }
  }
  ref.floor = first.pixels.empty() || K < 2 ? 0.0 : floor / (3.0 * double(first.pixels.size()));
  return ref;
}

Color false_colour(float t) {
  // Piecewise-linear approximation of matplotlib's "viridis".
  static const Color stops[] = {{0.267f, 0.005f, 0.329f}, {0.283f, 0.141f, 0.458f}, {0.254f, 0.265f, 0.530f},
                                {0.207f, 0.372f, 0.553f}, {0.164f, 0.471f, 0.558f}, {0.128f, 0.567f, 0.551f},
                                {0.135f, 0.659f, 0.518f}, {0.267f, 0.749f, 0.441f}, {0.478f, 0.821f, 0.318f},
                                {0.741f, 0.873f, 0.150f}, {0.993f, 0.906f, 0.144f}};
  constexpr int n = int(sizeof(stops) / sizeof(stops[0]));
  if (!(t > 0.0f)) return stops[0];
  if (t >= 1.0f) return stops[n - 1];
  const float x = t * float(n - 1);
  const int i = int(x);
  const float f = x - float(i);
  // The stops are sRGB colours: return them linear so that PNG output encodes them back.
  const Color c = stops[i] * (1.0f - f) + stops[i + 1] * f;
  return Color(srgb_to_linear(c.r), srgb_to_linear(c.g), srgb_to_linear(c.b));
}

Image error_map(const Image& image, const Image& reference) {
  compare_images(image, reference);
  const int w = image.width, h = image.height;
  const int bar = std::max(12, h / 12);
  Image out(w, h + bar);
  constexpr float lo = -4.0f, hi = 0.0f;  // log10 of the relative squared error
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      double rel = 0;
      for (int c = 0; c < 3; ++c) {
        const double d = double(image.at(x, y)[c]) - double(reference.at(x, y)[c]);
        const double r = reference.at(x, y)[c];
        rel += d * d / (r * r + 0.01) / 3.0;
      }
      const float l = rel > 0 ? float(std::log10(rel)) : lo;
      out.at(x, y) = false_colour((l - lo) / (hi - lo));
    }
  }
  // Colour bar: the ramp left to right, with a gap above it.
  for (int y = h + 2; y < h + bar; ++y)
    for (int x = 0; x < w; ++x) out.at(x, y) = false_colour((float(x) + 0.5f) / float(w));
  // Labels where the font is available; the bar alone still reads left = 1e-4, right = 1.
  OIIO::ImageBuf buf(OIIO::ImageSpec(w, h + bar, 3, OIIO::TypeDesc::FLOAT), out.pixels.data());
  const int size = std::max(8, bar - 6);
  const float white[3] = {1, 1, 1};
  const std::string font = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
  OIIO::ImageBufAlgo::render_text(buf, 2, h + bar - 3, "1e-4", size, font, white);
  OIIO::ImageBufAlgo::render_text(buf, w / 2 - size, h + bar - 3, "1e-2", size, font, white);
  OIIO::ImageBufAlgo::render_text(buf, w - 2 * size, h + bar - 3, "1", size, font, white);
  return out;
}

}  // namespace caustica
