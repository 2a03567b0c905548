// solvers/system_input.h: a system given as arrays is checked whole before a matrix or a
// solver sees it; each refusal names the argument, the element and the fix.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "solvers/system_input.h"

namespace radkit {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Arrays that own their storage, viewed as the checks take them.
struct CsrArrays {
  std::vector<std::int64_t> indptr, indices;
  std::vector<double> data;
  std::int64_t rows = 3, cols = 3;
  bool columns = false;
  CompressedInput input() const {
    CompressedInput in;
    in.columns = columns;
    in.rows = rows, in.cols = cols;
    in.indptr = {indptr.data(), indptr.size()};
    in.indices = {indices.data(), indices.size()};
    in.data = {data.data(), data.size()};
    return in;
  }
};

struct DenseArrays {
  std::vector<double> values;
  std::vector<std::int64_t> shape;
  ArrayInput input() const { return {{values.data(), values.size()}, shape}; }
};

/// Three patches, each seeing the other two equally.
CsrArrays goodCsr() { return {{0, 2, 4, 6}, {1, 2, 0, 2, 0, 1}, {0.5, 0.5, 0.5, 0.5, 0.5, 0.5}}; }
DenseArrays goodDense() { return {{0, 0.5, 0.5, 0.5, 0, 0.5, 0.5, 0.5, 0}, {3, 3}}; }

template <typename Fn>
void expectRefusal(Fn&& fn, const std::string& fragment) {
  try {
    fn();
    ADD_FAILURE() << "accepted; expected a refusal containing: " << fragment;
  } catch (const SystemInputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(fragment), std::string::npos) << what;
    EXPECT_NE(what.find("Fix:"), std::string::npos) << what;
  }
}

void expectCsrRefused(const CsrArrays& f, const std::string& fragment) {
  expectRefusal([&] { checkedCompressedFormFactors(f.input()); }, fragment);
}

void expectDenseRefused(const DenseArrays& f, const std::string& fragment) {
  expectRefusal([&] { checkedDenseFormFactors(f.input()); }, fragment);
}

TEST(SystemInput, WellFormedInputPasses) {
  const CsrMatrix<double> m = checkedCompressedFormFactors(goodCsr().input());
  EXPECT_EQ(m.rows(), 3);
  EXPECT_EQ(m.nonZeros(), 6u);
  EXPECT_EQ(m(2, 1), 0.5);
  const DenseMatrix<double> d = checkedDenseFormFactors(goodDense().input());
  EXPECT_EQ(d(1, 2), 0.5);
  EXPECT_EQ(d(1, 1), 0.0);
}

TEST(SystemInput, CsrIndicesOutOfRangeAreRefused) {
  for (std::int64_t bad : {std::int64_t(3), std::int64_t(-5), std::int64_t(100000000),
                           std::numeric_limits<std::int64_t>::min()}) {
    CsrArrays f = goodCsr();
    f.indices[3] = bad;
    expectCsrRefused(
        f, "F.indices[3] = " + std::to_string(bad) + " (an entry of row 1) is outside [0, 3)");
  }
}

TEST(SystemInput, CsrPointersAreChecked) {
  CsrArrays f = goodCsr();
  f.indptr[3] = 100000000;
  expectCsrRefused(f, "F.indptr[3] = 100000000 entries, but F.indices has 6 and F.data 6");
  f = goodCsr();
  f.indptr = {0, 4, 2, 6};
  expectCsrRefused(f, "F.indptr[2] = 2 is below F.indptr[1] = 4: row 1 would end before");
  f = goodCsr();
  f.indptr = {0, 2, 4, -6};
  expectCsrRefused(f, "F.indptr[3] = -6 is below F.indptr[2] = 4");
  f = goodCsr();
  f.indptr[0] = 1;
  expectCsrRefused(f, "F.indptr[0] = 1");
  f = goodCsr();
  f.indptr.pop_back();
  expectCsrRefused(f, "F.indptr has 3 entries for 3 rows");
  f = goodCsr();
  f.indptr.clear();
  expectCsrRefused(f, "F.indptr has 0 entries for 3 rows");
  f = goodCsr();
  f.data.pop_back();
  expectCsrRefused(f, "F.indices has 6 and F.data 5");
  f = goodCsr();
  f.indptr[3] = 5;
  expectCsrRefused(f, "F.indptr[3] = 5 entries, but F.indices has 6");
}

