// The data files of a run folder, every writer in one place, with the one reader of
// surfaces.csv; the viewer reads convergence.csv and surfaces.csv by the column
// names below. docs/formats.md describes each file.
//
// Units are part of the column names. Lengths and areas are in metres whatever the scene's
// --units (a millimetre scene's patch of 100 mm² is 1e-4 in area_m2); radiosity, emission and
// standard errors in W/m²; times in seconds (_s); sizes in bytes. Columns without a suffix are
// dimensionless (normals, reflectance, form factors, relative errors, z-scores).
// Every writer writes a temporary file and renames it into place (util/output_folder.h).
#pragma once

#include <cstddef>
#include <istream>
#include <string>
#include <utility>
#include <vector>

#include "geometry/patch_mesh.h"
#include "geometry/scene.h"
#include "radiosity/radiosity_solution.h"
#include "solvers/matrix.h"
#include "solvers/solver.h"
#include "util/errors.h"

namespace radkit {

/// \brief Reads CSV records (RFC 4180) one at a time: fields are separated by commas and
/// records by LF or CRLF; a double-quoted field may hold commas, "" (one quote), CR and LF.
/// Every reader of radkit's CSV files uses it, so a name that csvField quoted (a surface name
/// with a comma or a line break) reads back whole. Blank lines are skipped.
class CsvReader {
 public:
  /// \param path names the file in errors.
  CsvReader(std::istream& in, std::string path) : m_in(in), m_path(std::move(path)) {}
  /// \brief The next record into `fields`; false at the end of the input.
  /// \throws InputError naming the file and line when the input ends inside a quoted field.
  bool next(std::vector<std::string>& fields);
  /// The line (from 1) on which the record last read starts.
  long long line() const { return m_recordLine; }

