// The device engine's phases, one functor each: plain data in, plain data out, YUXI_HD, so the
// same code runs as a CUDA kernel and, in the host build, on the CPU (Thrust's CPP system).
// Each functor is applied to an index: a particle, a pair or a block of values. None adds to a
// value that another index also writes (no atomics): a pair writes its own force, and a particle
// sums the forces of its pairs in a fixed order, so the bits do not depend on the order in which
// the indices run (docs/ARCHITECTURE.md, "The device engine").
#pragma once

#include "contact/contact_geometry.hpp"
#include "core/always_inline.hpp"
#include "core/host_device.hpp"
#include "core/particle_energy.hpp"
#include "core/particle_fields.hpp"
#include "core/radial_wave.hpp"
#include "core/vec3.hpp"

#include <cstdint>

namespace yuxi::device {

// The box as the device sees it: bounds and which axes are periodic.
struct DeviceBox {
  Vec3 lo, hi;
  bool periodic[3] = {false, false, false};

  YUXI_HD double length(int a) const { return hi[a] - lo[a]; }
  // Box::wrap (core/box.cpp), operation for operation: a position into [lo, hi) on periodic axes.
  YUXI_HD Vec3 wrap(Vec3 p) const {
    for (int a = 0; a < 3; ++a) {
      if (!periodic[a]) continue;
      const double l = length(a);
      p[a] -= l * std::floor((p[a] - lo[a]) / l);
      if (p[a] >= hi[a]) p[a] -= l;
      if (p[a] < lo[a]) p[a] = lo[a];
    }
    return p;
  }
  // How wrap() moves p, as an image code (separation()): along each axis 0 (not), 1 (one box
  // length up) or 2 (one length down); 255 where it moves p farther.
  YUXI_HD std::uint8_t wrap_image(const Vec3& p) const {
    const Vec3 w = wrap(p);
    std::uint8_t code = 0, weight = 1;
    for (int a = 0; a < 3; ++a, weight = static_cast<std::uint8_t>(weight * 3)) {
      if (!periodic[a]) continue;
      const double lengths = std::floor((w[a] - p[a]) / length(a) + 0.5); // (a whole number)
      if (lengths == 1.0)
        code = static_cast<std::uint8_t>(code + weight);
      else if (lengths == -1.0)
        code = static_cast<std::uint8_t>(code + 2 * weight);
      else if (lengths != 0.0)
        return 255;
    }
    return code;
  }
};

// Linked cells over the box: n[a] cells of edge `edge[a]` along each axis.
struct DeviceCells {
  Vec3 lo, edge;
  int n[3] = {1, 1, 1};

  YUXI_HD int axis_cell(double x, int a) const {
    const double c = std::floor((x - lo[a]) / edge[a]);
    return c < 0 ? 0 : (c >= n[a] ? n[a] - 1 : static_cast<int>(c));
  }
  YUXI_HD std::uint32_t cell_of(const Vec3& x) const {
    return static_cast<std::uint32_t>((axis_cell(x.z, 2) * n[1] + axis_cell(x.y, 1)) * n[0] +
                                      axis_cell(x.x, 0));
  }
  YUXI_HD std::uint32_t count() const { return static_cast<std::uint32_t>(n[0] * n[1] * n[2]); }
};

// A pair's periodic image: for each axis 0 (none), 1 (+L) or 2 (-L), as a base-3 number.
// d = x_i - x_j with the partner j at its image. Along an axis where the image is one box length
// up, d = x_i - (x_j + L); where it is one length down, d = -(x_j - (x_i + L)): the particle near
// the lower face is always the one shifted up, as the CPU engine's ghosts are (domain/halo.hpp),
// so that both engines round the same sums and a pair's overlap agrees to the bit.
YUXI_ALWAYS_INLINE YUXI_HD Vec3 separation(const Vec3& xi, const Vec3& xj, std::uint8_t image,
                                           const DeviceBox& box) {
  Vec3 d;
  for (int a = 0; a < 3; ++a) {
    const int code = image % 3;
    image = static_cast<std::uint8_t>(image / 3);
    d[a] = code == 1   ? xi[a] - (xj[a] + box.length(a))
           : code == 2 ? -(xj[a] - (xi[a] + box.length(a)))
                       : xi[a] - xj[a];
  }
  return d;
}

// A particle's radius [length], mass [mass], inverse mass and inverse moment of inertia: the
// same four for every particle of a species.
struct Species {
  double radius, mass, inv_mass, inv_inertia;
};

// The particles, sorted by cell at each list build. No force or torque is kept per particle:
// the kicks sum them from the contacts (GrainLoads). Where the particles are of few species,
// each keeps the index of its species (2 bytes, not 32): a monodisperse bed, or a few sizes,
// reads one small table; otherwise each particle is a species of its own. A clump's member is
// a grain that names its clump (`body_of`): its clump moves it (clump_phases.hpp).
constexpr std::uint32_t no_body = 0xffffffffu;
struct Particles {
  Vec3 *x, *v, *w, *x_build;
  const Species* species;
  const std::uint16_t* species_of; // each particle's species; null: species[i] is particle i's
  const std::uint32_t* gid;        // the global id (the engine refuses ids beyond 32 bits)
  const Kind* kind;
  const std::uint8_t* material;
  const std::uint32_t* body_of; // each particle's clump (its index), or no_body; null: none
  std::uint32_t n;

