// Verlet neighbour list built from linked cells with the half-shell stencil.
//
// A pair (i, j) is listed when |x_i - x_j| < r_i + r_j + range, where range = skin plus any
// extra interaction range of the contact model. The list stays valid until some particle has
// moved more than skin/2 since the build (then no pair can have closed the gap unseen).
//
// Each physical pair is listed exactly once:
//  - owned-owned pairs through the half shell (the cell itself, later members only, plus 13
//    neighbour cells), Newton's third law giving the partner's force;
//  - owned-ghost pairs through all 27 cells, every one: the halo (domain/halo.hpp) gives each
//    rank the ghosts of a half shell, so of the two copies of a pair across ranks or across a
//    periodic boundary only one side holds the other as a ghost.
// Wall-wall pairs are never listed: wall particles move by prescription.
//
// Rows are grouped by the owned particle i (CSR: offsets/partners), and `rows` gives each pair's
// i as well, so that the pair loop scans all pairs as one flat range (core/overlap_scan.hpp);
// the contact history is stored aligned with `partners`.
//
// Where the forces on ghosts travel back to another rank, the pair loop computes the pairs with
// a ghost first, sends those forces, and computes the rest while they travel: `ghost_pairs`
// lists the former (index_ghost_pairs()); the rest are the pairs whose partner is owned.
#pragma once

#include "core/cell_grid.hpp"
#include "core/overlap_scan.hpp"
#include "core/particle_store.hpp"

#include <cstdint>
#include <vector>

namespace yuxi {

// A grain near a flat wall.
struct PlaneContactRef {
  std::uint32_t particle;
  std::uint32_t plane;
};

// A grain near a shaped wall (a mesh or a cylinder), with the triangles of a mesh that it may
// touch before the next build: wall_elements[first, first + count), ascending.
struct WallContactRef {
  std::uint32_t particle;
  std::uint32_t wall;
  std::uint32_t first = 0;
  std::uint32_t count = 0;
};

struct NeighborList {
  std::vector<std::uint32_t> offsets;       // n_owned + 1 row offsets into partners
  std::vector<std::uint32_t> partners;      // j of each pair, grouped by i
  std::vector<std::uint32_t> rows;          // i of each pair (aligned with partners)
  std::vector<PlaneContactRef> planes;      // grain-plane candidate contacts (filled by the owner)
  std::vector<WallContactRef> walls;        // grain-wall candidates (meshes, cylinders; the owner)
  std::vector<std::uint32_t> wall_elements; // their triangles
  std::vector<std::uint32_t> ghost_pairs;   // pairs whose partner is a ghost, ascending (or none)

  std::size_t memory_bytes() const {
    return (offsets.capacity() + partners.capacity() + rows.capacity() + ghost_pairs.capacity()) *
               sizeof(std::uint32_t) +
           planes.capacity() * sizeof(PlaneContactRef) + walls.capacity() * sizeof(WallContactRef) +
           wall_elements.capacity() * sizeof(std::uint32_t);
  }

  // The owned particles' count (partners at or above it are ghosts).
  std::uint32_t n_owned() const {
    return offsets.empty() ? 0 : static_cast<std::uint32_t>(offsets.size() - 1);
  }

  // The partner limit (core/overlap_scan.hpp) that passes the ghost pairs over where they are
  // computed apart, and none where the loop runs in list order.
  std::uint32_t owned_partner_limit() const {
    return ghost_pairs.empty() ? every_partner : n_owned();
  }

  // Fills `ghost_pairs`; their_own = false leaves it empty (the loop then runs in list order).
  void index_ghost_pairs(bool their_own) {
    ghost_pairs.clear();
    if (!their_own) return ghost_pairs.shrink_to_fit();
    const std::uint32_t owned = n_owned();
    for (std::uint32_t p = 0; p < partners.size(); ++p)
      if (partners[p] >= owned) ghost_pairs.push_back(p);
  }

  std::size_t n_pairs() const { return partners.size(); }

  // Fills `rows` from `offsets` (the builders call it last).
  void index_rows() {
    rows.reserve(partners.size()); // (exactly: resize() alone would double the memory)
    rows.resize(partners.size());
    for (std::uint32_t i = 0; i + 1 < offsets.size(); ++i)
      for (std::uint32_t p = offsets[i]; p < offsets[i + 1]; ++p) rows[p] = i;
  }
};

// Builds the pair rows. `grid` must have binned all particles of `store` (owned and ghosts).
void build_neighbor_list(const ParticleStore& store, const CellGrid& grid, double range,
                         NeighborList& list);

// Brute-force O(N^2) reference with the same pair rules, for tests.
void build_neighbor_list_brute_force(const ParticleStore& store, double range, NeighborList& list);

} // namespace yuxi
