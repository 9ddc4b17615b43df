// The device engine's phases of rigid clumps of spheres (docs/clumps.md), YUXI_HD functors as in
// step_phases.hpp: a thread a clump gathers its members' loads in member order (no atomics),
// a thread a clump kicks its centre and its NO_SQUISH momentum, drifts and turns it
// (core/free_rotation.hpp), and a thread a member places it from its clump. Every operation is
// the one ClumpBodies does on the CPU (sim/clump_bodies.cpp), in its order, so that a clump's
// motion from the same loads has the same bits.
#pragma once

#include "core/free_rotation.hpp"
#include "core/host_device.hpp"
#include "core/particle_energy.hpp"
#include "core/quaternion.hpp"
#include "core/vec3.hpp"
#include "device/step_phases.hpp"

#include <cstdint>

namespace yuxi::device {

// A clump's body on the device: centre of mass x, its velocity v, the orientation q (body frame
// to lab) and NO_SQUISH's conjugate momentum p, the angular velocity omega that they make (lab
// frame: lab_angular_velocity, made anew whenever q or p change, for the members' placing), the
// principal moments and the mass; its members are member slots first .. first + count of the
// clumps' arrays, in member order, of global ids gid, gid + 1, ...
struct RigidBody {
  Vec3 x, v;
  Quaternion q, p;
  Vec3 omega;
  Vec3 inertia;
  double mass;
  std::uint32_t first, count;
  std::uint32_t gid;
};

// The clumps: their bodies, and per member slot the member's centre in the principal frame and
// its particle's index (found again after every sort of the particles: RemapMembers).
struct ClumpSet {
  RigidBody* body;
  const Vec3* frame;
  std::uint32_t* member;
  std::uint32_t n;
};

// After the particles were sorted: each member's slot learns its particle's index.
struct RemapMembers {
  Particles p;
  ClumpSet clumps;
  YUXI_HD void operator()(std::uint32_t i) const {
    if (!p.is_member(i)) return;
    const RigidBody& b = clumps.body[p.body_of[i]];
    clumps.member[b.first + (p.gid[i] - b.gid)] = i;
  }
};

// The force and the torque (about the centre) on a clump: gravity M g, then member by member its
// contacts' force f_k and torque t_k, with the lever arm R b_k (ClumpBodies::gather_forces).
YUXI_ALWAYS_INLINE YUXI_HD void clump_loads(const ClumpSet& c, const RigidBody& b,
                                            const GrainLoads& loads, Vec3& force, Vec3& torque) {
  const Rotation turn = rotation_of(b.q);
  force = b.mass * loads.gravity;
  torque = Vec3{};
  for (std::uint32_t k = 0; k < b.count; ++k) {
    Vec3 f, t;
    loads.add_contacts(c.member[b.first + k], f, t);
    force += f;
    torque += cross(turn * c.frame[b.first + k], f) + t;
  }
}

// Each clump's load from what its members' contacts gave (clump_loads), kept for its kicks: the
// phases of a clump's step run apart (gather, kick and drift, place), each light enough for the
// GPU's registers.
struct GatherClumpLoads {
  ClumpSet clumps;
  GrainLoads loads;
  Vec3 *force, *torque; // per clump
  YUXI_HD void operator()(std::uint32_t c) const {
    clump_loads(clumps, clumps.body[c], loads, force[c], torque[c]);
  }
};

// Half a kick of a clump: velocity Verlet's of the centre and NO_SQUISH's of the momentum.
YUXI_ALWAYS_INLINE YUXI_HD void half_kick(RigidBody& b, double dt, const Vec3& force,
                                          const Vec3& torque) {
  const double half_dt = 0.5 * dt;
  const double kick = half_dt / b.mass;
  b.v.x += force.x * kick, b.v.y += force.y * kick, b.v.z += force.z * kick;
  kick_rotor(b.q, b.p, torque, half_dt);
}

// Half kicks of every clump under its kept load, `kicks` of them (1 or 2), then, where `drift`,
// the drift of its centre over dt (ClumpBodies::kick_drift and final_kick; NO_SQUISH's free
// rotation follows, TurnClumps). The second half kick of a step and the next step's first, under
// the same load, are one call of two kicks. Where the clumps do not drift, their angular
// velocity is made anew here (their p changed); otherwise by the last turn.
struct KickClumps {
  ClumpSet clumps;
  const Vec3 *force, *torque; // per clump
  double dt;
  int kicks;
  bool drift;
  YUXI_HD void operator()(std::uint32_t c) const {
    RigidBody b = clumps.body[c];
    for (int k = 0; k < kicks; ++k) half_kick(b, dt, force[c], torque[c]);
    if (drift)
      b.x.x += b.v.x * dt, b.x.y += b.v.y * dt, b.x.z += b.v.z * dt;
    else
      b.omega = lab_angular_velocity(b.q, b.p, b.inertia);
    clumps.body[c] = b;
  }
};

// One turn of NO_SQUISH's free rotation (free_rotation(): R3(h/2) R2(h/2) R1(h) R2(h/2) R3(h/2)),
// about body axis `axis` (1, 2, 3) by h, for every clump; the last of the five makes the angular
// velocity anew. Each turn waits on its sine and cosine: one pass a turn lets the processor run
// many clumps' turns at once (the CPU engine turns its bodies axis by axis too), with each
// clump's operations those of free_rotation() in its order, so its bits.
struct TurnClumps {
  ClumpSet clumps;
  int axis;
  double h;
  bool last;
  YUXI_HD void operator()(std::uint32_t c) const {
    RigidBody& b = clumps.body[c];
    Quaternion q = b.q, p = b.p;
    const double moment = axis == 1 ? b.inertia.x : axis == 2 ? b.inertia.y : b.inertia.z;
    rotate_about_body_axis(q, p, axis, moment, h);
    b.q = q;
    b.p = p;
    if (last) b.omega = lab_angular_velocity(q, p, b.inertia);
  }
};

// Each clump's member given its clump's velocities, v = V + omega x R b and w = omega, and
// (moved_far not null) its place x = X + R b, with whether it now stands more than half the
// skin from where it stood at the last list build (ClumpBodies::place_members; after KickDrift
// or FinalKick, which leave the members).
struct PlaceMembers {
  Particles p;
  ClumpSet clumps;
  double limit2;
  std::uint32_t* moved_far;
  YUXI_HD void operator()(std::uint32_t i) const {
    if (!p.is_member(i)) return;
    const RigidBody& b = clumps.body[p.body_of[i]];
    const Vec3 r = rotation_of(b.q) * clumps.frame[b.first + (p.gid[i] - b.gid)];
    p.v[i] = b.v + cross(b.omega, r);
    p.w[i] = b.omega;
    if (!moved_far) return;
    const Vec3 x = b.x + r;
    p.x[i] = x;
    moved_far[i] = !(norm2(x - p.x_build[i]) <= limit2) ? 1 : 0; // NaN too
  }
};

// At a list build in a step: each clump's centre wrapped into the periodic box, its members
// moved along by the same shift, never wrapped alone (ClumpBodies::wrap).
struct WrapClumps {
  Particles p;
  ClumpSet clumps;
  DeviceBox box;
  YUXI_HD void operator()(std::uint32_t c) const {
    RigidBody& b = clumps.body[c];
    const Vec3 wrapped = box.wrap(b.x);
    if (wrapped == b.x) return;
    const Vec3 shift = wrapped - b.x;
    b.x = wrapped;
    for (std::uint32_t k = 0; k < b.count; ++k) p.x[clumps.member[b.first + k]] += shift;
  }
};

// At a list build: 1 for a clump one of whose members left the box through an open face (it
// leaves whole, as on the CPU), with its mechanical energy; 0 for the others. `gone` holds the
// particles' flags (Escaped).
struct ClumpEscaped {
  ClumpSet clumps;
  const std::uint32_t* gone;
  Vec3 g_potential;
  std::uint32_t* clump_gone;
  double* energy;
  YUXI_HD void operator()(std::uint32_t c) const {
    const RigidBody& b = clumps.body[c];
    bool out = false;
    for (std::uint32_t k = 0; k < b.count; ++k) out = out || gone[clumps.member[b.first + k]] != 0;
    clump_gone[c] = out ? 1 : 0;
    energy[c] =
        out ? rigid_mechanical_energy(b.mass, b.x, b.v, b.q, b.p, b.inertia, g_potential) : 0.0;
  }
};

// Every member of a clump that leaves, flagged to leave with it.
struct MembersLeave {
  Particles p;
  const std::uint32_t* clump_gone;
  std::uint32_t* gone;
  YUXI_HD void operator()(std::uint32_t i) const {
    if (p.is_member(i) && clump_gone[p.body_of[i]]) gone[i] = 1;
  }
};

// Each member's clump index renumbered after clumps left (renumber[old] = new).
struct RenumberClumps {
  const std::uint32_t* renumber;
  std::uint32_t* body_of;
  YUXI_HD void operator()(std::uint32_t i) const {
    if (body_of[i] != no_body) body_of[i] = renumber[body_of[i]];
  }
};

// The clumps' energies [energy] (ClumpBodies::add_energies) and the work of periodic gravity over
// the drift just made, M g_p . V dt (read between the drift and the final kick), as the
// fixed-order sums read them.
struct ClumpTranslationalEnergy {
  const RigidBody* body;
  YUXI_HD double operator[](std::uint64_t c) const {
    return translational_energy(body[c].mass, body[c].v);
  }
};
struct ClumpGravitationalEnergy {
  const RigidBody* body;
  Vec3 g_potential;
  YUXI_HD double operator[](std::uint64_t c) const {
    return -(body[c].mass * dot(g_potential, body[c].x));
  }
};
struct ClumpGravityWork {
  const RigidBody* body;
  Vec3 g_periodic;
  double dt;
  YUXI_HD double operator[](std::uint64_t c) const {
    return body[c].mass * dot(g_periodic, body[c].v) * dt;
  }
};
// (written into an array: its divisions inside the sum's loop would spill registers on the GPU)
struct ClumpRotationalEnergy {
  const RigidBody* body;
  double* energy;
  YUXI_HD void operator()(std::uint32_t c) const {
    energy[c] = rotor_energy(body[c].q, body[c].p, body[c].inertia);
  }
};

} // namespace yuxi::device
