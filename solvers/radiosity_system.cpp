#include "solvers/radiosity_system.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace radkit {

namespace {

constexpr const char* kChannelName[3] = {"red", "green", "blue"};

[[noreturn]] void reject(const std::string& what) {
  throw std::invalid_argument("RadiositySystem: " + what);
}

std::string entry(const char* field, int c, int i, double v) {
  std::ostringstream s;
  s << field << "[" << kChannelName[c] << "][patch " << i << "] = " << v;
  return s.str();
}

void checkChannelSizes(const Channels& x, const char* field, int n) {
  for (int c = 0; c < 3; ++c)
    if (static_cast<int>(x[c].size()) != n)
      reject(std::string(field) + " channel " + kChannelName[c] + " has " +
             std::to_string(x[c].size()) + " entries for " + std::to_string(n) + " patches");
}

}  // namespace

const FormFactorMatrix& RadiositySystem::matrix() const {
  if (!formFactors) throw std::logic_error("RadiositySystem: no form-factor matrix set");
  return *formFactors;
}

void RadiositySystem::validate() const {
  const int n = size();
  if (!formFactors) reject("no form-factor matrix set (formFactors is null)");
  if (matrixSize(*formFactors) != n)
    reject("form-factor matrix is " + std::to_string(matrixSize(*formFactors)) + " x " +
           std::to_string(matrixSize(*formFactors)) + " for " + std::to_string(n) + " areas");
  for (int i = 0; i < n; ++i)
    if (!(area[i] > 0.0) || !std::isfinite(area[i]))
      reject("area[patch " + std::to_string(i) + "] = " + std::to_string(area[i]) +
             " must be finite and > 0; drop degenerate patches before solving");
  checkChannelSizes(reflectance, "reflectance", n);
  checkChannelSizes(emission, "emission", n);
  for (int c = 0; c < 3; ++c)
    for (int i = 0; i < n; ++i) {
      const double rho = reflectance[c][i], e = emission[c][i];
      if (!(rho >= 0.0 && rho < 1.0))
        reject(entry("reflectance", c, i, rho) + " is outside [0, 1); fix the material");
      if (!(e >= 0.0) || !std::isfinite(e))
        reject(entry("emission", c, i, e) + " must be finite and >= 0; fix the material");
    }
}

Channels residualVector(const RadiositySystem& system, const Channels& b) {
  Channels fb;
  multiply(system.matrix(), b, fb);
  Channels r = makeChannels(system.size());
  for (int c = 0; c < 3; ++c)
    for (int i = 0; i < system.size(); ++i)
      r[c][i] = system.emission[c][i] + system.reflectance[c][i] * fb[c][i] - b[c][i];
  return r;
}

double residualMeasure(const RadiositySystem& system, const Channels& r, const Channels& b,
                       ResidualNorm norm) {
  if (norm == ResidualNorm::Relative) {
    const double e = system.emissionNorm();
    return e > 0.0 ? maxAbs(r) / e : maxAbs(r);  // E = 0: absolute, B = 0 is exact
  }
  double worst = 0.0;
  for (int c = 0; c < 3; ++c)
    for (std::size_t i = 0; i < r[c].size(); ++i) {
      const double scale = std::max(std::fabs(b[c][i]), std::fabs(b[c][i] + r[c][i]));
      if (std::isnan(r[c][i])) return r[c][i];
      if (scale > 0.0) worst = std::max(worst, std::fabs(r[c][i]) / scale);
    }
  return worst;
}

double residualPower(const RadiositySystem& system, const Channels& r) {
  double power = 0.0;
  for (int i = 0; i < system.size(); ++i)
    power += system.area[i] * (std::fabs(r[0][i]) + std::fabs(r[1][i]) + std::fabs(r[2][i]));
  return power;
}

}  // namespace radkit
