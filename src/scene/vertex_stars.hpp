// The star of each vertex of a triangle mesh: the triangles that hold it. The contact rules
// (wall_touch.hpp, docs/walls.md section 2) read it to tell whether a touch on an edge or a
// vertex lies where that feature is the closest point of every triangle around it.
#pragma once

#include "scene/triangle_mesh.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace yuxi {

struct VertexStars {
  // The triangles of vertex v are triangles[first[v] .. first[v + 1]), ascending.
  std::vector<std::uint32_t> first;
  std::vector<std::uint32_t> triangles;

  static VertexStars of(const TriangleMesh& mesh);

  // Whether this was built for a mesh of that many vertices and triangles.
  bool fits(const TriangleMesh& mesh) const {
    return first.size() == mesh.vertices.size() + 1 && triangles.size() == 3 * mesh.n_triangles();
  }
  std::span<const std::uint32_t> around(std::uint32_t v) const {
    return {triangles.data() + first[v], triangles.data() + first[v + 1]};
  }
};

} // namespace yuxi