  YUXI_ALWAYS_INLINE YUXI_HD bool is_member(std::uint32_t i) const {
    return body_of != nullptr && body_of[i] != no_body;
  }
  // A grain that moves by itself (not a clump's member).
  YUXI_ALWAYS_INLINE YUXI_HD bool is_free_grain(std::uint32_t i) const {
    return kind[i] == Kind::grain && !is_member(i);
  }

  YUXI_ALWAYS_INLINE YUXI_HD const Species& of(std::uint32_t i) const {
    return species[species_of ? species_of[i] : i];
  }
  YUXI_ALWAYS_INLINE YUXI_HD double radius(std::uint32_t i) const { return of(i).radius; }
  YUXI_ALWAYS_INLINE YUXI_HD double mass(std::uint32_t i) const { return of(i).mass; }
  YUXI_ALWAYS_INLINE YUXI_HD double inv_mass(std::uint32_t i) const { return of(i).inv_mass; }
  YUXI_ALWAYS_INLINE YUXI_HD double inv_inertia(std::uint32_t i) const { return of(i).inv_inertia; }
};

// The half list in compressed rows: particle i's partners j > i are partner[row_start[i] ..
// row_start[i + 1]), each with its image. A pair's row is not kept (4 bytes a listed pair, most
// of which never touch): the phases run by row, and the touching pairs' list keeps theirs.
struct PairList {
  const std::uint32_t *row_start, *partner;
  const std::uint8_t* image;
  // The pairs where a particle is the partner, in pair order: reverse_pair[reverse_start[j] ..
  // reverse_start[j + 1]).
  const std::uint32_t *reverse_start, *reverse_pair;
  std::uint32_t n; // particles (rows)

  // The row of pair `pair`: the last i with row_start[i] <= pair (a binary search, for the
  // phases of a list build).
  YUXI_HD std::uint32_t row_of(std::uint32_t pair) const {
    std::uint32_t lo = 0, hi = n; // row_start[lo] <= pair < row_start[hi]
    while (hi - lo > 1) {
      const std::uint32_t mid = lo + (hi - lo) / 2;
      if (row_start[mid] <= pair)
        lo = mid;
      else
        hi = mid;
    }
    return lo;
  }
};

// Each particle's sort key at a list build (after wrapping it into the periodic box): its cell,
// then its global id (the list's reference positions are set after the sort). The order this gives
// depends on where the particles stand and nothing else, so a run continued from a checkpoint
// sorts, lists and sums as the run that wrote it. A clump's member is not wrapped alone (its
// clump wraps, at its centre, and takes it along): it is sorted into the cell of its wrapped
// place and stays where it stands, maybe outside the box (FindPartners).
struct CellOfParticle {
  Particles p;
  DeviceBox box;
  DeviceCells cells;
  std::uint64_t* key;
  YUXI_HD void operator()(std::uint32_t i) const {
    const Vec3 wrapped = box.wrap(p.x[i]);
    if (!p.is_member(i)) p.x[i] = wrapped;
    key[i] = (static_cast<std::uint64_t>(cells.cell_of(wrapped)) << 32) |
             static_cast<std::uint64_t>(p.gid[i]);
  }
};

// The smallest sort key of cell c (CellOfParticle): where the cell starts among the sorted keys.
struct FirstKeyOfCell {
  YUXI_HD std::uint64_t operator()(std::uint32_t c) const {
    return static_cast<std::uint64_t>(c) << 32;
  }
};

// Particle i's partners: every later particle (in cell order) of the 27 cells around it, closer
// than a_i + a_j + skin, that is not a wall particle with another wall particle, nor a member of
// i's clump. Counts them (count != nullptr) or writes them from out_start[i].
//
// The cells hold the particles at `at`: where they stand, or, for clumps' members, which stand
// where their clumps put them, maybe outside a periodic box, at their wrapped places
// (CellOfParticle). The images found between wrapped places are then made the images between
// where the particles stand (MemberImages).
struct FindPartners {
  Particles p;
  const Vec3* at; // each particle's place in the cells
  DeviceBox box;
  DeviceCells cells;
  const std::uint32_t* cell_start; // first particle of each cell, and the total at the end
  double skin;
  std::uint32_t* count;
  const std::uint32_t* out_start;
  std::uint32_t* partner;
  std::uint8_t* image;