TEST(SystemInput, ShapesAreChecked) {
  CsrArrays f = goodCsr();
  f.cols = 4;
  expectCsrRefused(f, "F: expected a square (n, n) matrix, got shape (3, 4)");
  f = CsrArrays{{0}, {}, {}, 0, 0};
  expectCsrRefused(f, "F: shape (0, 0) has no patches");
  f = goodCsr();
  f.rows = f.cols = -3;
  expectCsrRefused(f, "F: expected a square (n, n) matrix, got shape (-3, -3)");
  expectDenseRefused({{}, {-2, 2}}, "F: shape (-2, 2) has a negative extent");
  f.rows = f.cols = std::int64_t(1) << 40;
  expectCsrRefused(f, "patches are more than radkit indexes");
  expectDenseRefused({{0, 0, 0}, {3}}, "F: expected a square (n, n) array, got shape (3,)");
  expectDenseRefused({{0, 0, 0, 0, 0, 0}, {2, 3}}, "got shape (2, 3)");
  expectDenseRefused({{0, 0, 0}, {2, 2}}, "F: 3 values for shape (2, 2)");
}

TEST(SystemInput, DuplicatesAreSummedAndColumnsSorted) {
  // Row 0 lists column 2 before 1, and column 1 twice.
  const CsrArrays f{{0, 3, 5, 7}, {2, 1, 1, 0, 2, 1, 0}, {0.5, 0.25, 0.25, 0.5, 0.5, 0.5, 0.5}};
  const CsrMatrix<double> m = checkedCompressedFormFactors(f.input());
  ASSERT_EQ(m.nonZeros(), 6u);
  EXPECT_EQ(m.column(m.rowBegin(0)), 1);
  EXPECT_EQ(m.column(m.rowBegin(0) + 1), 2);
  EXPECT_EQ(m(0, 1), 0.5);
  EXPECT_EQ(m(2, 0), 0.5);
}

TEST(SystemInput, CscIsTransposedAndItsIndicesAreRows) {
  // Column 0 holds F[1, 0] = 0.25 and F[2, 0] = 0.5; column 1 holds F[0, 1] = 1.
  CsrArrays f{{0, 2, 3, 3}, {1, 2, 0}, {0.25, 0.5, 1.0}};
  f.columns = true;
  const CsrMatrix<double> m = checkedCompressedFormFactors(f.input());
  EXPECT_EQ(m(1, 0), 0.25);
  EXPECT_EQ(m(2, 0), 0.5);
  EXPECT_EQ(m(0, 1), 1.0);
  EXPECT_EQ(m(0, 0), 0.0);
  f.indices[1] = 7;
  expectCsrRefused(f, "F.indices[1] = 7 (an entry of column 0) is outside [0, 3). Fix: row");
}

TEST(SystemInput, CooIsChecked) {
  const std::vector<std::int64_t> row{0, 1, 1}, col{1, 0, 0};
  const std::vector<double> data{1.0, 0.5, 0.25};
  CooInput in{3, 3, {row.data(), 3}, {col.data(), 3}, {data.data(), 3}};
  const CsrMatrix<double> m = checkedCooFormFactors(in);
  EXPECT_EQ(m(1, 0), 0.75);  // duplicates summed
  EXPECT_EQ(m.nonZeros(), 2u);
  const std::vector<std::int64_t> badRow{0, 3, 1};
  in.row = {badRow.data(), 3};
  expectRefusal([&] { checkedCooFormFactors(in); }, "F.row[1] = 3 is outside [0, 3)");
  in.row = {row.data(), 2};
  expectRefusal([&] { checkedCooFormFactors(in); }, "F.row, F.col and F.data have 2, 3 and 3");
}

TEST(SystemInput, EntriesMustBeFiniteAndNonNegative) {
  for (double bad : {-0.9, kNaN, std::numeric_limits<double>::infinity()}) {
    const std::string what = std::isnan(bad) ? "nan is not finite"
                             : bad < 0       ? "-0.9 is negative"
                                             : "inf is not finite";
    DenseArrays d = goodDense();
    d.values[2 * 3 + 1] = bad;
    expectDenseRefused(d, "F[2, 1] = " + what);
    CsrArrays f = goodCsr();
    f.data[5] = bad;
    expectCsrRefused(f, "F.data[5] (F[2, 1]) = " + what);
  }
}

