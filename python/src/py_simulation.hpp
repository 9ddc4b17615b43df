// The Python API's simulation: a run opened from a scene, a run folder or a checkpoint, advanced
// in pieces by a RunDriver (the same files as `yuxi run`), with numpy views of this rank's
// particles and the changes between steps of Simulation's edits (simulation_edits.cpp).
#pragma once

#include "domain/collective_guard.hpp"
#include "py_scene.hpp"
#include "run/run_driver.hpp"
#include "run/run_opening.hpp"

#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <span>

namespace yuxi::python {

class PySimulation {
public:
  // A scene from t = 0, writing into `output` (runs/<name> when empty).
  // `device` ("cpu", "gpu" or "host"), where given, overrides the scene's run.device.
  PySimulation(const PyScene& scene, const std::string& output, bool overwrite, bool progress,
               bool force_dt, const std::optional<std::string>& device);
  // A run folder from its newest valid checkpoint (to a later end if `t_end` is given).
  static std::unique_ptr<PySimulation> resume(const std::string& folder,
                                              std::optional<double> t_end, bool progress,
                                              const std::optional<std::string>& device);
  // A checkpoint's state under another scene (yuxi run SCENE --from CHECKPOINT).
  static std::unique_ptr<PySimulation> branch(const std::string& from, const PyScene& scene,
                                              const std::string& output, bool overwrite,
                                              bool progress, bool force_dt,
                                              const std::optional<std::string>& device);

  // Steps to `until` (a step count), calling `callback(self)` every `every` steps; the
  // callback stops the run by returning False.
  void advance(pybind11::object self, std::int64_t until, pybind11::object callback,
               std::int64_t every);
  // One more insert, from an [[insert]] table as TOML text ("[[insert]]\n..."): it joins the
  // run's scene (and so its checkpoints) and pours from the next step on; returns its name.
  std::string add_insert(const std::string& table_toml);
  // New grains, or clumps (Simulation::add_grains, add_clumps; a shape of one member gives
  // spheres, as a fill does). Collective. What they bring meets the time-step check that a
  // scene's grains meet at the start, and is taken back where it fails. Returns their ids.
  std::vector<GlobalId> add_grains(std::span<const ParticleSpec> grains);
  std::vector<GlobalId> add_clumps(std::vector<PlacedClump> clumps);
  // Writes a checkpoint (into the run folder when `path` is empty); returns the file.
  std::string checkpoint(const std::string& path);
  pybind11::dict finish();
  // Finishes the run and frees the engine (before MPI ends). Collective.
  void close();

  // Every call on a closed simulation raises RuntimeError through these two.
  Simulation& sim() {
    if (!run_.sim) throw std::runtime_error("the simulation was closed");
    return *run_.sim;
  }
  const Simulation& sim() const {
    if (!run_.sim) throw std::runtime_error("the simulation was closed");
    return *run_.sim;
  }
  const Scene& scene() const { return run_.scene; }
  const std::filesystem::path& folder() const { return folder_; }
  RunDriver& driver() {
    if (!driver_) throw std::runtime_error("the simulation was closed");
    return *driver_;
  }
  // Changes with every step and every edit: a view of an older generation is stale.
  pybind11::tuple generation() const;
  void edited() { ++edits_; }
  bool finished() const { return finished_; }

  void set_progress(bool on) { progress_ = on; }

  // Called first by every collective call (one that every rank must make, in the same order):
  // raises CollectiveMismatch instead of waiting forever where the ranks do not all make it
  // (domain/collective_guard.hpp).
  void collective(const char* call) { guard().enter(call); }
  CollectiveGuard& guard() {
    if (!guard_) throw std::runtime_error("the simulation was closed");
    return *guard_;
  }

private:
  PySimulation() = default;
  void open_driver(bool resumed);
  // Whether the run as it stands passes the time-step check (collective): an addition is
  // refused only where it makes a passing check fail, not for the speeds of grains already there.
  bool time_step_holds();
  // The time-step check of what was just added (add_grains(), add_clumps()): where it fails,
  // `take_back()` and the books put back as they were (`books_before`: what the addition and the
  // taking back booked undone, escapes its list build found kept), then the error again (a time
  // step's named as `call`'s).
  void check_added(const char* call, const EnergyBooks& books_before,
                   const std::function<void()>& take_back);

  OpenedRun run_;
  std::filesystem::path folder_;
  std::unique_ptr<RunDriver> driver_;
  std::unique_ptr<CollectiveGuard> guard_;
  std::int64_t edits_ = 0;
  bool progress_ = true;
  bool force_dt_ = false; // (the time-step check of what add_insert pours)
  bool finished_ = false;
  // A KeyboardInterrupt met while stepping: the run checkpoints, then it is raised.
  std::optional<pybind11::error_already_set> interrupt_;
};

void bind_simulation(pybind11::module_& m);

} // namespace yuxi::python
