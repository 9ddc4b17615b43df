// Radial profiles of an x-y field in the sectors of a basin's excitation mode (Li & Cai 2008,
// Figs. 6 and 8; docs/models/fish-basin.md section 7).
//
// A wall that moves radially as cos(m alpha) has 2m antinodes, at azimuths alpha_k = k pi / m
// (k = 0 .. 2m - 1, measured from +x about the basin's axis), and 2m nodes halfway between
// them. A sector is the wedge of half-width `half_width` about one of these directions; a grid
// column belongs to it when its centre's azimuth lies within the wedge and its distance from
// the axis is below `r_max` (the container's inner radius).
//
//  - radial_profile: per radial bin [k dr, (k + 1) dr), the count, mean, median and largest
//    value over the columns of every antinode sector (or every node sector) together, skipping
//    NaN (empty columns of a free surface): how the surface height, or the column's elastic
//    energy, varies with the distance from the axis along the antinodes and the nodes.
//  - sector_peaks: the highest column of each antinode sector: where each jet or surface peak
//    stands (its azimuth and distance from the axis) and how high it is.
//
// Lengths in the scene's units (sigma), angles in radians.
#pragma once

#include "analysis/xy_grid.hpp"
#include "core/vec3.hpp"

#include <cstddef>
#include <vector>

namespace yuxi::analysis {

struct ModeSectors {
  Vec3 axis;         // a point on the vertical axis (z ignored)
  int mode = 2;      // m >= 1
  double half_width; // of each wedge [rad], at most pi / (2m) (wedges do not overlap)
  double r_max;      // columns beyond this distance from the axis are left out [length]
};

enum class SectorKind { antinode, node };

// The azimuth of sector k (0 .. 2m - 1) of a kind [rad].
double sector_azimuth(const ModeSectors& s, SectorKind kind, int k);
// The sector of a kind whose wedge holds the point, or -1.
int sector_of(const ModeSectors& s, SectorKind kind, const Vec3& p);

struct RadialProfile {
  double dr = 0;                         // bin width [length]; bin k is [k dr, (k + 1) dr)
  std::vector<std::size_t> count;        // columns with a finite value
  std::vector<double> mean, median, max; // NaN in a bin without one
};

// Throws std::invalid_argument for a mode < 1, a half-width outside (0, pi / (2m)], or
// dr <= 0 or r_max <= 0.
RadialProfile radial_profile(const GridField& field, const ModeSectors& s, SectorKind kind,
                             double dr);

struct SectorPeak {
  int sector = 0;     // k of the antinode (azimuth k pi / m)
  double azimuth = 0; // of the antinode [rad]
  double r = 0;       // distance of the highest column's centre from the axis [length]
  double value = 0;   // its value (NaN where the sector holds no finite value)
};

// One peak per antinode sector, in sector order.
std::vector<SectorPeak> sector_peaks(const GridField& field, const ModeSectors& s);

} // namespace yuxi::analysis
