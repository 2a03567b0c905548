#include "solvers/matrix.h"

namespace radkit {

std::string storageName(const FormFactorMatrix& f) {
  switch (f.index()) {
    case 0:
      return "dense-double";
    case 1:
      return "dense-float";
    case 2:
      return "csr-double";
    default:
      return "csr-float";
  }
}

int matrixSize(const FormFactorMatrix& f) {
  return std::visit([](const auto& m) { return m.rows(); }, f);
}

std::size_t matrixBytes(const FormFactorMatrix& f) {
  return std::visit([](const auto& m) { return m.bytes(); }, f);
}

}  // namespace radkit
