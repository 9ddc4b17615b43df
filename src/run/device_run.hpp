// A device engine (device/device_engine.hpp) for a simulation's scene, or a clear refusal.
//
// The device engine runs grains, wall particles (still or moving by the basin's wave) and planes
// (still or oscillating; the box's walls among them) in a box that is periodic or open along each
// axis, under gravity, with any contact law. A scene with more (meshes, cylinders, wall particles
// in rigid motion, inserts, outlets, several MPI ranks) is refused with an error that names each
// table it does not run: it never falls back to the CPU in silence.
#pragma once

#include "device/device_engine.hpp"

#include <memory>
#include <string>
#include <vector>

namespace yuxi {

class Simulation;

enum class DeviceChoice {
  host, // the device engine's code on the CPU (Thrust's CPP system): the reference build
  cuda, // the same code as CUDA on a GPU (a build with -DYUXI_CUDA=ON)
};

// What of `sim`'s scene the device engine does not run, one line each (empty: it runs all).
std::vector<std::string> device_engine_refusals(const Simulation& sim);
// Throws std::runtime_error where the choice is cuda and this build has no CUDA.
void check_device_choice(DeviceChoice choice);
// True where this build has the device engine for CUDA GPUs (-DYUXI_CUDA=ON).
bool build_has_cuda();

// Copies of the scene side by side along periodic axes (LAMMPS's `replicate`): a benchmark's
// way to a large system from a settled small one.
struct Replicas {
  int n[3] = {1, 1, 1};
};

// The engine, started from `sim`'s current state (tiled `replicas` times, each copy's ids offset
// by a multiple of the largest id + 1). Throws std::invalid_argument listing the refusals (or
// where a copy would go along an axis that is not periodic), or std::runtime_error where the
// choice is cuda and the build has no CUDA or the machine no GPU.
std::unique_ptr<device::DeviceEngine> make_device_engine(const Simulation& sim, DeviceChoice choice,
                                                         Replicas replicas = {});

} // namespace yuxi
