#include "photon/estimate.h"

#include <algorithm>
#include <cmath>

namespace radkit {

namespace {

/// Running Σ X_j and Σ X_j² over paths for a set of bins (patches or surfaces). The photons
/// of the current path are collected in `open` first, so X_j sums all its visits to a bin.
class PathTally {
 public:
  explicit PathTally(std::size_t bins)
      : m_sum(bins), m_sum2(bins), m_pending(bins), m_isOpen(bins, 0) {}

  void add(int bin, const Vec3& power) {
    if (!m_isOpen[bin]) m_open.push_back(bin), m_isOpen[bin] = 1;
    m_pending[bin] += power;
  }
  /// Ends the current path: its X_j enter the sums.
  void closePath() {
    for (int bin : m_open) {
      const Vec3 x = m_pending[bin];
      m_sum[bin] += x;
      m_sum2[bin] += mul(x, x);
      m_pending[bin] = {};
      m_isOpen[bin] = 0;
    }
    m_open.clear();
  }
  const Vec3& sum(int bin) const { return m_sum[bin]; }
  /// Estimated standard error of Σ_j X_j over n paths.
  Vec3 standardError(int bin, std::size_t n) const {
    if (n < 2) return {};
    Vec3 se;
    for (int c = 0; c < 3; ++c) {
      const double s = m_sum[bin][c], s2 = m_sum2[bin][c];
      const double var = std::max(0.0, s2 - s * s / double(n)) / double(n - 1);  // of one X_j
      se[c] = std::sqrt(double(n) * var);
    }
    return se;
  }

 private:
  std::vector<Vec3> m_sum, m_sum2, m_pending;
  std::vector<char> m_isOpen;
  std::vector<int> m_open;
};

}  // namespace

PhotonRadiosity estimateRadiosity(const Scene& scene, const PatchMesh& mesh,
                                  const std::vector<Photon>& photons, std::size_t paths) {
  const std::size_t surfaces = scene.surfaces.size();
  PathTally perPatch(mesh.size()), perSurface(surfaces), caustic(surfaces);
  std::vector<std::size_t> counts(surfaces, 0);
  for (std::size_t k = 0; k < photons.size(); ++k) {
    const Photon& p = photons[k];
    if (k > 0 && photons[k - 1].path != p.path) {
      perPatch.closePath();
      perSurface.closePath();
      caustic.closePath();
    }
    const Vec3 power = p.flux();
    const int s = mesh.patches[p.patch].surface;
    perPatch.add(p.patch, power);
    perSurface.add(s, power);
    ++counts[s];
    if (p.caustic) caustic.add(s, power);
  }
  perPatch.closePath();
  perSurface.closePath();
  caustic.closePath();

  PhotonRadiosity r;
  r.irradiance.resize(mesh.size());
  r.radiosity.resize(mesh.size());
  r.radiosityError.resize(mesh.size());
  for (int i = 0; i < mesh.size(); ++i) {
    const Patch& patch = mesh.patches[i];
    const Material& m = scene.materials[scene.surfaces[patch.surface].material];
    const Vec3 rho = m.diffuseAlbedo();
    r.irradiance[i] = perPatch.sum(i) / patch.area;           // H_i = Φ_i / A_i
    r.radiosity[i] = m.emission + mul(rho, r.irradiance[i]);  // B_i = E_i + ρ_i H_i
    r.radiosityError[i] = mul(rho, perPatch.standardError(i, paths)) / patch.area;
  }
  r.surfaces.resize(surfaces);
  for (std::size_t s = 0; s < surfaces; ++s) {
    SurfaceEstimate& e = r.surfaces[s];
    const Material& m = scene.materials[scene.surfaces[s].material];
    const Vec3 rho = m.diffuseAlbedo();
    e.name = scene.surfaces[s].name;
    for (int i = mesh.surfaceBegin[s]; i < mesh.surfaceBegin[s + 1]; ++i)
      e.area += mesh.patches[i].area;
    e.photons = counts[s];
    if (!(e.area > 0)) continue;
    e.irradiance = perSurface.sum(int(s)) / e.area;
    e.irradianceError = perSurface.standardError(int(s), paths) / e.area;
    e.radiosity = m.emission + mul(rho, e.irradiance);
    e.radiosityError = mul(rho, e.irradianceError);
    e.causticIrradiance = caustic.sum(int(s)) / e.area;
    e.causticIrradianceError = caustic.standardError(int(s), paths) / e.area;
  }
  return r;
}

}  // namespace radkit
