// Image files through OpenImageIO, written atomically (temporary file, then rename).
#include "io/image_io.h"
#include <OpenImageIO/imageio.h>
#include <algorithm>
#include <filesystem>
#include <OpenImageIO/filesystem.h>
#include "core/error.h"
#include "core/memory.h"
#include "io/atomic_file.h"

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
  check_output_file(path);
}

namespace {

static_assert(sizeof(Color) == 3 * sizeof(float), "PFM rows are written straight from the pixels");

// OpenImageIO 2.4 reads PFM but has no writer: the format is three header lines and
// little-endian float rows, bottom row first.
std::string encode_pfm(const Image& image) {
  std::string out = "PF\n" + std::to_string(image.width) + " " + std::to_string(image.height) + "\n-1.0\n";
  const size_t row = sizeof(Color) * size_t(image.width);
  out.reserve(out.size() + row * size_t(image.height));
  for (int y = image.height - 1; y >= 0; --y) out.append(reinterpret_cast<const char*>(&image.at(0, y)), row);
  return out;
}

// Encodes through OpenImageIO into memory where its writer for the format can (so that our own
// checked write puts the bytes on the disk: a full disk is then an error, never a short file),
// else straight into the temporary. Returns an error message, empty on success.
std::string write_with_oiio(AtomicFile& file, const Image& image, float exposure, bool ldr) {
  // The memory proxy outlives the writer, which may still close through it when destroyed.
  std::vector<unsigned char> encoded;
  OIIO::Filesystem::IOVecOutput memory(encoded);
  auto out = OIIO::ImageOutput::create(file.path());
  if (!out) return "cannot create an image writer: " + OIIO::geterror();
  OIIO::ImageSpec spec(image.width, image.height, 3, ldr ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::FLOAT);
  spec.attribute("oiio:ColorSpace", ldr ? "sRGB" : "Linear");
  const bool in_memory = out->supports("ioproxy") && out->set_ioproxy(&memory);
  if (!out->open(file.path(), spec)) return out->geterror();
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
  if (!ok) return out->geterror();
  if (in_memory) file.write(encoded.data(), encoded.size(), "image");
  return std::string();
}

}  // namespace

void write_image_to(AtomicFile& file, const Image& image, float exposure) {
  const std::string ext = extension_of(file.target());
  if (ext == ".pfm") {
    file.write(encode_pfm(image), "image");
    return;
  }
  const std::string error = write_with_oiio(file, image, exposure, ext == ".png");
  if (!error.empty()) throw InputError(file.target() + ": cannot write the image: " + error);
}

void write_image(const std::string& path, const Image& image, float exposure) {
  check_output_path(path);
  AtomicFile file(path);
  write_image_to(file, image, exposure);
  file.commit("image");
}

Image read_image(const std::string& path) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (!fs::exists(status)) throw InputError(path + ": image file not found");
  if (fs::is_directory(status)) throw InputError(path + ": is a folder, not an image file");
  if (!fs::is_regular_file(status)) throw InputError(path + ": is not a regular file (a device or a pipe?), not an image file");
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw InputError(path + ": cannot read image: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) throw InputError(path + ": image has no pixels");
  const double values = double(spec.width) * double(spec.height) * double(spec.nchannels);
  // PFM and the other PNM formats hold their values uncompressed (at least a bit each: P4): one
  // that declares more than it holds is refused before anything is allocated.
  if (std::string(in->format_name()) == "pnm" && values / 8.0 > double(fs::file_size(path, ec))) {
    throw InputError(path + ": the image declares " + std::to_string(spec.width) + " x " + std::to_string(spec.height) +
                     " pixels, more than the file holds");
  }
  check_memory(values * sizeof(float) + double(spec.width) * double(spec.height) * sizeof(Color),
               path + " (" + std::to_string(spec.width) + " x " + std::to_string(spec.height) + " pixels)");
  std::vector<float> data(size_t(spec.width) * spec.height * spec.nchannels);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, data.data())) {
    throw InputError(path + ": cannot read image: " + in->geterror());
  }
  Image img(spec.width, spec.height);
  const bool srgb = spec.format == OIIO::TypeDesc::UINT8 || spec.format == OIIO::TypeDesc::UINT16;
  for (size_t i = 0; i < img.pixels.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      float v = data[i * spec.nchannels + std::min(c, spec.nchannels - 1)];
      if (srgb) v = srgb_to_linear(v);
      img.pixels[i][c] = v;
    }
  }
  return img;
}

}  // namespace caustica
