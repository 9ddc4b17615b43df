// The shaped walls of a snapshot as one triangle surface, written as VTK XML PolyData (.vtp,
// ASCII) that ParaView opens beside the particles: each mesh's triangles at their current
// place, each cylinder tessellated, with per triangle (cell data) `force` (what the grains put
// on it), `pressure` (|force . unit normal| / area) and `wall` (the wall's index in the scene).
#pragma once

#include "core/box.hpp"
#include "core/vec3.hpp"
#include "scene/shaped_wall.hpp"

#include <array>
#include <cstdint>
#include <filesystem>
#include <span>
#include <vector>

namespace yuxi {

struct WallSurface {
  std::vector<Vec3> points;
  std::vector<std::array<std::uint32_t, 3>> triangles; // point indices
  std::vector<Vec3> force;                             // on each triangle, by the grains
  std::vector<std::int32_t> wall;                      // each triangle's wall index

  // The triangles of mesh `wall` at its current vertices (MeshWall::x; the rest positions
  // before it was first placed), loaded with `forces` (one per triangle, or empty: zero).
  void add_mesh(const MeshWall& mesh, std::span<const Vec3> forces, std::int32_t wall);
  // Cylinder `wall` cut into `segments` facets around its axis, turned by omega t (so that a
  // turning drum is seen to turn), between its ends, with a triangle fan on each capped end.
  // An infinite end is cut where the axis leaves `box` (the heights of its corners along the
  // axis). No load.
  void add_cylinder(const CylinderWall& cylinder, const Box& box, double t, std::int32_t wall,
                    int segments = 64);
  // |force . unit normal| / area of triangle k (0 for a degenerate one).
  double pressure(std::size_t k) const;
};

// Writes `surface` to `path` (.vtp) from this process alone; throws std::runtime_error if the
// file cannot be written.
void write_vtp(const std::filesystem::path& path, const WallSurface& surface);

} // namespace yuxi
