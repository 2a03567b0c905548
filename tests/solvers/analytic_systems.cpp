#include "analytic_systems.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

namespace radkit::test {

std::string storageLabel(Storage s) {
  switch (s) {
    case Storage::DenseDouble:
      return "dense-double";
    case Storage::DenseFloat:
      return "dense-float";
    case Storage::CsrDouble:
      return "csr-double";
    default:
      return "csr-float";
  }
}

namespace {

template <typename T>
DenseMatrix<T> dense(const std::vector<double>& f, int n) {
  DenseMatrix<T> m(n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) m(i, j) = static_cast<T>(f[std::size_t(i) * n + j]);
  return m;
}

template <typename T>
CsrMatrix<T> csr(const std::vector<double>& f, int n) {
  std::vector<std::int64_t> start{0};
  std::vector<int> column;
  std::vector<T> value;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j)
      if (f[std::size_t(i) * n + j] != 0.0) {
        column.push_back(j);
        value.push_back(static_cast<T>(f[std::size_t(i) * n + j]));
      }
    start.push_back(static_cast<std::int64_t>(column.size()));
  }
  return CsrMatrix<T>(n, std::move(start), std::move(column), std::move(value));
}

}  // namespace

Problem makeProblem(const std::vector<double>& f, std::vector<double> area, Channels rho,
                    Channels e, Storage s) {
  const int n = static_cast<int>(area.size());
  if (f.size() != std::size_t(n) * n) throw std::invalid_argument("makeProblem: F size");
  Problem p;
  switch (s) {
    case Storage::DenseDouble:
      p.f = std::make_shared<FormFactorMatrix>(dense<double>(f, n));
      break;
    case Storage::DenseFloat:
      p.f = std::make_shared<FormFactorMatrix>(dense<float>(f, n));
      break;
    case Storage::CsrDouble:
      p.f = std::make_shared<FormFactorMatrix>(csr<double>(f, n));
      break;
    case Storage::CsrFloat:
      p.f = std::make_shared<FormFactorMatrix>(csr<float>(f, n));
      break;
  }
  p.system.formFactors = p.f.get();
  p.system.area = std::move(area);
  p.system.reflectance = std::move(rho);
  p.system.emission = std::move(e);
  return p;
}

Channels grey(const std::vector<double>& v) { return {v, v, v}; }

std::vector<double> sphereFormFactors(const std::vector<double>& area) {
  const std::size_t n = area.size();
  double total = 0.0;
  for (double a : area) total += a;
  std::vector<double> f(n * n);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) f[i * n + j] = area[j] / total;
  return f;
}

std::vector<double> platesFormFactors() { return {0.0, 1.0, 1.0, 0.0}; }

std::vector<double> cubeFormFactors() {
  std::vector<double> f(36, 0.0);
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
      if (i != j) f[i * 6 + j] = (i / 2 == j / 2) ? kCubeOpposite : kCubeAdjacent;
  return f;
}

Problem randomReciprocal(int n, unsigned seed, Storage s) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<double> sym(std::size_t(n) * n, 0.0), area(n);
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      sym[std::size_t(i) * n + j] = sym[std::size_t(j) * n + i] = unit(rng);
  for (double& a : area) a = 0.5 + 1.5 * unit(rng);
  double largest = 0.0;
  for (int i = 0; i < n; ++i) {
    double row = 0.0;
    for (int j = 0; j < n; ++j) row += sym[std::size_t(i) * n + j] / area[i];
    largest = std::max(largest, row);
  }
  const double c = 0.98 / largest;  // one common factor keeps A_i F_ij = c S_ij symmetric
  std::vector<double> f(sym.size());
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      f[std::size_t(i) * n + j] = c * sym[std::size_t(i) * n + j] / area[i];
  Channels rho = makeChannels(n), e = makeChannels(n);
  for (int i = 0; i < n; ++i)
    for (int ch = 0; ch < 3; ++ch) {
      rho[ch][i] = unit(rng) < 0.2 ? 0.0 : 0.9 * unit(rng);
      e[ch][i] = unit(rng) < 0.5 ? 0.0 : unit(rng);
    }
  return makeProblem(f, area, rho, e, s);
}

Channels directSolve(const RadiositySystem& system) {
  const int n = system.size();
  Channels out = makeChannels(n);
  for (int c = 0; c < 3; ++c) {
    std::vector<long double> a(std::size_t(n) * (n + 1));
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) {
        const long double fij = std::visit(
            [&](const auto& m) { return static_cast<long double>(m(i, j)); }, system.matrix());
        a[std::size_t(i) * (n + 1) + j] = (i == j ? 1.0L : 0.0L) - system.reflectance[c][i] * fij;
      }
      a[std::size_t(i) * (n + 1) + n] = system.emission[c][i];
    }
    auto at = [&](int i, int j) -> long double& { return a[std::size_t(i) * (n + 1) + j]; };
    for (int k = 0; k < n; ++k) {
      int pivot = k;
      for (int i = k + 1; i < n; ++i)
        if (std::fabs(at(i, k)) > std::fabs(at(pivot, k))) pivot = i;
      for (int j = 0; j <= n; ++j) std::swap(at(k, j), at(pivot, j));
      for (int i = k + 1; i < n; ++i) {
        const long double m = at(i, k) / at(k, k);
        for (int j = k; j <= n; ++j) at(i, j) -= m * at(k, j);
      }
    }
    for (int i = n - 1; i >= 0; --i) {
      long double s = at(i, n);
      for (int j = i + 1; j < n; ++j) s -= at(i, j) * static_cast<long double>(out[c][j]);
      out[c][i] = static_cast<double>(s / at(i, i));
    }
  }
  return out;
}

double relativeError(const Channels& a, const Channels& b) {
  double err = 0.0;
  for (int c = 0; c < 3; ++c)
    for (std::size_t i = 0; i < b[c].size(); ++i) err = std::max(err, std::fabs(a[c][i] - b[c][i]));
  const double scale = maxAbs(b);
  return scale > 0.0 ? err / scale : err;
}

}  // namespace radkit::test