  YUXI_HD void operator()(std::uint32_t i) const {
    const Vec3 xi = at[i];
    int c[3];
    for (int a = 0; a < 3; ++a) c[a] = cells.axis_cell(xi[a], a);
    std::uint32_t found = 0, next = count ? 0 : out_start[i];
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int d[3] = {dx, dy, dz};
          int nc[3];
          std::uint8_t code = 0, weight = 1;
          bool inside = true;
          for (int a = 0; a < 3; ++a, weight = static_cast<std::uint8_t>(weight * 3)) {
            nc[a] = c[a] + d[a];
            if (nc[a] < 0 || nc[a] >= cells.n[a]) {
              if (!box.periodic[a]) {
                inside = false;
                break;
              }
              // Across the periodic face: the partner's image is one box length away.
              const bool below = nc[a] < 0;
              nc[a] = below ? nc[a] + cells.n[a] : nc[a] - cells.n[a];
              code = static_cast<std::uint8_t>(code + weight * (below ? 2 : 1));
            }
          }
          if (!inside) continue;
          const std::uint32_t cell =
              static_cast<std::uint32_t>((nc[2] * cells.n[1] + nc[1]) * cells.n[0] + nc[0]);
          for (std::uint32_t j = cell_start[cell]; j < cell_start[cell + 1]; ++j) {
            if (j <= i) continue;
            if (p.kind[i] == Kind::wall && p.kind[j] == Kind::wall) continue;
            if (p.is_member(i) && p.body_of[i] == p.body_of[j]) continue; // (one clump's members)
            const Vec3 dij = separation(xi, at[j], code, box); // as PairForces sees the pair
            const double reach = p.radius(i) + p.radius(j) + skin;
            if (!(norm2(dij) < reach * reach)) continue;
            if (count) {
              ++found;
            } else {
              partner[next] = j;
              image[next] = code;
              ++next;
            }
          }
        }
    if (count) count[i] = found;
  }
};

// After FindPartners, where clumps' members are: the image of each pair of row i with a member,
// found between wrapped places, made the image between where the two particles stand (a member
// is not wrapped alone): each one's wrap (DeviceBox::wrap_image) added in. An image beyond one
// box length (a clump about as long as the periodic box) cannot be written: it sets *too_wide.
struct MemberImages {
  Particles p;
  PairList list;
  DeviceBox box;
  std::uint8_t* image;
  std::uint32_t* too_wide;
  YUXI_HD void operator()(std::uint32_t i) const {
    const bool member_i = p.is_member(i);
    const std::uint8_t wrap_i = member_i ? box.wrap_image(p.x[i]) : 0;
    for (std::uint32_t pair = list.row_start[i]; pair < list.row_start[i + 1]; ++pair) {
      const std::uint32_t j = list.partner[pair];
      if (!member_i && !p.is_member(j)) continue;
      const std::uint8_t wrap_j = p.is_member(j) ? box.wrap_image(p.x[j]) : 0;
      // Along each axis, in box lengths up: the image's, plus j's wrap, less i's.
      const auto up = [](unsigned c) { return c == 1 ? 1 : c == 2 ? -1 : 0; };
      unsigned in = image[pair], wi = wrap_i, wj = wrap_j, out = 0, weight = 1;
      bool fits = wrap_i != 255 && wrap_j != 255;
      for (int a = 0; a < 3; ++a, weight *= 3, in /= 3, wi /= 3, wj /= 3) {
        const int m = up(in % 3) + up(wj % 3) - up(wi % 3);
        fits = fits && m >= -1 && m <= 1;
        out += weight * (m == 1 ? 1u : m == -1 ? 2u : 0u);
      }
      if (fits)
        image[pair] = static_cast<std::uint8_t>(out);
      else
        *too_wide = 1; // (every thread that writes writes 1)
    }
  }
};

// Each particle's place in the cells at a list build: where it stands, or a clump's member's
// wrapped place (FindPartners).
struct PlaceInCells {
  Particles p;
  DeviceBox box;
  Vec3* at;
  YUXI_HD void operator()(std::uint32_t i) const {
    at[i] = p.is_member(i) ? box.wrap(p.x[i]) : p.x[i];
  }
};

// Each contact's key, the global ids of its two particles (smaller first, as 32-bit halves), so
// that its state follows it across list builds whatever the local order.
YUXI_HD inline std::uint64_t contact_key(GlobalId a, GlobalId b) {
  const std::uint64_t lo = static_cast<std::uint64_t>(a < b ? a : b);
  const std::uint64_t hi = static_cast<std::uint64_t>(a < b ? b : a);
  return (lo << 32) | hi;
}

