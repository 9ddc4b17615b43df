// Coarse-graining on a cylindrical grid, for silos, drums and the basin (docs/coarse-graining.md,
// "Cylindrical grids"): about an axis parallel to z through (x0, y0), n_r x n_theta x n_z points at
// the centres of equal cells of [r_lo, r_hi] x [0, 2 pi) x [z_lo, z_hi] (theta from +x towards
// +y). Theta, z or both may be averaged: the fields are then means around the circle, or over
// [z_lo, z_hi] (of the grains, and the parts of branches, within it). The fields are those of
// coarse_grain.hpp, evaluated at each point with the function of the Cartesian distance (3-D; 2-D
// in x, y where z is averaged); a mean around the circle samples it w / 8 apart at r_hi, which
// gives the mean to about 1e-5 of the field's largest value (the trapezoidal rule; the cut
// functions are not smooth at their cutoff, so the rule is of second order).
// Plain bins are the cells of the grid: annular sectors (annuli where theta is averaged, as 256
// sectors whose vectors and tensors are each turned into the basis at the sector's middle: exact
// for scalars, to about 1e-5 for the rest). Vectors and tensors are given in the local basis
// (e_r, e_theta, e_z) of each point.
// Points are stored with r fastest: index = (k * n_theta + j) * n_r + i.
#pragma once

#include "analysis/coarse_grain.hpp"

#include <array>
#include <cstddef>
#include <span>
#include <vector>

namespace yuxi::analysis {

struct CgCylinder {
  double x0 = 0.0, y0 = 0.0;     // the axis, parallel to z, m
  double r_lo = 0.0, r_hi = 1.0; // m
  double z_lo = 0.0, z_hi = 1.0; // m
  std::array<int, 3> n{1, 1, 1}; // points along r, theta, z (1 where averaged)
  bool theta_averaged = false, z_averaged = false;

  // Throws std::invalid_argument naming the problem: r_lo < 0, hi <= lo, n < 1, an averaged
  // axis with n != 1.
  void check() const;
  std::size_t size() const { return static_cast<std::size_t>(n[0]) * n[1] * n[2]; }
  std::size_t index(int i, int j, int k) const {
    return (static_cast<std::size_t>(k) * n[1] + j) * n[0] + i;
  }
  double r(int i) const { return r_lo + (i + 0.5) * (r_hi - r_lo) / n[0]; }
  double theta(int j) const; // rad; pi where averaged
  double z(int k) const { return z_lo + (k + 0.5) * (z_hi - z_lo) / n[2]; }
  // The volume of cell (i, any j, any k), m^3: an annular sector (or annulus) of its height.
  double cell_volume(int i) const;
};

struct CgCylinderSettings {
  CgKind kind = CgKind::gaussian;
  double width = 0.0, cutoff = 0.0; // w, c, m (bins: unused)
  CgCylinder grid;
  CgParts parts;
};

// The sums at every point of the grid (cg_sums_per_point a point, vectors and tensors in the
// point's basis); coarse_grain_fields(sums, grid.size()) makes the fields. Sums of parts add up,
// as on a Cartesian grid. Throws std::invalid_argument for bad settings.
std::vector<double> coarse_grain_sums(const CgGrains& grains, std::span<const CgContact> contacts,
                                      const CgCylinderSettings& settings);

// Both.
CgFields coarse_grain(const CgGrains& grains, std::span<const CgContact> contacts,
                      const CgCylinderSettings& settings);

} // namespace yuxi::analysis
