// libFuzzer target for the arrays of the Python module's System(F, area, reflectance, emission):
// the bytes become the arrays numpy and scipy would hand over, which go through the checks the
// module uses (solvers/system_input.h). A SystemInputError is the clean refusal; an accepted
// system is solved for a few iterations by every built-in solver, whose B must stay finite.
// Any other exception, a sanitizer report, a non-finite B or an unknown exit is a finding; but
// southwell and cg need a reciprocal F (A_i F_ij = A_j F_ji, docs/solvers.md), which the
// checks do not ask of F, so on a non-reciprocal one they may end "diverged" with B infinite.
//
// Input, read front to back (bytes past the end read as 0):
//   byte  format: bits 0-1 F as 0 dense, 1 CSR, 2 CSC, 3 COO; bit 2 reflectance grey (n,)
//         else (n, 3); bit 3 emission grey; bit 4 the per-patch residual norm; bit 5 indptr
//         given raw (else made from per-row counts, always well formed); bit 6 twisted shapes
//   byte  n, signed (F is n x n; 0 and negative sizes are refused)
//   if twisted shapes: 4 signed bytes added to F's columns and to the lengths of area,
//         reflectance and emission (scipy's arrays can be set to any length)
//   F     dense: n x n values. CSR/CSC: nnz (byte), nnz (index, value) pairs, then indptr:
//         raw, a length byte and that many indices; or n counts (bytes, each capped to the
//         entries left; the last pointer is nnz). COO: nnz (byte), then (row, col, value)
//   area, reflectance, emission: their values in order
// An index is a signed byte, or after -128 eight bytes of int64. A value is a byte b: below
// 0xE0 a plain number (F: b / 200 / n, so random rows sum near 1; area b / 50; reflectance
// b / 200; emission b / 100), else a special: raw double, NaN, ±inf, -0, -1, 1e300, 1e-300,
// the smallest subnormal, the largest double, 1 − 2⁻⁵³, 1 + 2⁻⁵², 1.05 (the row-sum limit).
// RADKIT_FUZZ_VERBOSE=1 prints each input's refusal or the exits of its solves (to read a seed or
// a finding: build-sanitize/fuzz/fuzz_python_arrays FILE).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <set>
#include <string>
#include <variant>
#include <vector>

#include "solvers/registry.h"
#include "solvers/system_input.h"

namespace {

using namespace radkit;

class Reader {
 public:
  Reader(const std::uint8_t* data, std::size_t size) : m_data(data), m_size(size) {}
  std::uint8_t byte() { return m_pos < m_size ? m_data[m_pos++] : 0; }
  std::int64_t raw64() {
    std::uint64_t v = 0;
    for (int k = 0; k < 8; ++k) v |= std::uint64_t(byte()) << (8 * k);
    std::int64_t s;
    std::memcpy(&s, &v, sizeof s);
    return s;
  }
  std::int64_t index() {
    const auto v = static_cast<std::int8_t>(byte());
    return v == -128 ? raw64() : v;
  }
  /// A value: plain numbers scaled by `scale`, specials as they are.
  double value(double scale) {
    const std::uint8_t b = byte();
    if (b < 0xE0) return b * scale;
    constexpr double kMax = std::numeric_limits<double>::max();
    switch (b) {
      case 0xE0: {
        const std::int64_t bits = raw64();
        double d;
        std::memcpy(&d, &bits, sizeof d);
        return d;
      }
      case 0xE1:
        return std::numeric_limits<double>::quiet_NaN();
      case 0xE2:
        return std::numeric_limits<double>::infinity();
      case 0xE3:
        return -std::numeric_limits<double>::infinity();
      case 0xE4:
        return -0.0;
      case 0xE5:
        return -1.0;
      case 0xE6:
        return 1e300;
      case 0xE7:
        return 1e-300;
      case 0xE8:
        return std::numeric_limits<double>::denorm_min();
      case 0xE9:
        return kMax;
      case 0xEA:
        return 1.0 - std::ldexp(1.0, -53);
      case 0xEB:
        return 1.0 + std::ldexp(1.0, -52);
      case 0xEC:
        return 1.0 + kRowSumTolerance;
      default:
        return (b - 0xEC) * 0.0625;  // 0 .. 1.1875 in sixteenths
    }
  }

