#include "render/exr_io.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>

#include <filesystem>
#include <stdexcept>
#include <vector>

namespace radkit {

namespace {

const char* const kChannels[3] = {"R", "G", "B"};

}  // namespace

void writeExr(const std::string& path, const RadianceImage& image) {
  const std::string tmp = path + ".tmp";
  // Interleaved floats: channel c of pixel k at 3k + c.
  std::vector<float> pixels(std::size_t(image.width) * image.height * 3);
  for (std::size_t k = 0; k < image.radiance.size(); ++k)
    for (int c = 0; c < 3; ++c) pixels[3 * k + c] = float(image.radiance[k][c]);
  try {
    Imf::Header header(image.width, image.height);
    header.compression() = Imf::ZIP_COMPRESSION;
    Imf::FrameBuffer frame;
    for (int c = 0; c < 3; ++c) {
      header.channels().insert(kChannels[c], Imf::Channel(Imf::FLOAT));
      frame.insert(kChannels[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(pixels.data() + c),
                                            3 * sizeof(float), 3 * sizeof(float) * image.width));
    }
    {
      Imf::OutputFile file(tmp.c_str(), header);
      file.setFrameBuffer(frame);
      file.writePixels(image.height);
    }  // closed before the rename
    std::filesystem::rename(tmp, path);
  } catch (const std::exception& e) {
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
    throw std::runtime_error(path + ": cannot write the EXR: " + e.what());
  }
}

RadianceImage readExr(const std::string& path) {
  try {
    Imf::InputFile file(path.c_str());
    const Imath::Box2i window = file.header().dataWindow();
    RadianceImage img;
    img.width = window.max.x - window.min.x + 1;
    img.height = window.max.y - window.min.y + 1;
    std::vector<float> pixels(std::size_t(img.width) * img.height * 3);
    Imf::FrameBuffer frame;
    // The slice base is shifted so the data window's corner lands on pixels[0].
    const std::ptrdiff_t origin = std::ptrdiff_t(window.min.y) * img.width + window.min.x;
    for (int c = 0; c < 3; ++c)
      frame.insert(kChannels[c],
                   Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(pixels.data() + c - 3 * origin),
                              3 * sizeof(float), 3 * sizeof(float) * img.width));
    file.setFrameBuffer(frame);
    file.readPixels(window.min.y, window.max.y);
    img.radiance.resize(std::size_t(img.width) * img.height);
    for (std::size_t k = 0; k < img.radiance.size(); ++k)
      img.radiance[k] = {pixels[3 * k], pixels[3 * k + 1], pixels[3 * k + 2]};
    return img;
  } catch (const std::exception& e) {
    throw std::runtime_error(path + ": cannot read the EXR: " + e.what());
  }
}

}  // namespace radkit