TEST(SystemInput, RowSumsAboveOnePlusTheToleranceAreRefused) {
  DenseArrays d = goodDense();
  d.values[3] = d.values[5] = 0.75;  // row 1 sums to 1.5
  expectDenseRefused(d, "F row 1 sums to 1.5, above 1 + 0.05");
  CsrArrays f = goodCsr();
  f.data[2] = f.data[3] = 0.75;
  expectCsrRefused(f, "F row 1 sums to 1.5");
  d.values[3] = d.values[5] = 0.5 + kRowSumTolerance / 2;  // within the tolerance
  EXPECT_NO_THROW(checkedDenseFormFactors(d.input()));
  // Finite entries whose sum overflows.
  d = {{1e308, 1e308, 0, 0}, {2, 2}};
  expectDenseRefused(d, "F row 0 sums to inf");
  // A patch may see itself (an enclosure given as one patch).
  const DenseArrays enclosure{{0.0, 1.0, 0.25, 0.75}, {2, 2}};
  EXPECT_NO_THROW(checkedDenseFormFactors(enclosure.input()));
}

TEST(SystemInput, PerPatchArraysAreChecked) {
  const FormFactorMatrix f(checkedDenseFormFactors(goodDense().input()));
  const DenseArrays ones{{1, 1, 1}, {3}}, half{{0.5, 0.5, 0.5}, {3}}, lit{{1, 0, 0}, {3}};
  const RadiositySystem s = checkedSystem(f, ones.input(), half.input(), lit.input());
  EXPECT_NO_THROW(s.validate());
  EXPECT_EQ(s.emission[2][0], 1.0);
  const auto refusedWith = [&](const DenseArrays& area, const DenseArrays& rho,
                               const DenseArrays& e, const std::string& fragment) {
    expectRefusal([&] { checkedSystem(f, area.input(), rho.input(), e.input()); }, fragment);
  };
  refusedWith({{1, 0, 1}, {3}}, half, lit, "area[1] = 0 must be finite and > 0");
  refusedWith({{1, kNaN, 1}, {3}}, half, lit, "area[1] = nan");
  refusedWith({{1, 1}, {2}}, half, lit, "area: expected shape (3,), got (2,)");
  refusedWith({{1, 1, 1}, {3, 1}}, half, lit, "area: expected shape (3,), got (3, 1)");
  refusedWith(ones, {{0.5, 0.5, 1.0}, {3}}, lit, "reflectance[2] = 1 is outside [0, 1)");
  refusedWith(ones, {{0.5, 0.5, 0.5, 0.5, -0.1, 0.5, 0.5, 0.5, 0.5}, {3, 3}}, lit,
              "reflectance[1, 1] = -0.1 is outside [0, 1)");
  refusedWith(ones, {{0.5, 0.5}, {2}}, lit, "reflectance: expected shape (3, 3) or (3,)");
  refusedWith(ones, half, {{-1, 0, 0}, {3}}, "emission[0] = -1 must be finite and >= 0");
  refusedWith(ones, half, {{0, 0, std::numeric_limits<double>::infinity()}, {3}},
              "emission[2] = inf");
  // Magnitudes whose products overflow in the solvers (found by fuzz_python_arrays: E at the
  // largest double made B inf in the first sweep).
  refusedWith(ones, half, {{std::numeric_limits<double>::max(), 0, 0}, {3}},
              "emission[0] = 1.797693135e+308 is above 1e+50");
  refusedWith({{1, 1e60, 1}, {3}}, half, lit, "area[1] = 1e+60 is not in [1e-50, 1e+50]");
  refusedWith({{1, 1e-60, 1}, {3}}, half, lit, "area[1] = 1e-60 is not in [1e-50, 1e+50]");
  refusedWith(ones, {{0.5, std::numeric_limits<double>::denorm_min(), 0.5}, {3}}, lit,
              "reflectance[1] = 4.940656458e-324 is below 1e-50 but not 0");
  const DenseArrays edge{{kMaxMagnitude, 1 / kMaxMagnitude, 1}, {3}}, dark{{0, 0.5, 0.5}, {3}};
  EXPECT_NO_THROW(checkedSystem(f, edge.input(), dark.input(), edge.input()));
}

}  // namespace
}  // namespace radkit
