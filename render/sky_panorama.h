// A scene's sky as an equirectangular panorama: sky.pfm in a run folder, which the viewer
// draws behind the patches and other renderers can take as an environment map.
#pragma once

#include "daylight/sky.h"
#include "render/radiosity_image.h"

namespace radkit {

/// sky.pfm's width in pixels (height is half): 0.35° a pixel, finer than the physical sky's
/// table near the zenith and about the sun's diameter (0.53°).
constexpr int kSkyPanoramaWidth = 1024;

/// \brief The direction of panorama point (u, v), both in [0, 1] from the left and from the
/// top: bearing 360°·u clockwise from the sky's north towards its east (north at the left
/// edge, east a quarter across, south in the middle), elevation 90° − 180°·v above its
/// horizon. The layout of `radkit sky --projection panorama` (atmosphere/sky_image.h).
Vec3 panoramaDirection(const SkyModel& sky, double u, double v);

/// \brief `sky` as a width × width/2 panorama of radiance (W m⁻² sr⁻¹): SkyModel::radiance
/// at each pixel centre (the ground's glow below the horizon) plus the sun's disc, drawn so
/// that its irradiance is kept (the pixels whose centres it covers, or the nearest one when
/// it covers none). Parallel over rows; deterministic.
RadianceImage skyPanorama(const SkyModel& sky, int width = kSkyPanoramaWidth);

}  // namespace radkit