 private:
  std::istream& m_in;
  std::string m_path;
  long long m_line = 1, m_recordLine = 0;
};

/// \brief The fields of the first record of `text` (CsvReader's rules); a lone line of a
/// file read line by line splits as before, but only a CsvReader reads quoted line breaks.
std::vector<std::string> splitCsvLine(const std::string& text);

// --- patches.csv, solution-<solver>.csv ---------------------------------------------------
/// The header of patches.csv (one row per patch, B zero when no solution is given).
constexpr const char* kPatchesCsvHeader =
    "id,surface,area_m2,cx_m,cy_m,cz_m,nx,ny,nz,rho_r,rho_g,rho_b,e_r_W_m2,e_g_W_m2,e_b_W_m2,"
    "b_r_W_m2,b_g_W_m2,b_b_W_m2";
/// \param radiosity per-patch B (W/m²) or nullptr for zeros.
void writePatchesCsv(const std::string& path, const Scene& scene, const PatchMesh& mesh,
                     const std::vector<Vec3>* radiosity);
/// solution-<solver>.csv: patches.csv's columns with that solver's B.
void writeSolutionCsv(const std::string& path, const Scene& scene, const PatchMesh& mesh,
                      const SolveResult& solve);

// --- radiosity.vtp ----------------------------------------------------------------------------
/// A named per-patch scalar written as cell data (hierarchical radiosity's level, links, ...).
struct CellArray {
  std::string name;
  std::vector<double> values;
};
/// \brief The patches as VTK XML PolyData (text, without VTK: only viewer/ links it), in the
/// scene's own units (ParaView shows the model as modelled), with cell data surface, area,
/// reflectance, emission, radiosity (when given) and `extra`.
void writePatchesVtp(const std::string& path, const Scene& scene, const PatchMesh& mesh,
                     const std::vector<Vec3>* radiosity, const std::vector<CellArray>& extra = {});

// --- surfaces.csv -----------------------------------------------------------------------------
namespace surfaces_csv {
constexpr const char* kSurface = "surface";
constexpr const char* kArea = "area_m2";
constexpr const char* kRadiosity[3] = {"b_r_W_m2", "b_g_W_m2", "b_b_W_m2"};
constexpr const char* kLuminance = "luminance_cd_m2";  ///< with --photometric
constexpr const char* kIlluminance = "illuminance_lux";
/// With a sky: the sky view factor and the illuminance of the daylight arriving directly.
constexpr const char* kSkyViewFactor = "sky_view_factor";
constexpr const char* kDaylightIlluminance = "daylight_illuminance_lux";
}  // namespace surfaces_csv
/// `surface,area_m2,b_r_W_m2,b_g_W_m2,b_b_W_m2[,luminance_cd_m2,illuminance_lux]
/// [,sky_view_factor,daylight_illuminance_lux]`: photometric columns with --photometric or a
/// sky, the daylight columns with a sky.
void writeSurfacesCsv(const std::string& path, const Scene& scene,
                      const std::vector<SurfaceResult>& results, bool photometric);

/// One row of surfaces.csv as read back.
struct SurfaceRadiosity {
  std::string name;
  double area = 0;  ///< m²
  Vec3 radiosity;   ///< W/m²
};
/// \brief Reads surfaces.csv by its column names (CsvReader). Throws std::runtime_error (or
/// InputError) naming the file, the line and what to fix.
std::vector<SurfaceRadiosity> readSurfacesCsv(const std::string& path);

// --- convergence.csv --------------------------------------------------------------------------
namespace convergence_csv {
constexpr const char* kSolver = "solver";
constexpr const char* kIteration = "iteration";
constexpr const char* kSweeps = "sweeps";  ///< sweep-equivalents (a Southwell shot: 1/n)
constexpr const char* kSeconds = "time_s";
constexpr const char* kResidual = "residual";  ///< relative: ‖E + ρFB − B‖ / ‖E‖ (solver.h)
constexpr const char* kUnshotPower = "unshot_power_W";
}  // namespace convergence_csv
/// \brief One row per kept history row of every solve, 17 significant digits;
/// `metresPerUnit` turns the scene-unit areas in the unshot power into m².
void writeConvergenceCsv(const std::string& path, const std::vector<SolveResult>& solves,
                         double metresPerUnit);

// --- comparison.csv (radkit photons --compare) ------------------------------------------------
/// One row of comparison.csv.
struct SurfaceComparison {
  std::string name;
  double area = 0;           ///< scene units²
  Vec3 photon, photonError;  ///< photon-map B and its estimated standard error
  Vec3 radiosity;            ///< the radiosity solution's B
  Vec3 relativeDifference;   ///< (photon − radiosity)/radiosity, 0 where radiosity is 0
  Vec3 zScore;               ///< (photon − radiosity)/photonError, 0 where the error is 0
};
/// \brief `surface,area_m2,photon_b_{r,g,b}_W_m2,radiosity_b_{r,g,b}_W_m2,rel_diff_{r,g,b},
/// photon_se_{r,g,b}_W_m2,z_{r,g,b}`.
void writeComparisonCsv(const std::string& path, const std::vector<SurfaceComparison>& rows,
                        double metresPerUnit);

// --- surface_formfactors.csv, formfactors.mtx, formfactors.bin --------------------------------
/// \brief Writes `from,to,F` for every ordered pair of surfaces (names quoted when needed).
/// \param surfaceNames one name per surface of the mesh (see surfaceNames()).
void writeSurfaceFormFactors(const std::string& path, const PatchMesh& mesh,
                             const std::vector<std::string>& surfaceNames,
                             const FormFactorMatrix& f);
/// \brief Writes F as Matrix Market `coordinate real general`: row i+1, column j+1, F_ij, for
/// every stored non-zero; `comments` become `%` lines after the banner (describe the run).
/// Values are the shortest text that reads back exactly (float storage as floats). Streamed:
/// the text is never held in memory whole.
void writeMatrixMarket(const std::string& path, const FormFactorMatrix& f,
                       const std::vector<std::string>& comments);
/// Magic of formfactors.bin, version 1.
constexpr char kFormFactorBinaryMagic[9] = "RADKITF1";
/// \brief Writes F compactly for the viewer (formfactors.bin), streamed row by row, all
/// numbers little-endian: the 8-byte magic, int64 n, int64 non-zeros, then per row an int32
/// k and either (k >= 0) k uint32 columns ascending and k float32 values, or (k = −1, when
/// that is smaller) n float32 values. At most 4n² + 4n + 24 bytes.
void writeFormFactorBinary(const std::string& path, const FormFactorMatrix& f);

}  // namespace radkit