// Where key k stands in the ascending keys[0, n), or n where it is not there.
YUXI_HD inline std::uint32_t find_key(const std::uint64_t* keys, std::uint32_t n, std::uint64_t k) {
  std::uint32_t lo = 0, hi = n;
  while (lo < hi) {
    const std::uint32_t mid = lo + (hi - lo) / 2;
    if (keys[mid] < k)
      lo = mid + 1;
    else
      hi = mid;
  }
  return lo < n && keys[lo] == k ? lo : n;
}

// A pair's flag holds two bits: `touches_now` (it overlaps at this evaluation) and
// `touched_before` (it overlapped at the last one, or its contact came back at a list build).
constexpr std::uint8_t touches_now = 1, touched_before = 2;

// A contact stashed across a list build: its state stays in its slot of the last evaluation
// (the engine's carried states, untouched by the build), and the stash keeps where: the slot,
// with the top bit set where the state there is seen from the larger id (the pair's row
// particle had it).
constexpr std::uint32_t seen_from_larger = 0x80000000u;

// Before a list build: the key of each open contact, and where its state is.
struct StashContact {
  Particles p;
  PairList list;
  const std::uint32_t* slot; // per pair
  const std::uint32_t* open_pairs;
  std::uint64_t* key;
  std::uint32_t* held; // the slot, and seen_from_larger
  YUXI_HD void operator()(std::uint32_t k) const {
    const std::uint32_t pair = open_pairs[k];
    const GlobalId gi = p.gid[list.row_of(pair)], gj = p.gid[list.partner[pair]];
    key[k] = contact_key(gi, gj);
    held[k] = slot[pair] | (gi < gj ? 0u : seen_from_larger);
  }
};

// A stashed contact's state as seen from the smaller id (for the host).
template <class Model> struct StashedState {
  const typename Model::State* state; // per slot of the last evaluation
  const std::uint32_t* held;
  typename Model::State* out;
  YUXI_HD void operator()(std::uint32_t k) const {
    const typename Model::State& s = state[held[k] & ~seen_from_larger];
    out[k] = (held[k] & seen_from_larger) ? s.mirrored() : s;
  }
};

// After a list build: each pair of row i finds its stashed contact (binary search on the sorted
// keys). A found one is open and takes its state's slot; the state there is turned to be seen
// from the pair's row particle where the last one saw it from the other (in place: one pair
// finds each contact).
template <class Model> struct RestoreContact {
  Particles p;
  PairList list;
  const std::uint64_t* key;
  const std::uint32_t* held;
  std::uint32_t n_stashed;
  typename Model::State* state; // per slot of the last evaluation
  std::uint32_t* slot;          // per pair
  std::uint8_t* open;
  YUXI_HD void operator()(std::uint32_t i) const {
    const GlobalId gi = p.gid[i];
    for (std::uint32_t pair = list.row_start[i]; pair < list.row_start[i + 1]; ++pair) {
      const GlobalId gj = p.gid[list.partner[pair]];
      const std::uint32_t at = find_key(key, n_stashed, contact_key(gi, gj));
      const bool found = at < n_stashed;
      open[pair] = found ? touches_now : 0; // (the next evaluation reads it as touched_before)
      if (!found) continue;
      const std::uint32_t c = held[at] & ~seen_from_larger;
      slot[pair] = c;
      if (((held[at] & seen_from_larger) != 0) != (gi > gj)) state[c] = state[c].mirrored();
    }
  }
};

// Which pairs of row i touch this step (the overlap test of contact_forces.hpp's sweep), and
// how many of them are flagged. A pair with either flag bit is flagged: the flagged pairs are
// gathered into one list (GatherTouches), so that the laws run on full warps (most listed pairs
// do not touch: 83 % on the chute), and only they have a state. A pair that touched and does not
// touch any more releases its springs (PairForces).
struct FindTouches {
  Particles p;
  PairList list;
  DeviceBox box;
  std::uint8_t* open;
  std::uint32_t* flagged; // per row
  YUXI_HD void operator()(std::uint32_t i) const {
    std::uint32_t count = 0;
    for (std::uint32_t pair = list.row_start[i]; pair < list.row_start[i + 1]; ++pair) {
      const std::uint32_t j = list.partner[pair];
      const double touch = p.radius(i) + p.radius(j);
      const bool overlaps =
          norm2(separation(p.x[i], p.x[j], list.image[pair], box)) < touch * touch;
      const auto flag = static_cast<std::uint8_t>(
          (overlaps ? touches_now : 0) | ((open[pair] & touches_now) ? touched_before : 0));
      open[pair] = flag;
      if (flag != 0) ++count;
    }
    flagged[i] = count;
  }
};

