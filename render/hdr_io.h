// High-dynamic-range output: Portable Float Map (.pfm) files and the filmic tone curve.
// (.exr is in exr_io.h, through OpenEXR; PFM needs no library and loads in ImageMagick,
// GIMP, Photoshop, HDRView and Python's imageio.)
#pragma once

#include <string>
#include <vector>

#include "render/radiosity_image.h"
#include "util/canvas.h"

namespace radkit {

/// \brief Writes linear radiance as a colour PFM ("PF", little-endian float, rows bottom to
/// top, as the format demands), atomically.
void writePfm(const std::string& path, const RadianceImage& image);
/// \brief Reads a colour PFM of either byte order (tests and tools); throws
/// std::runtime_error naming the file on malformed input. Only radiance is filled.
RadianceImage readPfm(const std::string& path);

/// \brief Narkowicz's ACES filmic fit, x(2.51x + 0.03) / (x(2.43x + 0.59) + 0.14) clamped to
/// [0, 1] ("ACES Filmic Tone Mapping Curve", 2016), applied per channel.
double acesFilmic(double x);

/// How linear radiance becomes display values.
enum class ToneCurve {
  Srgb,    ///< exposure, clamp, sRGB transfer curve (toneMap in radiosity_image.h)
  Filmic,  ///< exposure, ACES filmic fit, sRGB transfer curve
};

/// \brief 8-bit image of `image` × exposure through the chosen curve.
Canvas toneMapCurve(const RadianceImage& image, double exposure, ToneCurve curve);

/// \brief A RadianceImage of linear pixels (row-major, top row first) that show no patch, to
/// be tone mapped at `exposure`: what images rendered without a patch mesh (sky, clouds,
/// landscapes, pillars) are written as.
RadianceImage pixelImage(int width, int height, std::vector<Vec3> radiance, double exposure);

/// \brief Writes `stem`.pfm (linear) and `stem`.png (ACES filmic at image.exposure), each
/// atomically.
void writeLinearAndPng(const std::string& stem, const RadianceImage& image);

/// \brief Grey image of |Y(image) − Y(reference)| / Y(reference) per pixel, white at 20 % or
/// more (0 where the reference is black); tone map it with the sRGB curve at exposure 1.
RadianceImage relativeDifferenceImage(int width, int height, const std::vector<Vec3>& image,
                                      const std::vector<Vec3>& reference);

}  // namespace radkit
