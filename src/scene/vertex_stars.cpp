#include "scene/vertex_stars.hpp"

namespace yuxi {

VertexStars VertexStars::of(const TriangleMesh& mesh) {
  // A counting sort of the (vertex, triangle) incidences: triangles come out ascending.
  VertexStars s;
  s.first.assign(mesh.vertices.size() + 1, 0);
  for (const auto& tri : mesh.triangles)
    for (const std::uint32_t v : tri) ++s.first[v + 1];
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) s.first[v + 1] += s.first[v];
  s.triangles.resize(3 * mesh.n_triangles());
  std::vector<std::uint32_t> next(s.first.begin(), s.first.end() - 1);
  for (std::uint32_t t = 0; t < mesh.n_triangles(); ++t)
    for (const std::uint32_t v : mesh.triangles[t]) s.triangles[next[v]++] = t;
  return s;
}

} // namespace yuxi