// Row i's flagged pairs into the list of this step, in pair order from the row's first slot
// c = first_slot[i]: each slot learns its pair and row, and takes the pair's state, the one it
// had at its last slot where it touched then, a fresh one otherwise; the pair learns its new
// slot. States live in slots only, two arrays of them in turn (the last evaluation's, this
// one's), so that a pair that does not touch holds none.
template <class Model> struct GatherTouches {
  PairList list;
  const std::uint8_t* open;
  const std::uint32_t* first_slot;      // per row
  const typename Model::State* carried; // per slot of the last evaluation
  typename Model::State* state;         // per slot of this one
  std::uint32_t* slot;                  // per pair
  std::uint32_t* touch_pair;            // per slot
  std::uint32_t* touch_row;             // per slot
  YUXI_HD void operator()(std::uint32_t i) const {
    std::uint32_t c = first_slot[i];
    for (std::uint32_t pair = list.row_start[i]; pair < list.row_start[i + 1]; ++pair) {
      if (open[pair] == 0) continue;
      state[c] = (open[pair] & touched_before) ? carried[slot[pair]] : typename Model::State{};
      slot[pair] = c;
      touch_pair[c] = pair;
      touch_row[c] = i;
      ++c;
    }
  }
};

// What the flagged pairs' contacts gave this step, one slot per flagged pair in pair order (the
// list `touch_pair`), for the sums over their particles and the energy books.
struct PairOutput {
  Vec3* force;    // on the row particle i (-force on the partner j)
  Vec3* torque_i; // on i
  Vec3* torque_j; // on j
  double* elastic;
  double* relaxation; // held in the contact's relaxation buffer (null: the law holds none)
  double* dissipated; // this step, releases of parted contacts included
  double* wall_work;  // this step, by a moving wall particle on its partner (null: none moves)
};

// The contact law on each flagged pair (contact_forces.hpp's sweep and compute_pairs), in its
// slot c: a pair that overlaps is evaluated, one that has come apart releases what its springs
// held.
template <class Model> struct PairForces {
  Particles p;
  PairList list;
  DeviceBox box;
  const typename Model::Coeffs* coeffs; // per material pair, n_materials^2
  std::uint32_t n_materials;
  double dt;
  typename Model::State* state; // per slot
  const std::uint8_t* open;
  const std::uint32_t* touch_pair; // per slot
  const std::uint32_t* touch_row;  // per slot
  PairOutput out;

  YUXI_HD void operator()(std::uint32_t c) const {
    const std::uint32_t pair = touch_pair[c];
    const std::uint32_t i = touch_row[c], j = list.partner[pair];
    const typename Model::Coeffs& k = coeffs[p.material[i] * n_materials + p.material[j]];
    ContactResult r;
    double released = 0.0, work = 0.0;
    if (open[pair] & touches_now) {
      const Vec3 d = separation(p.x[i], p.x[j], list.image[pair], box);
      const ContactGeometry g = pair_geometry(d, norm2(d), p.radius(i), p.radius(j), p.v[i], p.v[j],
                                              p.w[i], p.w[j], p.inv_mass(i), p.inv_mass(j), dt);
      r = Model::evaluate(g, k, state[c]);
      // Work of a wall particle's prescribed motion (contact_forces.hpp, book_wall_work).
      if (p.kind[j] == Kind::wall) work += dot(r.force, p.v[j]) * dt;
      if (p.kind[i] == Kind::wall) work -= dot(r.force, p.v[i]) * dt;
    } else {
      released = Model::release(k, state[c]);
      state[c] = typename Model::State{};
    }
    out.force[c] = r.force;
    out.torque_i[c] = r.torque_i;
    out.torque_j[c] = r.torque_j;
    out.elastic[c] = r.elastic;
    if (out.relaxation) out.relaxation[c] = r.relaxation;
    out.dissipated[c] = r.dissipated + released;
    if (out.wall_work) out.wall_work[c] = work;
  }
};

// The planes of a scene (scene/plane_wall.hpp), as arrays: a point, the unit normal into the
// grains' side, the material, the largest excursion of its oscillation, and where the
// oscillation has it now (offset along the normal, velocity; PlaneWall::offset and velocity, on
// the host: the same sine and cosine for every backend).
struct PlaneSet {
  const Vec3* point;
  const Vec3* normal;
  const std::uint8_t* material;
  const double* excursion;
  const double* offset;
  const Vec3* velocity;
  std::uint32_t count;
};

// The grain-plane candidates: for each particle, its planes (grains only) closer than its radius
// and the skin (NeighborSearch::build). Counts them (count != nullptr) or writes them from
// start[i]: the particle of each candidate (`row`) and its plane.
struct FindPlanes {
  Particles p;
  PlaneSet planes;
  double skin;
  std::uint32_t* count;
  const std::uint32_t* start;
  std::uint32_t* row;
  std::uint8_t* plane;
  YUXI_HD void operator()(std::uint32_t i) const {
    std::uint32_t found = 0, at = count ? 0 : start[i];
    if (p.kind[i] == Kind::grain)
      for (std::uint32_t k = 0; k < planes.count; ++k) {
        if (!(dot(p.x[i] - planes.point[k], planes.normal[k]) <
              p.radius(i) + skin + planes.excursion[k]))
          continue;
        if (count) {
          ++found;
        } else {
          row[at] = i;
          plane[at] = static_cast<std::uint8_t>(k);
          ++at;
        }
      }
    if (count) count[i] = found;
  }
};

