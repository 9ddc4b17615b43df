// Rigid clumps of spheres in a simulation, one part of it (docs/clumps.md). A clump's members
// are grains of the particle store, with the clump's id in their `body` field; the clump
// itself, its body, lives here: mass, principal moments, centre of mass and its velocity,
// orientation q and the conjugate momentum p of NO_SQUISH (core/free_rotation.hpp), and the
// members' centres in its principal frame. The part integrates the bodies (velocity Verlet for
// the centre, NO_SQUISH for the orientation), places the members from them at every drift
// (x = X + R b, v = V + omega x R b, w = omega), and adds the members' contact forces and
// torques onto them, member by member in the order of the shape, so the sum does not depend on
// where the list build sorted the members.
//
// Members take their body's mass in contacts (inv_mass = 1 / M, as LAMMPS's granular pair
// styles do with rigid bodies); their `mass` field holds their share of it, by volume, for the
// analyses that weigh grains. The books take the bodies' energies in place of the members'.
#pragma once

#include "core/archive.hpp"
#include "core/box.hpp"
#include "core/particle_store.hpp"
#include "core/quaternion.hpp"
#include "core/vec3.hpp"
#include "scene/clump_shape.hpp"
#include "sim/energy_books.hpp"

#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace yuxi {

struct ClumpBody {
  GlobalId id = -1;   // the global id of member 0; member k has id + k
  double mass = 0.0;  // M [mass]
  Vec3 inertia;       // principal moments I1, I2, I3 [mass length^2]
  Vec3 x;             // centre of mass
  Vec3 v;             // its velocity
  Quaternion q;       // body frame -> lab
  Quaternion p;       // NO_SQUISH's conjugate momentum 2 q (0, L_body)
  Vec3 force, torque; // at the last force evaluation (lab frame; the torque about x)
  std::uint8_t material = 0;
  std::int32_t shape = -1;   // the scene's [[shape]] it is made of (its index), -1: none named
  std::vector<Vec3> members; // centres in the principal frame [length]
  std::vector<double> radii; // [length]

  // The angular velocity in the lab frame [rad/time].
  Vec3 angular_velocity() const;
  // The member whose position decides the clump's owner on several ranks (clump_anchor).
  std::size_t anchor() const { return clump_anchor(members); }
  // Member k's centre relative to the centre of mass, in the lab frame.
  Vec3 arm(std::size_t k) const;
  // Turning at omega (lab frame) [rad/time]: NO_SQUISH's momentum p = 2 q (0, I to_body(q, omega))
  // made from it, for the orientation q.
  void set_angular_velocity(const Vec3& omega);
  // The smallest mass a normal contact on one of its members can meet, a lower bound of the
  // effective mass 1 / (1/M + (b x n) . I^-1 (b x n)) over every member k and normal n:
  // 1 / (1/M + max_k sum_a d_ka^2 / I_a), d_ka the distance of b_k from principal axis a (the
  // time step's check).
  double smallest_contact_mass() const;
  // The diameter of the smallest sphere about the centre of mass that holds every member,
  // 2 max_k (|b_k| + a_k) [length]: however the clump turns, no two of its members stand
  // farther apart, surfaces included.
  double span() const;
};

// A clump of `shape` (scene/clump_shape.hpp) and `density` [mass/length^3]: its body, of id
// `first_id`, its centre of mass at x, turned by `orientation` from the principal frame, moving
// at v and turning at omega (lab frame) [length/time, rad/time]; and its members (ids first_id +
// k, in the shape's order), each with its share of the mass by volume. Throws
// std::invalid_argument for a density that is not positive and finite, or an orientation that
// is not a unit quaternion.
struct PlacedClump {
  ClumpBody body;
  std::vector<ParticleSpec> members;
};
PlacedClump make_clump(const ClumpShape& shape, double density, std::uint8_t material,
                       GlobalId first_id, const Vec3& x, const Quaternion& orientation,
                       const Vec3& v = {}, const Vec3& omega = {});
// A clump of one member as what it is, a plain sphere: a free grain that spins by itself, of
// the clump's mass, place and motion.
ParticleSpec lone_member_as_sphere(const PlacedClump& clump);

class ClumpBodies {
public:
  // The bodies (ids ascending and unique; the members must be in the store before the first
  // list build: index_members()).
  void set(std::vector<ClumpBody> bodies);
  bool empty() const { return bodies_.empty(); }
  std::size_t size() const { return bodies_.size(); }
  const std::vector<ClumpBody>& bodies() const { return bodies_; }
  // The members of every body among the owned particles of `s`, found again after the particles
  // were sorted (a list build). Throws std::invalid_argument where a body's member is missing,
  // or where a grain names a body that is not here.
  void index_members(const ParticleStore& s);

