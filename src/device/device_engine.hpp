// The device engine: the whole step on a GPU, or, in the host build, the same code on the CPU
// through Thrust's CPP system (docs/ARCHITECTURE.md, "The device engine"). Its state stays on
// the device between the calls below; the host sees it only when it asks (particles(),
// energies()).
//
// This header is plain C++ (no Thrust, no CUDA): the rest of yuxi includes it from files that g++
// compiles. make_device_engine<Model> is defined in device_engine.cpp, which is compiled by g++
// with Thrust's CPP system (library yuxi_device) and, with -DYUXI_CUDA=ON, by nvcc as CUDA
// (library yuxi_device_cuda).
#pragma once

#include "core/particle_fields.hpp"
#include "core/quaternion.hpp"
#include "core/vec3.hpp"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace yuxi::device {

// The particles a device engine starts from, or that it gives back (in global-id order).
struct HostParticles {
  std::vector<Vec3> x, v, w, f, torque, x_rest;
  // Where each particle stood at the last list build (a run continued mid-way: the engine makes
  // that build's list again, as a checkpoint's is made, and goes on bit for bit); empty: the
  // list is built where the particles stand.
  std::vector<Vec3> x_build;
  std::vector<double> radius, mass, inv_mass, inv_inertia;
  std::vector<GlobalId> gid;
  std::vector<Kind> kind;
  std::vector<std::uint8_t> material;
  std::vector<std::uint16_t> motion; // a wall particle's index into DeviceScene::motions
  // The clump each particle is a member of (its DeviceClump's id), -1 for none; empty: no
  // particle is a member.
  std::vector<GlobalId> body;
  std::size_t size() const { return x.size(); }
};

// A rigid clump of spheres (sim/clump_bodies.hpp, ClumpBody; docs/clumps.md): its members are
// the particles whose `body` is its id, of ids id, id + 1, ... in member order. The body carries
// the motion: its centre of mass, its velocity, its orientation and NO_SQUISH's conjugate
// momentum (core/free_rotation.hpp); the members are placed from it at every drift.
struct DeviceClump {
  GlobalId id = -1;
  double mass = 0;           // M [mass]
  Vec3 inertia;              // principal moments [mass length^2]
  Vec3 x, v;                 // centre of mass and its velocity
  Quaternion q, p;           // body frame -> lab, and its conjugate momentum 2 q (0, L_body)
  Vec3 force, torque;        // of the last evaluation (gravity included; the torque about x)
  std::vector<Vec3> members; // the members' centres in the principal frame [length]
};

// A wall particles' motion: standing still, or the fish basin's radial cosine wave
// (scene/wall_motion.hpp, RadialCosineMotion).
struct DeviceMotion {
  bool radial_cosine = false;
  Vec3 center;
  int mode = 2;
  double amplitude = 0, omega = 0, t0 = 0;
};

// A plane wall (scene/plane_wall.hpp; the box's walls are such planes): a point, the unit normal
// into the grains' side, the material, and its oscillation along the normal,
// A sin(omega (t - t0)) from t0 on.
struct DevicePlane {
  Vec3 point, normal;
  std::uint8_t material = 0;
  double amplitude = 0, omega = 0, t0 = 0;
  // Where the oscillation has it at time t, and how fast it moves: PlaneWall::offset and
  // velocity, operation for operation (computed on the host, for every backend).
  double offset(double t) const {
    return (amplitude == 0.0 || t < t0) ? 0.0 : amplitude * std::sin(omega * (t - t0));
  }
  Vec3 velocity(double t) const {
    if (amplitude == 0.0 || t < t0) return {};
    return (amplitude * omega * std::cos(omega * (t - t0))) * normal;
  }
};

// What the grains did to a plane at the last force evaluation: the force on it, and how many
// grains touch it; and the plane's work on the grains since the engine started.
struct PlaneLoad {
  Vec3 force;
  std::size_t contacts = 0;
  double work = 0;
};

// What the device engine runs: particles in a box that is periodic or open along each axis,
// gravity, one contact law with its coefficients per material pair (Model::Coeffs, row-major,
// n_materials^2 of them), wall particles standing or moving by one of `motions` (at most 8).
struct DeviceScene {
  HostParticles particles;
  Vec3 lo, hi;
  bool periodic[3] = {false, false, false};
  Vec3 gravity;
  double dt = 0, skin = 0, cell_size = 0, time = 0;
  std::size_t n_materials = 1;
  std::vector<DeviceMotion> motions;
  std::vector<DevicePlane> planes; // at most 255
  bool remove_escaped = false;     // a grain out of the box leaves (else it stops the run)
  // The clumps, ids ascending; their members are among the particles.
  std::vector<DeviceClump> clumps;
  // The particles' f and torque, and the clumps', are those of the last step (a run continued
  // mid-way): kept, not computed again at the start.
  bool forces_given = false;
};