// A grain-plane contact's key: the grain's global id, then the plane.
YUXI_HD inline std::uint64_t plane_key(GlobalId grain, std::uint32_t plane) {
  return (static_cast<std::uint64_t>(grain) << 8) | plane;
}

// Before a list build: the key and the state of each open grain-plane contact.
template <class Model> struct StashPlane {
  Particles p;
  const std::uint32_t* row;
  const std::uint8_t* plane;
  const typename Model::State* state;
  const std::uint32_t* open_candidates;
  std::uint64_t* key;
  typename Model::State* stashed;
  YUXI_HD void operator()(std::uint32_t k) const {
    const std::uint32_t c = open_candidates[k];
    key[k] = plane_key(p.gid[row[c]], plane[c]);
    stashed[k] = state[c];
  }
};

// After a list build: each candidate takes its stashed state back (binary search on the keys).
template <class Model> struct RestorePlane {
  Particles p;
  const std::uint32_t* row;
  const std::uint8_t* plane;
  const std::uint64_t* key;
  const typename Model::State* stashed;
  std::uint32_t n_stashed;
  typename Model::State* state;
  std::uint8_t* open;
  YUXI_HD void operator()(std::uint32_t c) const {
    const std::uint32_t at = find_key(key, n_stashed, plane_key(p.gid[row[c]], plane[c]));
    const bool found = at < n_stashed;
    open[c] = found ? 1 : 0;
    state[c] = found ? stashed[at] : typename Model::State{};
  }
};

// What a grain-plane contact gave this step.
struct PlaneOutput {
  Vec3* force;  // on the grain
  Vec3* torque; // on the grain
  double* elastic;
  double* relaxation;
  double* dissipated; // this step, releases of parted contacts included
  double* work;       // this step, of the plane's motion on the grain: F . v_plane dt
};

// The contact law on each grain-plane candidate (ContactForces::compute_planes): one that
// overlaps is evaluated, one that has come apart releases what it held.
template <class Model> struct PlaneForces {
  Particles p;
  PlaneSet planes;
  const std::uint32_t* row;
  const std::uint8_t* plane;
  const typename Model::Coeffs* coeffs; // per material pair, n_materials^2
  std::uint32_t n_materials;
  double dt;
  typename Model::State* state;
  std::uint8_t* open;
  PlaneOutput out;
  YUXI_HD void operator()(std::uint32_t c) const {
    const std::uint32_t i = row[c], k = plane[c];
    const double dist = dot(p.x[i] - planes.point[k], planes.normal[k]) - planes.offset[k];
    const typename Model::Coeffs& co = coeffs[p.material[i] * n_materials + planes.material[k]];
    ContactResult r;
    double released = 0.0, work = 0.0;
    if (dist < p.radius(i)) {
      open[c] = 1;
      const Vec3 v_plane = planes.velocity[k];
      const ContactGeometry g = wall_geometry(planes.normal[k], dist, p.radius(i), p.v[i], v_plane,
                                              p.w[i], p.inv_mass(i), dt);
      r = Model::evaluate(g, co, state[c]);
      work = dot(r.force, v_plane) * dt;
    } else if (open[c]) {
      released = Model::release(co, state[c]);
      state[c] = typename Model::State{};
      open[c] = 0;
    }
    out.force[c] = r.force;
    out.torque[c] = r.torque_i;
    out.elastic[c] = r.elastic;
    out.relaxation[c] = r.relaxation;
    out.dissipated[c] = r.dissipated + released;
    out.work[c] = work;
  }
};

// `values` where the candidate's plane is `plane`, zero elsewhere (one plane's share of a sum).
struct OfPlane {
  const double* values;
  const std::uint8_t* plane_of;
  std::uint32_t plane;
  double* out;
  YUXI_HD void operator()(std::uint32_t c) const {
    out[c] = plane_of[c] == plane ? values[c] : 0.0;
  }
};

