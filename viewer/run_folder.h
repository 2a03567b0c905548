// RunFolder: the files `radkit run` writes, read into plain structs for the viewer.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "geometry/scene.h"
#include "util/errors.h"
#include "util/vec3.h"

namespace radkit::viewer {

/// The patches of radiosity.vtp: shared points, polygons (3 or 4 corners) and per-patch
/// cell data. Patch i is polygon i; all vectors indexed by patch have the same size.
struct PatchData {
  std::vector<Vec3> points;                ///< scene units
  std::vector<std::vector<int>> polygons;  ///< indices into points, counter-clockwise
  std::vector<int> surface;                ///< index into RunReport::surfaces
  std::vector<double> area;                ///< scene units²
  std::vector<Vec3> reflectance;           ///< ρ per RGB channel
  std::vector<Vec3> emission;              ///< E, W/m²
  std::vector<Vec3> radiosity;             ///< B, W/m²

  int size() const { return static_cast<int>(polygons.size()); }
  bool emits(int patch) const { return maxComponent(emission[patch]) > 0; }
  Bounds3 bounds() const;
};

/// Largest |radiosity| or emission radiosity.vtp may hold (W/m²; sunlight is 1e3, the sun's
/// surface 6e7): the views' colour scales multiply and sum these, which must stay finite.
constexpr double kMaxRadiosity = 1e30;

/// formfactors.bin or formfactors.mtx as compressed rows: row i holds F_ij for j = column[k],
/// k in [rowStart[i], rowStart[i+1]).
struct FormFactorRows {
  int n = 0;
  std::vector<long long> rowStart;  ///< size n + 1
  std::vector<int> column;          ///< from 0
  std::vector<double> value;

  long long nonZeros() const { return static_cast<long long>(value.size()); }
  /// Row i densely (n values).
  std::vector<double> row(int i) const;
  double maxValue() const;
};

/// One solver run's block of convergence.csv.
struct SolverHistory {
  std::string solver;
  std::vector<int> iteration;
  std::vector<double> seconds, residual, unshotPower;
};

/// One row of surfaces.csv; photometric columns are NaN when absent.
struct SurfaceSummary {
  std::string name;
  double area = 0;
  Vec3 radiosity;  ///< area-weighted mean B, W/m²
  double luminance = NAN, illuminance = NAN;
};

/// Where a sky panorama's directions lie in the scene: a right-handed orthonormal frame.
struct SkyFrame {
  Vec3 up, north, east;  ///< east = north × up
};

/// What the viewer needs from report.json.
struct RunReport {
  std::string sceneName, sceneFile, units;
  std::vector<std::string> surfaces;  ///< names in surface-index order
  std::optional<Camera> camera;
  std::optional<SkyFrame> skyFrame;  ///< "sky_panorama" of a run under a sky
};

/// sky.pfm: the run's sky as radiance over directions (render/sky_panorama.h's layout:
/// column u at bearing 360°u from north towards east, row v at elevation 90° − 180°v).
struct SkyPanorama {
  int width = 0, height = 0;
  std::vector<Vec3> radiance;  ///< W m⁻² sr⁻¹, row-major, top row (the zenith) first
  SkyFrame frame;
};

/// links.png decoded: 8-bit RGB, rows from the top.
struct LinksImage {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  ///< width × height × 3
};

/// A whole run folder. Optional files that are absent leave their member empty
/// (with the reason in the matching `...Missing` message, for the views to show).
struct RunFolder {
  std::string path;
  RunReport report;
  PatchData patches;
  std::optional<FormFactorRows> formFactors;
  std::vector<SolverHistory> convergence;
  std::vector<SurfaceSummary> surfaces;
  std::string formFactorsMissing, convergenceMissing;
  /// A hierarchical run's links.png (its links as blocks of F, written by the run); empty if
  /// the folder has none. The matrix mode shows it when there is no formfactors.mtx.
  std::string linksImage;
  /// Its pixels, decoded when the folder is read (so a damaged file is refused before a
  /// window opens).
  LinksImage links;
  /// The sky behind the patches, when report.json names a panorama and sky.pfm is there.
  std::optional<SkyPanorama> sky;

  /// Name of a patch's surface ("#3" when report.json lists fewer surfaces).
  std::string surfaceName(int patch) const;
};

/// \brief Reads radiosity.vtp and report.json (required), formfactors.bin or .mtx, links.png,
/// convergence.csv, surfaces.csv and sky.pfm (optional), and checks they agree (patch count,
/// surface indices). Each must be a regular file (a FIFO would block the read). \throws
/// radkit::InputError naming the file, the line or element and the fix.
RunFolder readRunFolder(const std::string& folder);

/// \brief The parsers behind readRunFolder, one file each (`path` names the file in errors).
/// readPatchesVtp (patches_vtp.cpp) reads the ASCII VTK XML radkit writes, needs every cell
/// array above and checks every index, count and value the views rely on.
PatchData readPatchesVtp(const std::string& path);
RunReport readRunReport(const std::string& path);
FormFactorRows readFormFactorsMtx(const std::string& path);
/// formfactors.bin (writeFormFactorBinary's layout); read instead of the .mtx when present.
FormFactorRows readFormFactorsBin(const std::string& path);
std::vector<SolverHistory> readConvergenceCsv(const std::string& path);
std::vector<SurfaceSummary> readSurfacesCsv(const std::string& path);
/// \brief sky.pfm: a colour PFM twice as wide as high (at most kMaxSkySide wide) of finite
/// radiance >= 0. The frame is report.json's and is left empty here.
SkyPanorama readSkyPanorama(const std::string& path);
constexpr int kMaxSkySide = 8192;
/// \brief links.png through stb_image: a PNG whose declared size is at most kMaxLinksSide per
/// side and kMaxLinksPixels in all, checked before decoding.
LinksImage readLinksPng(const std::string& path);
constexpr int kMaxLinksSide = 16384;
constexpr long long kMaxLinksPixels = 1LL << 25;  ///< 32 Mpixels (radkit writes about 1)

}  // namespace radkit::viewer