// The energy books, each summed in a fixed order [energy].
struct DeviceEnergies {
  double translational = 0, rotational = 0; // now
  double gravitational = 0;                 // -m g . x over grains, g's potential part, now
  std::int64_t grains = 0, contacts = 0;    // now (contacts: touching at the last evaluation)
  double elastic = 0;                       // held in the contacts' springs now
  double relaxation = 0;    // held in the contacts' relaxation buffers now (thermodynamic law)
  double dissipated = 0;    // since the start, releases included
  double gravity_work = 0;  // of periodic gravity since the start
  double wall_work = 0;     // of moving wall particles on the grains since the start
  double removed = 0;       // mechanical energy of the grains removed on escape since the start
  std::int64_t escaped = 0; // grains removed on escape since the start
};

// An open contact: keyed by its particles' ids, smaller first, its state as seen from the
// smaller; a grain-plane contact by the grain's id and -(plane index + 1), as the CPU engine's
// history keys it (contact/contact_history.hpp).
template <class State> struct KeyedState {
  GlobalId first = 0, second = 0;
  State state;
};

// A contact's elastic energy at the last force evaluation, by its particles' ids (a plane's as
// -(plane index + 1)).
struct PairEnergy {
  GlobalId first = 0, second = 0;
  double elastic = 0;
};

// Wall time of each phase of the steps run so far [s]. Thrust's algorithms return once the
// device has finished, so each phase's time is its own.
struct DevicePhaseSeconds {
  double list_build = 0;  // escapes, the cell sort, the list and the contacts' states carried over
  double forces = 0;      // the contact law on each pair and each particle's sum
  double integration = 0; // the two half kicks and the drift, the walls' motion
  double books = 0;       // the energy books' fixed-order sums
};

// Bytes held on the device, by what they hold.
struct DeviceMemory {
  std::size_t particles = 0; // per particle: state, properties, the list's reference positions
  std::size_t cells = 0;     // each cell's first particle
  std::size_t pairs = 0;     // per listed pair: partner, image, flag, slot, the reverse list
  std::size_t contacts = 0;  // per touching pair: the state, force, torques and energies
  std::size_t planes = 0;    // the planes and the grain-plane candidates
  std::size_t clumps = 0;    // the clumps' bodies, their members' frames and indices
  std::size_t work = 0;      // the fixed-order sums' partial sums and Thrust's kept scratch
  std::size_t total() const {
    return particles + cells + pairs + contacts + planes + clumps + work;
  }
  // The most held at once since the engine started, the temporary arrays of list builds and
  // outputs included (on the GPU, Thrust's temporary storage too; the host build's algorithms
  // keep theirs in host memory). Counted per thread: two engines alive on one thread count
  // together.
  std::size_t peak = 0;
};

class DeviceEngine {
public:
  virtual ~DeviceEngine() = default;
  // Advances the state by `steps` time steps.
  virtual void run(std::int64_t steps) = 0;
  // A copy of the particles, in global-id order (forces and torques of the last evaluation;
  // a clump's member's, its contacts' alone).
  virtual HostParticles particles() const = 0;
  // The clumps that remain, ids ascending (force and torque of the last evaluation).
  virtual std::vector<DeviceClump> clumps() const = 0;
  virtual DeviceEnergies energies() const = 0;
  virtual std::int64_t step() const = 0;
  virtual double time() const = 0;
  virtual std::int64_t list_builds() const = 0;
  virtual DevicePhaseSeconds phase_seconds() const = 0;
  // The contacts that held elastic energy at the last force evaluation (per-grain energies of an
  // analysis; copied to the host, so for samples, not every step).
  virtual std::vector<PairEnergy> pair_energies() const = 0;
  // Each plane's load at the last force evaluation, summed in a fixed order.
  virtual std::vector<PlaneLoad> plane_loads() const = 0;
  virtual std::size_t listed_pairs() const = 0;
  // Bytes held on the device now, by part, and in all; and the most held at once.
  virtual DeviceMemory device_memory() const = 0;
  std::size_t device_bytes() const { return device_memory().total(); }
  // "cuda: <device name>" or "host (Thrust CPP)".
  virtual std::string device_name() const = 0;
};

// The engine of one contact law, whose contacts' states the host can read.
template <class Model> class LawEngine : public DeviceEngine {
public:
  // The contacts open now (touching at the last force evaluation), in ascending key order.
  virtual std::vector<KeyedState<typename Model::State>> open_contacts() const = 0;
};

// An engine for contact law `Model`, on the CPU through Thrust's CPP system (the host build,
// library yuxi_device) or as CUDA on the GPU (library yuxi_device_cuda, built with
// -DYUXI_CUDA=ON): the same source, device_engine.cpp. It builds the list and computes the forces
// of the start (without advancing the contacts' history), as the CPU engine does. Throws
// std::invalid_argument naming what it cannot run (a periodic axis of fewer than 3 cells, ids
// beyond 32 bits), and make_cuda_engine std::runtime_error where no GPU is found.
//
// `contacts` are the contacts open at the start (a run continued from another engine), as
// open_contacts() gives them.
template <class Model>
std::unique_ptr<LawEngine<Model>>
make_host_engine(const DeviceScene& scene, const std::vector<typename Model::Coeffs>& coeffs,
                 const std::vector<KeyedState<typename Model::State>>& contacts = {});
template <class Model>
std::unique_ptr<LawEngine<Model>>
make_cuda_engine(const DeviceScene& scene, const std::vector<typename Model::Coeffs>& coeffs,
                 const std::vector<KeyedState<typename Model::State>>& contacts = {});

} // namespace yuxi::device