// Each grain's force and torque: gravity, then its touching pairs as the row particle, then as
// the partner, each in pair order, then its plane contacts in candidate order. Wall particles
// have none. No array keeps them between steps (48 bytes a particle): each kick sums them again
// from what the contacts gave, in the same order, so to the same bits (docs/ARCHITECTURE.md,
// "The device engine").
struct GrainLoads {
  PairList list;
  PairOutput out;
  const std::uint8_t* open;         // FindTouches's flags
  const std::uint32_t* slot;        // a flagged pair's slot in `out` (PairForces)
  const std::uint32_t* plane_start; // each particle's first grain-plane candidate
  PlaneOutput planes;
  Vec3 gravity;
  YUXI_ALWAYS_INLINE YUXI_HD void operator()(const Particles& p, std::uint32_t i, Vec3& f,
                                             Vec3& t) const {
    f = gravity * p.mass(i);
    t = Vec3{};
    add_contacts(i, f, t);
  }
  // What particle i's contacts gave, added to f and t in the order above.
  YUXI_ALWAYS_INLINE YUXI_HD void add_contacts(std::uint32_t i, Vec3& f, Vec3& t) const {
    for (std::uint32_t k = list.row_start[i]; k < list.row_start[i + 1]; ++k) {
      if (!(open[k] & touches_now)) continue;
      f += out.force[slot[k]];
      t += out.torque_i[slot[k]];
    }
    for (std::uint32_t k = list.reverse_start[i]; k < list.reverse_start[i + 1]; ++k) {
      const std::uint32_t pair = list.reverse_pair[k];
      if (!(open[pair] & touches_now)) continue;
      f -= out.force[slot[pair]];
      t += out.torque_j[slot[pair]];
    }
    for (std::uint32_t c = plane_start[i]; c < plane_start[i + 1]; ++c) {
      f += planes.force[c];
      t += planes.torque[c];
    }
  }
};

// The force (or the torque) on particles first, first + 1, ... into out[0], out[1], ... (zero
// for wall particles; a clump's member's from its contacts alone, as its clump takes gravity):
// for the host, at an output step.
struct WriteLoads {
  Particles p;
  GrainLoads loads;
  std::uint32_t first;
  bool torque;
  Vec3* out;
  YUXI_HD void operator()(std::uint32_t k) const {
    const std::uint32_t i = first + k;
    Vec3 f, t;
    if (p.is_member(i))
      loads.add_contacts(i, f, t);
    else if (p.kind[i] == Kind::grain)
      loads(p, i, f, t);
    out[k] = torque ? t : f;
  }
};

// Half a kick of grain i under force f and torque t (Simulation::kick_drift and final_kick,
// operation for operation).
YUXI_ALWAYS_INLINE YUXI_HD void half_kick(const Particles& p, std::uint32_t i, double dt,
                                          const Vec3& f, const Vec3& torque) {
  const double half_dt = 0.5 * dt;
  const double kick = half_dt * p.inv_mass(i), spin = half_dt * p.inv_inertia(i);
  Vec3 v = p.v[i], w = p.w[i];
  v.x = v.x + f.x * kick, v.y = v.y + f.y * kick, v.z = v.z + f.z * kick;
  w.x += torque.x * spin, w.y += torque.y * spin, w.z += torque.z * spin;
  p.v[i] = v;
  p.w[i] = w;
}

// The drift of grain i over dt, and whether it has now moved more than half the skin since the
// last list build (limit2: that half squared).
YUXI_ALWAYS_INLINE YUXI_HD std::uint32_t drift(const Particles& p, std::uint32_t i, double dt,
                                               double limit2) {
  const Vec3 v = p.v[i], x = p.x[i];
  const double xx = x.x + v.x * dt, xy = x.y + v.y * dt, xz = x.z + v.z * dt;
  p.x[i] = Vec3{xx, xy, xz};
  const Vec3 b = p.x_build[i];
  const double dx = xx - b.x, dy = xy - b.y, dz = xz - b.z;
  return !(dx * dx + dy * dy + dz * dz <= limit2) ? 1 : 0; // NaN too
}

// The first half kick and the drift of every free grain, and whether it moved more than half the
// skin since the last list build: under the forces the last step's contacts gave, or under
// `given` ones (a run continued mid-way, before its first step). Clumps' members are left to
// their clumps (KickClumps and PlaceMembers, after this).
struct KickDrift {
  Particles p;
  GrainLoads loads;
  const Vec3 *given_force, *given_torque; // null: summed from the contacts
  double dt, limit2;
  std::uint32_t*
      moved_far; // 1 where the grain moved far (32-bit: CUB reduces 8-bit flags with spills)
  YUXI_HD void operator()(std::uint32_t i) const {
    if (!p.is_free_grain(i)) {
      moved_far[i] = 0;
      return;
    }
    Vec3 f, t;
    if (given_force) {
      f = given_force[i];
      t = given_torque[i];
    } else {
      loads(p, i, f, t);
    }
    half_kick(p, i, dt, f, t);
    moved_far[i] = drift(p, i, dt, limit2);
  }
};

