// The near pairs' counterpart for meshes (core/near_pairs.hpp): of each grain's candidate
// triangles in the neighbour list, those that can touch before the near pairs are picked again.
//
// A mesh's candidates are the triangles whose box, grown by the skin, a grain's sphere reached
// at the list build; a grain resting on a mesh lists several for each one it touches, and each
// costs a closest-point test per step. The near elements of a still mesh are those closer than
// r + margin to the grain's centre when picked (the margin of the near pairs). A triangle left
// out was farther than that; the mesh does not move, and while every grain has moved less than
// margin/2 since, it cannot touch. So the contact search finds the same touches, in the same
// order, through the near elements as through the whole list: the same bits. A moving mesh
// keeps all its candidates, and a cylinder has none.
#pragma once

#include "core/neighbor_list.hpp"
#include "core/particle_store.hpp"
#include "scene/shaped_wall.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace yuxi {

struct NearWallElements {
  std::vector<std::uint32_t> elements; // triangle indices, candidate after candidate
  std::vector<std::uint32_t> start;    // candidate k's: elements[start[k] .. start[k + 1])
  bool picked = false;                 // (valid while the near pairs hold)

  std::span<const std::uint32_t> of(std::size_t k) const {
    return {elements.data() + start[k], start[k + 1] - start[k]};
  }
  std::size_t memory_bytes() const {
    return (elements.capacity() + start.capacity()) * sizeof(std::uint32_t);
  }
};

// Picks the near elements of every listed wall candidate (NeighborList::walls), with the
// meshes placed as they are now.
void pick_near_wall_elements(const ParticleStore& s, const NeighborList& list,
                             const std::vector<ShapedWall>& walls, double margin,
                             NearWallElements& near);

} // namespace yuxi