  // The first half kick by the last forces and the drift over dt (velocity Verlet; NO_SQUISH's
  // R3 R2 R1 R2 R3 for the orientation); gravity's work along periodic axes M g_p . dX added
  // to `gravity_work`.
  void kick_drift(double dt, const Vec3& g_periodic, double& gravity_work);
  // The second half kick by the forces just gathered.
  void final_kick(double dt);
  // The members placed from their bodies, x = X + R b (never wrapped one by one: a clump stays
  // whole across a periodic face, wrap() moves it), with the bodies' velocities at their
  // points; returns whether a member moved farther than sqrt(limit2) from where it stood at the
  // last list build, and raises `moved2` to the largest squared displacement of a member.
  // `moved2` null: velocities only, the positions kept. The placing keeps each member's arm
  // R b, which the gathering of the forces and the velocities after the second kick reuse until
  // the bodies turn again (the same bits as computing them anew).
  bool place_members(ParticleStore& s, double limit2, double* moved2);
  // Each body's force and torque: gravity M g, plus its members' contact forces and torques,
  // member by member.
  void gather_forces(const ParticleStore& s, const Vec3& gravity);

  // The bodies' translational, rotational and gravitational energies and their count, added to
  // the books (members are left out of the per-grain sums).
  void add_energies(EnergyBooks& e, const Vec3& g_potential) const;
  // The mechanical energy of body b (as the books count it).
  double mechanical_energy(std::size_t b, const Vec3& g_potential) const;
  // The body of member i of the store, by its index here.
  std::size_t body_of(const ParticleStore& s, std::size_t i) const;
  // A new body (a clump poured in), its id above every body's here; its members go into the
  // store before the next list build.
  void add(ClumpBody body);
  // Body b (its index here), to change its motion or its pose between steps: the caller places
  // the members next (place_members(); with `moved2` null, the velocities alone, where the pose
  // stayed).
  ClumpBody& motion_of(std::size_t b) { return bodies_[b]; }
  // Removes bodies (indices here, ascending); returns the store indices of their members among
  // the owned particles of `s`, to be removed by the caller (ascending). The members are found
  // by their `body` field, so this holds between list builds too, after other removals.
  std::vector<std::size_t> remove(const ParticleStore& s, std::span<const std::size_t> bodies);
  // Wraps the centres of mass into the box's periodic axes, each clump's members in `s` shifted
  // with it (at a list build).
  void wrap(const Box& box, ParticleStore& s);
  // The largest distance of a member's centre from its clump's anchor member's
  // (scene/clump_shape.hpp: clump_anchor) [length]: how far a member may stand outside the
  // sub-domain that owns its clump (0 without clumps).
  double reach() const;
  // The largest span() of the clumps here, and the id of a clump that has it (-1: none here).
  std::pair<double, GlobalId> widest() const;

  // Moving between ranks with their members (sim/exchange.cpp), the body with its anchor
  // member: the body of id `id` (its index here), or size() where none is here; a body's
  // bytes; a body taken out (its members leave with it); one that arrived, its centre shifted
  // by `shift` (a periodic boundary crossed), put in its place among the ids. Members are found
  // again by index_members().
  std::size_t find(GlobalId id) const;
  std::string pack(std::size_t b) const;
  void take_out(std::size_t b);
  void take_in(const std::string& bytes, const Vec3& shift);

  // Each body's `shape`, an index into `saved` (the names it was given under), made the index of
  // that name in `now`, or -1 where `now` lacks it or the index was beyond `saved`.
  void rename_shapes(const std::vector<std::string>& saved, const std::vector<std::string>& now);

  void save(ArchiveWriter& ar) const;
  // Throws ArchiveError where the section is damaged, std::invalid_argument where a body is
  // impossible (non-finite, not positive mass or moments, no members).
  void load(ArchiveReader& ar);

private:
  std::vector<ClumpBody> bodies_;
  // Store indices of the members, body by body in member order (first_[b] to first_[b + 1]).
  std::vector<std::size_t> first_;
  std::vector<std::uint32_t> member_index_;
  // Each member's arm R(q) b at the last placing, indexed as member_index_; valid while
  // arms_ready_ (until the bodies turn or change).
  std::vector<Vec3> arms_;
  bool arms_ready_ = false;

  // The members' indices and arms forgotten: the bodies changed (until index_members()).
  void forget_layout();
};

} // namespace yuxi
