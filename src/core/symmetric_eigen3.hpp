// The eigenvalues and eigenvectors of a symmetric 3 x 3 matrix (an inertia tensor) by cyclic
// Jacobi rotations (Golub & Van Loan, Matrix Computations, 4th ed., section 8.5): accurate to
// round-off relative to the matrix's norm, whatever its spread of eigenvalues. Written here
// because it is a dozen lines and a linear-algebra package for one 3 x 3 matrix a shape is not
// worth its dependency.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

namespace yuxi {

struct SymmetricEigen3 {
  std::array<double, 3> values{};              // ascending
  std::array<std::array<double, 3>, 3> axes{}; // axes[k]: the unit eigenvector of values[k]
};

// a: the symmetric matrix, a[r][c]. The eigenvectors form a right-handed frame
// (axes[0] x axes[1] = axes[2]).
inline SymmetricEigen3 symmetric_eigen3(std::array<std::array<double, 3>, 3> a) {
  // Scaled by a power of two (exactly) to entries of order one, so that the squares of the
  // stopping test neither underflow nor overflow (an inertia tensor goes as size^5).
  double largest = 0;
  for (const auto& row : a)
    for (const double x : row) largest = std::max(largest, std::abs(x));
  const int exponent = largest > 0 && std::isfinite(largest) ? std::ilogb(largest) : 0;
  for (auto& row : a)
    for (double& x : row) x = std::ldexp(x, -exponent);
  std::array<std::array<double, 3>, 3> v{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}}; // columns: vectors
  for (int sweep = 0; sweep < 64; ++sweep) {
    const double off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
    const double diag = a[0][0] * a[0][0] + a[1][1] * a[1][1] + a[2][2] * a[2][2];
    if (off <= 1e-36 * diag || off == 0.0) break;
    for (int p = 0; p < 2; ++p)
      for (int q = p + 1; q < 3; ++q) {
        if (a[p][q] == 0.0) continue;
        // The rotation in the (p, q) plane that zeroes a[p][q]: t = tan(theta) of the smaller
        // root of t^2 + 2 tau t - 1 = 0.
        const double tau = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
        const double t = (tau >= 0 ? 1.0 : -1.0) / (std::abs(tau) + std::sqrt(1.0 + tau * tau));
        const double c = 1.0 / std::sqrt(1.0 + t * t), s = t * c;
        for (int k = 0; k < 3; ++k) { // a <- a J
          const double akp = a[k][p], akq = a[k][q];
          a[k][p] = c * akp - s * akq;
          a[k][q] = s * akp + c * akq;
        }
        for (int k = 0; k < 3; ++k) { // a <- J^T a
          const double apk = a[p][k], aqk = a[q][k];
          a[p][k] = c * apk - s * aqk;
          a[q][k] = s * apk + c * aqk;
        }
        for (int k = 0; k < 3; ++k) { // v <- v J
          const double vkp = v[k][p], vkq = v[k][q];
          v[k][p] = c * vkp - s * vkq;
          v[k][q] = s * vkp + c * vkq;
        }
      }
  }
  std::array<int, 3> order{0, 1, 2};
  std::sort(order.begin(), order.end(), [&](int i, int j) { return a[i][i] < a[j][j]; });
  SymmetricEigen3 e;
  for (int k = 0; k < 3; ++k) {
    e.values[k] = std::ldexp(a[order[k]][order[k]], exponent);
    for (int r = 0; r < 3; ++r) e.axes[k][r] = v[r][order[k]];
  }
  // Right-handed: the third axis is the cross product of the first two.
  const auto& x = e.axes[0];
  const auto& y = e.axes[1];
  e.axes[2] = {x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0]};
  return e;
}

} // namespace yuxi
