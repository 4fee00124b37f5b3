// Image files through OpenImageIO, written atomically (temporary file, then rename).
#include "io/image_io.h"
#include <OpenImageIO/imageio.h>
#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <unistd.h>
#include "core/error.h"

namespace caustica {
namespace fs = std::filesystem;

static std::string extension_of(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

bool is_supported_image_path(const std::string& path) {
  const std::string ext = extension_of(path);
  return ext == ".exr" || ext == ".hdr" || ext == ".pfm" || ext == ".png";
}

void check_output_path(const std::string& path) {
  if (!is_supported_image_path(path)) {
    throw InputError(path + ": unknown image type \"" + extension_of(path) + "\" (known: .exr, .hdr, .pfm, .png)");
  }
  fs::path dir = fs::path(path).parent_path();
  if (dir.empty()) dir = ".";
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw InputError(path + ": output folder " + dir.string() + " does not exist");
  if (access(dir.c_str(), W_OK) != 0) throw InputError(path + ": output folder " + dir.string() + " is not writable");
  if (fs::is_directory(path, ec)) throw InputError(path + ": is a directory");
}

namespace {

static_assert(sizeof(Color) == 3 * sizeof(float), "PFM rows are written straight from the pixels");

bool write_pfm(const std::string& path, const Image& image) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) return false;
  bool ok = std::fprintf(f, "PF\n%d %d\n-1.0\n", image.width, image.height) > 0;
  for (int y = image.height - 1; y >= 0 && ok; --y) {
    ok = std::fwrite(&image.at(0, y), sizeof(Color), size_t(image.width), f) == size_t(image.width);
  }
  return std::fclose(f) == 0 && ok;
}

// Returns an error message, empty on success.
std::string write_with_oiio(const std::string& path, const Image& image, float exposure, bool ldr) {
  auto out = OIIO::ImageOutput::create(path);
  if (!out) return "cannot create an image writer: " + OIIO::geterror();
  OIIO::ImageSpec spec(image.width, image.height, 3, ldr ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::FLOAT);
  spec.attribute("oiio:ColorSpace", ldr ? "sRGB" : "Linear");
  if (!out->open(path, spec)) return out->geterror();
  bool ok;
  if (ldr) {
    const float scale = std::exp2(exposure);
    std::vector<unsigned char> bytes(image.pixels.size() * 3);
    for (size_t i = 0; i < image.pixels.size(); ++i) {
      for (int c = 0; c < 3; ++c) {
        bytes[3 * i + c] = static_cast<unsigned char>(std::lround(255.0f * linear_to_srgb(image.pixels[i][c] * scale)));
      }
    }
    ok = out->write_image(OIIO::TypeDesc::UINT8, bytes.data());
  } else {
    ok = out->write_image(OIIO::TypeDesc::FLOAT, image.pixels.data());
  }
  ok = out->close() && ok;
  return ok ? std::string() : out->geterror();
}

}  // namespace

void write_image(const std::string& path, const Image& image, float exposure) {
  check_output_path(path);
  const std::string ext = extension_of(path);
  static std::atomic<int> counter{0};
  const fs::path target(path);
  const fs::path tmp = target.parent_path() /
      ("." + target.stem().string() + ".tmp" + std::to_string(getpid()) + "_" + std::to_string(counter++) + ext);
  std::string error;
  if (ext == ".pfm") {
    // OpenImageIO 2.4 reads PFM but has no writer: the format is three header lines and
    // little-endian float rows, bottom row first.
    if (!write_pfm(tmp.string(), image)) error = std::strerror(errno);
  } else {
    error = write_with_oiio(tmp.string(), image, exposure, ext == ".png");
  }
  if (!error.empty()) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw InputError(path + ": cannot write image: " + error);
  }
  std::error_code ec;
  fs::rename(tmp, target, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw InputError(path + ": cannot rename the finished image into place: " + ec.message());
  }
}

Image read_image(const std::string& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw InputError(path + ": image file not found");
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw InputError(path + ": cannot read image: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) throw InputError(path + ": image has no pixels");
  std::vector<float> data(size_t(spec.width) * spec.height * spec.nchannels);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, data.data())) {
    throw InputError(path + ": cannot read image: " + in->geterror());
  }
  Image img(spec.width, spec.height);
  const bool srgb = spec.format == OIIO::TypeDesc::UINT8 || spec.format == OIIO::TypeDesc::UINT16;
  for (size_t i = 0; i < img.pixels.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      float v = data[i * spec.nchannels + std::min(c, spec.nchannels - 1)];
      if (srgb) v = v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
      img.pixels[i][c] = v;
    }
  }
  return img;
}

}  // namespace caustica