// The second half kick of every free grain (Simulation::final_kick); where `moved_far` is given,
// the next step's first half kick and drift as well, under the same forces (KickDrift): the
// same operations in the same order, with one sum of the forces instead of two. (Clumps:
// KickClumps and PlaceMembers, after this.)
struct FinalKick {
  Particles p;
  GrainLoads loads;
  double dt, limit2;
  std::uint32_t* moved_far; // null: the kick alone
  YUXI_HD void operator()(std::uint32_t i) const {
    if (!p.is_free_grain(i)) {
      if (moved_far) moved_far[i] = 0;
      return;
    }
    Vec3 f, t;
    loads(p, i, f, t);
    half_kick(p, i, dt, f, t);
    if (!moved_far) return;
    half_kick(p, i, dt, f, t);
    moved_far[i] = drift(p, i, dt, limit2);
  }
};

// A wall motion at one time, as the host computed it: sine and cosine once per step on the
// host, so that every backend places the walls with the same bits (scene/wall_motion.hpp).
struct MotionNow {
  bool moving = false; // a radial cosine wave that has started; otherwise the walls stand
  Vec3 center;
  int mode = 0;
  double radial = 0, speed = 0;
};
constexpr int max_wall_motions = 8;

// Wall particles in motion placed at the new time (Walls::place), and whether each moved more
// than half the skin since the last list build.
struct PlaceWalls {
  Particles p;
  const Vec3* x_rest;
  const std::uint16_t* motion;
  MotionNow now[max_wall_motions];
  double limit2;
  std::uint32_t* moved_far;
  YUXI_HD void operator()(std::uint32_t i) const {
    if (p.kind[i] == Kind::grain) return;
    const MotionNow& m = now[motion[i]];
    if (!m.moving) return;
    const PlacedPoint q = radial_cosine_place(m.center, m.mode, m.radial, m.speed, x_rest[i]);
    p.x[i] = q.position;
    p.v[i] = q.velocity;
    if (!(norm2(q.position - p.x_build[i]) <= limit2)) moved_far[i] = 1;
  }
};

// Values that the fixed-order sums read as they add (StridedSum), computed from the particles
// where they stand then, so that no array holds them [energy]. Zero for wall particles and
// clumps' members (their clumps' are summed apart: clump_phases.hpp).
//
// The work of periodic gravity over the drift just made, m g_p . v dt, v the half-step velocity
// (Simulation::kick_drift's gravity work): read between KickDrift and FinalKick.
struct GravityWork {
  Particles p;
  Vec3 g_periodic;
  double dt;
  YUXI_HD double operator[](std::uint64_t k) const {
    const auto i = static_cast<std::uint32_t>(k); // (k < n < 2^31)
    if (!p.is_free_grain(i)) return 0.0;
    const Vec3 v = p.v[i];
    return p.mass(i) * (g_periodic.x * v.x + g_periodic.y * v.y + g_periodic.z * v.z) * dt;
  }
};
// Each grain's energy of translation, of rotation, and gravitational under gravity's potential
// part, -m g_potential . x (sim/energy_ledger.cpp, EnergyLedger::parts).
struct TranslationalEnergy {
  Particles p;
  YUXI_HD double operator[](std::uint64_t k) const {
    const auto i = static_cast<std::uint32_t>(k); // (k < n < 2^31)
    return p.is_free_grain(i) ? translational_energy(p.mass(i), p.v[i]) : 0.0;
  }
};
// (written into an array, not computed as the sum reads it: its division, inside the sum's
// loop, spills registers on the GPU)
struct RotationalEnergy {
  Particles p;
  double* energy;
  YUXI_HD void operator()(std::uint32_t i) const {
    energy[i] = p.is_free_grain(i) ? rotational_energy(p.w[i], p.inv_inertia(i)) : 0.0;
  }
};
struct GravitationalEnergy {
  Particles p;
  Vec3 g_potential;
  YUXI_HD double operator[](std::uint64_t k) const {
    const auto i = static_cast<std::uint32_t>(k); // (k < n < 2^31)
    return p.is_free_grain(i) ? -(p.mass(i) * dot(g_potential, p.x[i])) : 0.0;
  }
};

// One level of a sum in a fixed order: sums[t] = values[t] + values[t + stride] + values[t + 2
// stride] + ..., added in that order, for t in [0, stride). Neighbouring threads read
// neighbouring values (coalesced on the GPU, cache lines shared on the CPU). The order depends on
// n and the stride only, so every backend gives the same bits (device_engine.cpp, OrderedSums).
// Values: an array, or values computed as they are read (GravityWork).
template <class Values> struct StridedSum {
  Values values;
  std::uint32_t n, stride;
  double* sums;
  YUXI_HD void operator()(std::uint32_t t) const {
    double s = 0.0;
    for (std::uint64_t k = t; k < n; k += stride) s += values[k];
    sums[t] = s;
  }
};

} // namespace yuxi::device
