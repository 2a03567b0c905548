// Volume scene files (docs/formats.md, "Volume scenes"): a medium (a cloud layer or a
// homogeneous box), and optionally the sun, the camera and the ground's albedo, for
// `radkit clouds --scene`. A plain reader: every problem throws InputError naming the file.
#pragma once

#include <nlohmann/json.hpp>

#include <memory>
#include <optional>
#include <string>

#include "geometry/scene.h"
#include "media/medium.h"
#include "util/errors.h"

namespace radkit::media {

struct VolumeScene {
  std::string file;
  std::string kind;  ///< the medium's "type": "cloud-layer" or "homogeneous-box"
  std::unique_ptr<Medium> medium;
  std::string phaseName, phaseParams;  ///< as given to makePhaseFunction
  std::optional<double> sunElevationDeg, sunAzimuthDeg;
  std::optional<Camera> camera;  ///< position, look_at, up, fov_deg
  double groundAlbedo = 0;       ///< Lambertian ground at z = 0, in [0, 1)
};

/// \brief The medium of `j` (the file's "medium" object); `file` names it in errors. `kind`,
/// `phaseName` and `phaseParams`, when given, receive its type and phase function.
std::unique_ptr<Medium> parseMedium(const nlohmann::json& j, const std::string& file,
                                    std::string* kind = nullptr, std::string* phaseName = nullptr,
                                    std::string* phaseParams = nullptr);

/// \brief Reads and checks a volume scene file.
VolumeScene loadVolumeScene(const std::string& path);

}  // namespace radkit::media
