#include "render/hdr_io.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "util/output_folder.h"

namespace radkit {

void writePfm(const std::string& path, const RadianceImage& image) {
  std::ostringstream out;
  // Header: "PF", width height, scale; a negative scale means little-endian floats.
  out << "PF\n" << image.width << ' ' << image.height << "\n-1.0\n";
  std::string body(std::size_t(image.width) * image.height * 12, '\0');
  char* p = body.data();
  for (int y = image.height - 1; y >= 0; --y)
    for (int x = 0; x < image.width; ++x) {
      const Vec3& v = image.radiance[std::size_t(y) * image.width + x];
      for (int c = 0; c < 3; ++c) {
        float f = float(v[c]);
        std::uint32_t bits;
        std::memcpy(&bits, &f, 4);
        for (int b = 0; b < 4; ++b) *p++ = char((bits >> (8 * b)) & 0xff);
      }
    }
  writeFileAtomically(path, out.str() + body);
}

RadianceImage readPfm(const std::string& path) {
  // Opening a FIFO or a device for reading blocks or never ends.
  std::error_code ec;
  if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec))
    throw std::runtime_error(path +
                             ": not a regular file (a folder, pipe or device). Fix: give the "
                             "path of a PFM file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot open");
  std::string magic;
  RadianceImage img;
  double scale = 0;
  in >> magic >> img.width >> img.height >> scale;
  if (!in || magic != "PF" || img.width <= 0 || img.height <= 0 || scale == 0)
    throw std::runtime_error(path + ": not a colour PFM (expected \"PF\", width, height, scale)");
  in.get();  // the single whitespace character before the data
  // The header's size is checked against the bytes left before allocating: a mutated header
  // (PF 2000000000 2000000000) asked for 48 EB.
  const std::streamoff at = in.tellg();
  in.seekg(0, std::ios::end);
  const std::streamoff left = in.tellg() - at;
  in.seekg(at);
  if (left < 0 || double(img.width) * img.height * 12 > double(left))
    throw std::runtime_error(
        path + ": PFM header says " + std::to_string(img.width) + "x" + std::to_string(img.height) +
        " pixels (" + std::to_string(std::uint64_t(img.width) * std::uint64_t(img.height) * 12) +
        " bytes) but " + std::to_string(left) + " bytes follow it. Fix: give a whole PFM file");
  std::string body(std::size_t(img.width) * img.height * 12, '\0');
  if (!in.read(body.data(), std::streamsize(body.size())))
    throw std::runtime_error(path + ": PFM data shorter than " + std::to_string(body.size()) +
                             " bytes");
  const bool little = scale < 0;
  img.radiance.resize(std::size_t(img.width) * img.height);
  img.patch.assign(img.radiance.size(), -1);
  const auto* q = reinterpret_cast<const unsigned char*>(body.data());
  for (int y = img.height - 1; y >= 0; --y)
    for (int x = 0; x < img.width; ++x)
      for (int c = 0; c < 3; ++c, q += 4) {
        std::uint32_t bits = 0;
        for (int b = 0; b < 4; ++b) bits |= std::uint32_t(q[little ? b : 3 - b]) << (8 * b);
        float f;
        std::memcpy(&f, &bits, 4);
        // One NaN made every comparison with the image meaningless (max(NaN, x) is x).
        if (!(f >= 0 && f <= std::numeric_limits<float>::max()))
          throw std::runtime_error(path + ": pixel (" + std::to_string(x) + ", " +
                                   std::to_string(y) + ") channel " + std::to_string(c) + " is " +
                                   std::to_string(f) +
                                   "; radiance is finite and >= 0. Fix: repair or re-render "
                                   "the reference");
        img.radiance[std::size_t(y) * img.width + x][c] = f;  // |scale| is conventionally 1
      }
  return img;
}

double acesFilmic(double x) {
  x = std::max(0.0, x);
  return std::clamp(x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

Canvas toneMapCurve(const RadianceImage& image, double exposure, ToneCurve curve) {
  if (curve == ToneCurve::Srgb) return toneMap(image, exposure);
  Canvas c(image.width, image.height, {0, 0, 0});
  auto byte = [](double t) { return std::uint8_t(std::lround(255 * srgbEncode(acesFilmic(t)))); };
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const Vec3 v = image.radiance[std::size_t(y) * image.width + x] * exposure;
      c.set(x, y, {byte(v.x), byte(v.y), byte(v.z)});
    }
  return c;
}

RadianceImage pixelImage(int width, int height, std::vector<Vec3> radiance, double exposure) {
  RadianceImage img;
  img.width = width, img.height = height;
  img.patch.assign(radiance.size(), -1);
  img.radiance = std::move(radiance);
  img.exposure = exposure;
  return img;
}

void writeLinearAndPng(const std::string& stem, const RadianceImage& image) {
  writePfm(stem + ".pfm", image);
  writePng(stem + ".png", toneMapCurve(image, image.exposure, ToneCurve::Filmic));
}

RadianceImage relativeDifferenceImage(int width, int height, const std::vector<Vec3>& image,
                                      const std::vector<Vec3>& reference) {
  std::vector<Vec3> grey(reference.size());
  for (std::size_t i = 0; i < reference.size(); ++i) {
    const double ref = luminance(reference[i]);
    const double rel = ref > 0 ? std::fabs(luminance(image[i]) - ref) / ref : 0;
    grey[i] = Vec3{1, 1, 1} * std::min(1.0, 5 * rel);
  }
  return pixelImage(width, height, std::move(grey), 1);
}

}  // namespace radkit
