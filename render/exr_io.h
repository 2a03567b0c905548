// OpenEXR output of linear radiance (render --out x.exr), through the OpenEXR library.
#pragma once

#include <string>

#include "render/radiosity_image.h"

namespace radkit {

/// \brief Writes R, G, B as 32-bit float channels (ZIP compression, lossless), so the file
/// holds exactly the values a PFM of the same render holds. Written as FILE.tmp, then renamed.
/// \throws std::runtime_error naming the file when OpenEXR fails.
void writeExr(const std::string& path, const RadianceImage& image);

/// \brief Reads the R, G, B channels of a scan-line EXR (tests and tools); only radiance is
/// filled. \throws std::runtime_error naming the file.
RadianceImage readExr(const std::string& path);

}  // namespace radkit
