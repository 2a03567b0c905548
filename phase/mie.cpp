// Mie theory (mie.h): Bohren and Huffman's (1983) series of chapter 4 (a_n, b_n through the
// logarithmic derivative D_n as in section 4.8, Q_sca, Q_ext, Q_back and g as sums over them,
// S1 and S2 through the angular functions π_n, τ_n), and Hansen and Travis's (1974) gamma
// distribution of radii.
#include "phase/mie.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "util/format.h"
#include "util/vec3.h"

namespace radkit {

using Complex = std::complex<double>;

double MieSphere::phase(int i, double x) const {
  return (std::norm(s1[i]) + std::norm(s2[i])) / (2 * kPi * x * x * qsca);
}

MieSphere mieSphere(double x, Complex m, const std::vector<double>& cosines) {
  if (!(x > 0 && x <= 1e5))
    throw std::invalid_argument("mieSphere: size parameter x " + formatNumber(x) +
                                " is outside (0, 1e5]");
  if (!(m.real() > 0) || !(m.imag() >= 0))
    throw std::invalid_argument("mieSphere: refractive index needs Re m > 0 and Im m >= 0");
  MieSphere r;
  // Wiscombe (1980), "Improved Mie scattering algorithms", Appl. Opt. 19, 1505: enough terms.
  const int nStop = std::max(1, int(x + 4 * std::cbrt(x) + 2));
  r.terms = nStop;
  // D_n(mx) = ψ_n'(mx)/ψ_n(mx) by downward recurrence (upward is unstable for Im(mx) > 0) from
  // D = 0. Errors of the start decay only above the turning point n ≈ |mx|, whose width grows
  // as |mx|^{1/3}: BHMIE's start, max(nStop, |mx|) + 15, leaves D_n wrong by O(1) near n ≈ x
  // at x = 1000 (Q_ext off by 0.16 %; 7e-3 in D_n at x = 114, against scipy's spherical Bessel
  // functions), so 8|mx|^{1/3} more terms are run, which brings D_n to ~1e-12 there.
  const Complex mx = m * x;
  const double mxAbs = std::abs(mx);
  const int nStart = int(std::max(double(nStop), mxAbs) + 15 + 8 * std::cbrt(mxAbs));
  std::vector<Complex> d(nStart + 1, Complex(0));
  for (int n = nStart; n >= 1; --n) {
    const Complex nz = double(n) / mx;
    d[n - 1] = nz - 1.0 / (d[n] + nz);
  }
  // Riccati-Bessel ψ_n(x) = x j_n(x) and χ_n(x) = −x y_n(x) upward, ξ_n = ψ_n − iχ_n.
  std::vector<Complex> a(nStop + 2, Complex(0)), b(nStop + 2, Complex(0));
  double psiPrev = std::cos(x), psi = std::sin(x);   // ψ_{-1}, ψ_0
  double chiPrev = -std::sin(x), chi = std::cos(x);  // χ_{-1}, χ_0
  double sumExt = 0, sumSca = 0;
  Complex sumBack(0);
  for (int n = 1; n <= nStop; ++n) {
    const double k = (2.0 * n - 1) / x;
    const double psiNext = k * psi - psiPrev, chiNext = k * chi - chiPrev;
    psiPrev = psi, psi = psiNext, chiPrev = chi, chi = chiNext;
    const Complex xi(psi, -chi), xiPrev(psiPrev, -chiPrev);
    const double nx = n / x;
    const Complex da = d[n] / m + nx, db = m * d[n] + nx;
    a[n] = (da * psi - psiPrev) / (da * xi - xiPrev);
    b[n] = (db * psi - psiPrev) / (db * xi - xiPrev);
    const double w = 2.0 * n + 1;
    sumExt += w * (a[n].real() + b[n].real());
    sumSca += w * (std::norm(a[n]) + std::norm(b[n]));
    sumBack += w * (n % 2 ? -1.0 : 1.0) * (a[n] - b[n]);
  }
  double sumG = 0;
  for (int n = 1; n <= nStop; ++n) {
    // a_{nStop+1} = b_{nStop+1} = 0: the series is truncated there.
    sumG +=
        n * (n + 2.0) / (n + 1) * (a[n] * std::conj(a[n + 1]) + b[n] * std::conj(b[n + 1])).real() +
        (2.0 * n + 1) / (n * (n + 1.0)) * (a[n] * std::conj(b[n])).real();
  }
  r.qext = 2 / (x * x) * sumExt;
  r.qsca = 2 / (x * x) * sumSca;
  r.qback = std::norm(sumBack) / (x * x);
  r.g = 4 / (x * x) * sumG / r.qsca;

  // Amplitude functions through π_n = P_n^1/sin θ and τ_n = dP_n^1/dθ, by their recurrences
  // π_{n+1} = ((2n+1) μ π_n − (n+1) π_{n−1})/n, τ_n = n μ π_n − (n+1) π_{n−1}.
  for (int n = 1; n <= nStop; ++n) {
    const double f = (2.0 * n + 1) / (n * (n + 1.0));
    a[n] *= f, b[n] *= f;  // the weights folded in once, not once per angle
  }
  r.s1.resize(cosines.size());
  r.s2.resize(cosines.size());
  for (size_t i = 0; i < cosines.size(); ++i) {
    const double mu = cosines[i];
    double piPrev = 0, pi = 1;
    double s1r = 0, s1i = 0, s2r = 0, s2i = 0;  // real arithmetic: ~2x faster than complex
    for (int n = 1; n <= nStop; ++n) {
      const double tau = n * mu * pi - (n + 1) * piPrev;
      s1r += a[n].real() * pi + b[n].real() * tau;
      s1i += a[n].imag() * pi + b[n].imag() * tau;
      s2r += a[n].real() * tau + b[n].real() * pi;
      s2i += a[n].imag() * tau + b[n].imag() * pi;
      const double piNext = ((2.0 * n + 1) * mu * pi - (n + 1.0) * piPrev) / n;
      piPrev = pi, pi = piNext;
    }
    r.s1[i] = {s1r, s1i};
    r.s2[i] = {s2r, s2i};
  }
  return r;
}

TabulatedPhase MiePhase::table() const { return TabulatedPhase(theta, phase, "mie-cloud"); }

MiePhase mieCloud(const MieCloudSettings& s) {
  const Clock::time_point t0 = Clock::now();
  const double a = s.effectiveRadius, v = s.effectiveVariance;
  if (!(a > 0) || !(v > 0 && v < 0.5) || !(s.wavelength > 0) || !(s.mediumIndex > 0))
    throw std::invalid_argument(
        "mieCloud: needs r_eff > 0, v_eff in (0, 0.5), wavelength > 0 "
        "and medium index > 0");
  if (s.radii < 8 || s.angles < 3)
    throw std::invalid_argument("mieCloud: needs at least 8 radii and 3 angles");
  // n(r) ∝ r^α e^{−r/β}, α = (1 − 3v)/v, β = a v. The cross section (∝ r² for r ≫ λ) weights
  // it further by r², so the radii that matter are those where r^{α+2} e^{−r/β} is within
  // e^{−18} (~1.5e-8) of its peak at (α + 2)β.
  const double alpha = (1 - 3 * v) / v, beta = a * v;
  const auto logWeight = [&](double r) { return (alpha + 2) * std::log(r) - r / beta; };
  const double rPeak = (alpha + 2) * beta, peak = logWeight(rPeak);
  double rLo = rPeak, rHi = rPeak;
  while (rLo > 1e-3 * rPeak && logWeight(rLo) > peak - 18) rLo *= 0.98;
  while (logWeight(rHi) > peak - 18) rHi *= 1.02;

  MiePhase out;
  out.theta = forwardRefinedAngles(s.angles);
  std::vector<double> cosines(out.theta.size());
  for (size_t i = 0; i < cosines.size(); ++i) cosines[i] = std::cos(out.theta[i]);
  const int nr = s.radii;
  out.radii.resize(nr);
  out.radiusG.resize(nr);
  for (int j = 0; j < nr; ++j) out.radii[j] = rLo + (rHi - rLo) * j / (nr - 1);

  const double k = 2 * kPi * s.mediumIndex / s.wavelength;  // wavenumber in the medium
  const Complex m = s.refractiveIndex / s.mediumIndex;
  // Per radius: n(r)·dr·C_sca, n(r)·dr·C_ext, and n(r)·dr·(|S1|² + |S2|²)/(2k²), the latter
  // being C_sca times that radius's phase function.
  std::vector<double> wSca(nr), wExt(nr), wNumber(nr);
  std::vector<std::vector<double>> contribution(nr);
  tbb::parallel_for(0, nr, [&](int j) {
    const double r = out.radii[j];
    const double trapezoid = (j == 0 || j == nr - 1) ? 0.5 : 1.0;
    // Normalised to the peak so that r^α stays representable for small v.
    const double w = trapezoid * std::exp(alpha * std::log(r / rPeak) - (r - rPeak) / beta);
    const MieSphere sphere = mieSphere(k * r, m, cosines);
    const double area = kPi * r * r;
    wNumber[j] = w;
    wSca[j] = w * sphere.qsca * area;
    wExt[j] = w * sphere.qext * area;
    out.radiusG[j] = sphere.g;
    std::vector<double>& c = contribution[j];
    c.resize(cosines.size());
    for (size_t i = 0; i < cosines.size(); ++i)
      c[i] = w * (std::norm(sphere.s1[i]) + std::norm(sphere.s2[i])) / (2 * k * k);
  });
  // Summed in a fixed order: the table does not depend on the thread count.
  double number = 0, sca = 0, ext = 0, gSum = 0;
  out.phase.assign(cosines.size(), 0);
  out.weights = wNumber;
  for (int j = 0; j < nr; ++j) {
    number += wNumber[j], sca += wSca[j], ext += wExt[j], gSum += wSca[j] * out.radiusG[j];
    for (size_t i = 0; i < cosines.size(); ++i) out.phase[i] += contribution[j][i];
  }
  for (double& p : out.phase) p /= sca;
  out.crossSectionScattering = sca / number;
  out.crossSectionExtinction = ext / number;
  out.g = gSum / sca;
  out.seconds = secondsSince(t0);
  return out;
}

}  // namespace radkit
