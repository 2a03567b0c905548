// What the viewer shows and how radiosity becomes colour: view modes, channels, exposure,
// photometric units. No VTK here, so the colour maths is testable without a display.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "util/errors.h"
#include "util/photometry.h"
#include "util/vec3.h"
#include "viewer/run_folder.h"

namespace radkit::viewer {

/// Background of every view (RGB in [0, 1]).
constexpr double kBackground[3] = {0.11, 0.11, 0.13};

/// What fills the window: the scene coloured one of three ways, or the matrix, or the chart.
enum class ViewMode { Radiosity, FalseColour, FormFactorRow, Matrix, Convergence };
/// The quantity false colour shows: one radiosity channel or the luminance of B.
enum class Channel { Red, Green, Blue, Luminance };

/// A parsed `--mode`: the mode, plus the row (patch id) for formfactors-row:ID.
struct ModeChoice {
  ViewMode mode = ViewMode::Radiosity;
  int row = -1;
};

/// \brief Parses radiosity|false-colour|formfactors-row:ID|matrix|convergence.
/// \throws radkit::InputError listing the valid modes (ID is checked later, against the run).
ModeChoice parseMode(const std::string& text);
/// \brief Parses r|g|b|luminance (also red, green, blue, l). \throws radkit::InputError.
Channel parseChannel(const std::string& text);
std::string modeName(ViewMode mode);

/// Everything the scene view needs to colour the patches; changed by the keys.
struct ViewSettings {
  ViewMode mode = ViewMode::Radiosity;
  Channel channel = Channel::Luminance;
  bool smooth = false;       ///< vertex-interpolated instead of flat patches
  bool photometric = false;  ///< false colour of luminance in cd/m² instead of W/m²
  bool edges = false;        ///< draw patch outlines
  double exposure = 0;       ///< multiplier on radiance L = B/π; 0: automatic
  int picked = -1;           ///< picked patch, -1 for none
};

/// \brief Automatic exposure for true colour: maps the area-weighted 95th percentile of the
/// luminance of L = B/π over non-emitting patches to 0.8, as render/radiosity_image.cpp does
/// over pixels (so the viewer and render.png agree up to what the camera sees).
double autoExposure(const PatchData& patches);

/// \brief True colour of radiosity B: sRGB(exposure × B/π), clamped, as 8-bit RGB.
std::array<std::uint8_t, 3> trueColour(const Vec3& radiosity, double exposure);

/// \brief The false-colour quantity of B: B_r, B_g, B_b or Y(B) in W/m², or with
/// `photometric` the luminance 683 lm/W × Y(B)/π in cd/m² (Y: Rec. 709 weights).
double channelValue(const Vec3& radiosity, Channel channel, bool photometric);
/// Name and unit of channelValue for the scalar bar: "luminance (cd/m²)".
std::string channelLabel(Channel channel, bool photometric);

/// \brief Top of the false-colour range: the area-weighted 99th percentile of `values` over
/// non-emitting patches, rounded up to two significant digits, so that a few hot patches next
/// to a lamp do not darken the rest; patches above it (and emitters) get the above-range colour.
double falseColourTop(const PatchData& patches, const std::vector<double>& values);

/// \brief The heat-map cells of F: n ≤ maxCells keeps one cell per patch pair; above that
/// each cell is the MEAN of F over its block × block tile (block = ceil(n / maxCells)), as
/// formfactors.png does, so a cell is the average coupling of the patches it stands for.
struct MatrixCells {
  int cells = 0;              ///< cells per side
  int block = 1;              ///< patches per cell side
  std::vector<double> value;  ///< row-major, row 0 = patch rows [0, block)
};
MatrixCells downsampleMatrix(const FormFactorRows& f, int maxCells);

}  // namespace radkit::viewer
