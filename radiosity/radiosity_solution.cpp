#include "radiosity/radiosity_solution.h"

#include <cmath>
#include <iomanip>
#include <sstream>

#include "solvers/kernels.h"
#include "util/output_folder.h"

namespace radkit {

namespace {

const Material& materialOf(const Scene& scene, const Patch& p) {
  return scene.materials[scene.surfaces[p.surface].material];
}
}  // namespace

RadiositySystem makeRadiositySystem(const Scene& scene, const PatchMesh& mesh,
                                    const FormFactorMatrix& f) {
  RadiositySystem s;
  s.formFactors = &f;
  const double m2 = scene.metresPerUnit() * scene.metresPerUnit();
  const int n = mesh.size();
  s.area.resize(n);
  for (int c = 0; c < 3; ++c) {
    s.reflectance[c].resize(n);
    s.emission[c].resize(n);
  }
  for (int i = 0; i < n; ++i) {
    const Patch& p = mesh.patches[i];
    s.area[i] = p.area * m2;
    const Material& m = materialOf(scene, p);
    for (int c = 0; c < 3; ++c) {
      s.reflectance[c][i] = m.diffuseAlbedo()[c];  // radiosity sees the diffuse part only
      s.emission[c][i] = m.emission[c];
    }
  }
  return s;
}

std::vector<Vec3> toVec3(const Channels& c) {
  std::vector<Vec3> v(c[0].size());
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = {c[0][i], c[1][i], c[2][i]};
  return v;
}

std::vector<Vec3> irradiance(const FormFactorMatrix& f, const Channels& radiosity) {
  Channels h = makeChannels(matrixSize(f));
  multiply(f, radiosity, h);
  return toVec3(h);
}

std::vector<SurfaceResult> surfaceResults(const Scene& scene, const PatchMesh& mesh,
                                          const std::vector<Vec3>& b, const std::vector<Vec3>& h) {
  const double m2 = scene.metresPerUnit() * scene.metresPerUnit();
  std::vector<SurfaceResult> out(scene.surfaces.size());
  for (std::size_t s = 0; s < out.size(); ++s) {
    SurfaceResult& r = out[s];
    r.name = scene.surfaces[s].name;
    for (int i = mesh.surfaceBegin[s]; i < mesh.surfaceBegin[s + 1]; ++i) {
      double a = mesh.patches[i].area;
      r.area += a;
      r.radiosity += b[i] * a;
      r.irradiance += h[i] * a;
    }
    if (r.area > 0) {
      r.radiosity = r.radiosity / r.area;
      r.irradiance = r.irradiance / r.area;
    }
    r.area *= m2;
    r.luminance = kLumensPerWatt * luminance(r.radiosity) / M_PI;
    r.illuminance = kLumensPerWatt * luminance(r.irradiance);
  }
  return out;
}

EnergyBalance energyBalance(const Scene& scene, const PatchMesh& mesh, const FormFactorMatrix& f,
                            const std::vector<Vec3>& b, const std::vector<Vec3>& h,
                            const std::vector<Vec3>* daylight) {
  const double m2 = scene.metresPerUnit() * scene.metresPerUnit();
  std::vector<double> rows = rowSums(f);
  EnergyBalance e;
  for (int i = 0; i < mesh.size(); ++i) {
    const Patch& p = mesh.patches[i];
    const Material& m = materialOf(scene, p);
    double a = p.area * m2;
    e.emitted += m.emission * a;
    if (daylight) e.emitted += (*daylight)[i] * a;
    e.absorbed += mul(Vec3{1, 1, 1} - m.diffuseAlbedo(), h[i]) * a;
    e.escaped += b[i] * (a * std::max(0.0, 1 - rows[i]));
  }
  for (int c = 0; c < 3; ++c)
    if (e.emitted[c] > 0)
      e.relativeImbalance =
          std::max(e.relativeImbalance,
                   std::fabs(e.emitted[c] - e.absorbed[c] - e.escaped[c]) / e.emitted[c]);
  return e;
}

}  // namespace radkit
