#include <gtest/gtest.h>

#include "solvers/matrix.h"

namespace radkit {

TEST(CsrMatrix, Exact) {
  // [[0 2 0], [1 0 3], [0 0 0]]
  CsrMatrix<double> m(3, {0, 1, 3, 3}, {1, 0, 2}, {2.0, 1.0, 3.0});
  EXPECT_EQ(m(0, 1), 2.0);
  EXPECT_EQ(m(0, 0), 0.0);
  EXPECT_EQ(m(1, 2), 3.0);
  EXPECT_EQ(m(2, 2), 0.0);
  EXPECT_EQ(m.nonZeros(), 3u);
  FormFactorMatrix f = m;
  EXPECT_EQ(storageName(f), "csr-double");
  EXPECT_EQ(matrixSize(f), 3);
}

TEST(CsrMatrix, Construct) {
  EXPECT_THROW(CsrMatrix<float>(3, {0, 1}, {0}, {1.0f}), std::invalid_argument);
}

// RADKIT_DCHECK (util/check.h) guards matrix indices in Debug builds and costs nothing in
// Release: there the condition is not even evaluated.
TEST(DenseMatrix, IndexCheckedInDebugOnly) {
  DenseMatrix<double> m(2);
#ifndef NDEBUG
  EXPECT_DEATH(m(2, 0), "internal check failed: inRange\\(i\\) && inRange\\(j\\)");
#else
  int evaluated = 0;
  RADKIT_DCHECK(++evaluated > 0);
  EXPECT_EQ(evaluated, 0);
  EXPECT_EQ(m(1, 1), 0.0);
#endif
}

}  // namespace radkit