 private:
  const std::uint8_t* m_data;
  std::size_t m_size, m_pos = 0;
};

struct OwnedArray {
  std::vector<double> values;
  std::vector<std::int64_t> shape;
  ArrayInput input() const { return {{values.data(), values.size()}, shape}; }
};

/// Per-patch values: `length` rows of 1 (grey) or 3.
OwnedArray patchArray(Reader& in, std::int64_t length, bool grey, double scale) {
  OwnedArray a;
  length = std::max<std::int64_t>(length, 0);
  a.shape = grey ? std::vector<std::int64_t>{length} : std::vector<std::int64_t>{length, 3};
  a.values.resize(static_cast<std::size_t>(length) * (grey ? 1 : 3));
  for (double& v : a.values) v = in.value(scale);
  return a;
}

[[noreturn]] void finding(const std::string& what) {
  std::fprintf(stderr, "python_arrays_fuzzer: %s\n", what.c_str());
  std::abort();
}

const bool kVerbose = std::getenv("RADKIT_FUZZ_VERBOSE") != nullptr;

/// A_i F_ij = A_j F_ji for every pair, to 1e-9 relative.
bool reciprocal(const RadiositySystem& s) {
  return std::visit(
      [&](const auto& m) {
        for (int i = 0; i < s.size(); ++i)
          for (int j = 0; j < i; ++j) {
            const double a = s.area[i] * m(i, j), b = s.area[j] * m(j, i);
            if (std::fabs(a - b) > 1e-9 * std::max(a, b)) return false;
          }
        return true;
      },
      s.matrix());
}

void solveWithEverySolver(const RadiositySystem& system, bool perPatch) {
  const bool isReciprocal = reciprocal(system);
  static const std::set<std::string> kExits{"converged", "max_iterations", "time_limit",
                                            "stagnated", "diverged",       "predicted_over_budget"};
  for (const std::string& name : solverNames()) {
    SolverSettings settings;
    settings.tolerance = 1e-12;
    settings.maxIterations = 20;  // Southwell: 20 shots
    settings.norm = perPatch ? ResidualNorm::PerPatch : ResidualNorm::Relative;
    const std::unique_ptr<Solver> solver = makeSolver(name);
    const SolveResult r = solve(*solver, system, settings);
    if (!kExits.count(r.exit)) finding(name + ": unknown exit '" + r.exit + "': " + r.reason);
    const bool held = isReciprocal || (name != "southwell" && name != "cg");
    if (!allFinite(r.radiosity) && (held || r.exit != "diverged"))
      finding(name + ": B not finite; " + r.exit + ": " + r.reason);
    if (kVerbose)
      std::fprintf(stderr, "%d patches, %s: %s\n", system.size(), name.c_str(), r.reason.c_str());
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* bytes, std::size_t size) {
  Reader in(bytes, size);
  const std::uint8_t format = in.byte();
  const std::int64_t n = static_cast<std::int8_t>(in.byte());
  std::int64_t extra[4] = {0, 0, 0, 0};  // F's columns, area, reflectance, emission lengths
  if (format & 0x40)
    for (std::int64_t& e : extra) e = static_cast<std::int8_t>(in.byte());
  const double fScale = 1.0 / 200.0 / double(std::max<std::int64_t>(n, 1));
  std::vector<std::int64_t> indptr, indices, rows;
  std::vector<double> data;
  try {
    FormFactorMatrix f;
    const std::int64_t cols = n + extra[0];
    switch (format & 3) {
      case 0: {
        OwnedArray dense;
        dense.shape = {n, cols};
        const std::int64_t count = n > 0 && cols > 0 ? n * cols : 0;
        dense.values.resize(static_cast<std::size_t>(count));
        for (double& v : dense.values) v = in.value(fScale);
        f = checkedDenseFormFactors(dense.input());
        break;
      }
      case 1:
      case 2: {
        const int nnz = in.byte();
        for (int k = 0; k < nnz; ++k) {
          indices.push_back(in.index());
          data.push_back(in.value(fScale));
        }
        if (format & 0x20) {
          const int length = in.byte();
          for (int k = 0; k < length; ++k) indptr.push_back(in.index());
        } else {
          const std::int64_t major = (format & 3) == 2 ? cols : n;
          indptr.push_back(0);
          for (std::int64_t i = 0; i < major; ++i)
            indptr.push_back(std::min<std::int64_t>(nnz, indptr.back() + in.byte() % 8));
          if (!indptr.empty() && major > 0) indptr.back() = nnz;
        }
        CompressedInput c;
        c.columns = (format & 3) == 2;
        c.rows = n, c.cols = cols;
        c.indptr = {indptr.data(), indptr.size()};
        c.indices = {indices.data(), indices.size()};
        c.data = {data.data(), data.size()};
        f = checkedCompressedFormFactors(c);
        break;
      }
      default: {
        const int nnz = in.byte();
        for (int k = 0; k < nnz; ++k) {
          rows.push_back(in.index());
          indices.push_back(in.index());
          data.push_back(in.value(fScale));
        }
        CooInput c;
        c.rows = n, c.cols = cols;
        c.row = {rows.data(), rows.size()};
        c.col = {indices.data(), indices.size()};
        c.data = {data.data(), data.size()};
        f = checkedCooFormFactors(c);
        break;
      }
    }
    const OwnedArray area = patchArray(in, n + extra[1], true, 1.0 / 50.0);
    const OwnedArray rho = patchArray(in, n + extra[2], format & 4, 1.0 / 200.0);
    const OwnedArray e = patchArray(in, n + extra[3], format & 8, 1.0 / 100.0);
    const RadiositySystem system = checkedSystem(f, area.input(), rho.input(), e.input());
    system.validate();  // the solvers' own check must accept what these checks accept
    solveWithEverySolver(system, format & 0x10);
  } catch (const SystemInputError& error) {
    // A clean refusal naming the element: what bad arrays must give.
    if (kVerbose) std::fprintf(stderr, "refused: %s\n", error.what());
  }
  return 0;
}
