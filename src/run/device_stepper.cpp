#include "run/device_stepper.hpp"

#include "analysis/grain_energy.hpp"
#include "contact/contact_history.hpp"
#include "sim/simulation.hpp"

#include <chrono>
#include <stdexcept>
#include <unordered_map>
#include <variant>

namespace yuxi {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// The engine's open contacts as the CPU engine's history stashes them.
template <class Model>
std::string contact_stash(const ContactLaw<Model>&, const device::DeviceEngine& engine,
                          std::size_t& touching) {
  using State = typename Model::State;
  const auto& typed = dynamic_cast<const device::LawEngine<Model>&>(engine);
  const auto open = typed.open_contacts();
  touching = open.size();
  std::vector<typename ContactHistory<State>::Entry> entries(open.size());
  for (std::size_t k = 0; k < open.size(); ++k)
    entries[k] = {{open[k].first, open[k].second}, open[k].state};
  return ContactHistory<State>::pack_entries(entries);
}

} // namespace

DeviceStepper::DeviceStepper(Simulation& sim, DeviceChoice choice) : sim_(sim), choice_(choice) {
  start();
}

void DeviceStepper::start() {
  earlier_ = phase_seconds();
  engine_.reset(); // (its memory first: the new engine's may not fit beside it)
  engine_ = make_device_engine(sim_, choice_);
  start_ = sim_.energies();
  start_step_ = sim_.step_count();
  start_builds_ = sim_.list_builds();
  start_plane_work_.clear();
  for (const WallLoad& load : sim_.plane_loads()) start_plane_work_.push_back(load.work);
  edits_seen_ = sim_.edits();
}

DeviceStepper::~DeviceStepper() = default;

EngineState DeviceStepper::engine_state() const {
  EngineState s;
  device::HostParticles p = engine_->particles();
  s.gid = std::move(p.gid);
  s.x = std::move(p.x);
  s.x_build = std::move(p.x_build);
  s.v = std::move(p.v);
  s.w = std::move(p.w);
  s.f = std::move(p.f);
  s.torque = std::move(p.torque);
  for (const device::DeviceClump& c : engine_->clumps())
    s.clumps.push_back({c.id, c.x, c.v, c.q, c.p, c.force, c.torque});
  s.time = engine_->time();
  s.step = step();
  // (the engine's first build made the list of the simulation's last one again)
  s.list_builds = start_builds_ + engine_->list_builds() - 1;
  s.contact_stash =
      std::visit([&](const auto& law) { return contact_stash(law, *engine_, s.touching); },
                 sim_.contact_law());
  const std::vector<device::PlaneLoad> loads = engine_->plane_loads();
  for (std::size_t k = 0; k < loads.size(); ++k) {
    WallLoad& l = s.plane_loads.emplace_back();
    l.force = loads[k].force;
    l.contacts = loads[k].contacts;
    s.plane_work.push_back((k < start_plane_work_.size() ? start_plane_work_[k] : 0.0) +
                           loads[k].work);
  }
  s.books = books();
  s.elastic = s.books.elastic;
  s.relaxation = s.books.relaxation;
  return s;
}

EnergyBooks DeviceStepper::books() const {
  const device::DeviceEnergies e = engine_->energies();
  EnergyBooks b = start_; // (inserted, and the cumulative books, as the engine started)
  b.step = step();
  b.time = time();
  b.translational = e.translational;
  b.rotational = e.rotational;
  b.gravitational = e.gravitational;
  b.elastic = e.elastic;
  b.relaxation = e.relaxation;
  b.grains = static_cast<std::size_t>(e.grains);
  b.contacts = static_cast<std::size_t>(e.contacts);
  b.dissipated += e.dissipated;
  b.gravity_work += e.gravity_work;
  b.wall_work += e.wall_work;
  b.removed += e.removed;
  b.escaped += static_cast<std::size_t>(e.escaped);
  return b;
}

void DeviceStepper::advance(std::int64_t steps) {
  if (handed_over_ && sim_.edits() != edits_seen_) start();
  const auto t0 = std::chrono::steady_clock::now();
  try {
    engine_->run(steps);
  } catch (const std::runtime_error& e) { // a grain out of the box (on_escape = "stop")
    throw SimulationError(e.what());
  }
  handed_over_ = steps == 0 && handed_over_;
  device_seconds_ += seconds_since(t0);
}

void DeviceStepper::hand_over() {
  if (handed_over_) return;
  const auto t0 = std::chrono::steady_clock::now();
  sim_.take_engine_state(engine_state());
  handed_over_ = true;
  edits_seen_ = sim_.edits();
  handover_seconds_ += seconds_since(t0);
}

std::vector<double> DeviceStepper::particle_elastic_energy() const {
  if (!handed_over_)
    throw std::logic_error("particle_elastic_energy: the state was not handed over");
  const ParticleStore& s = sim_.particles();
  std::unordered_map<GlobalId, std::size_t> index;
  index.reserve(s.n_owned());
  for (std::size_t i = 0; i < s.n_owned(); ++i) index.emplace(s.gid[i], i);
  std::vector<analysis::ContactEnergy> contacts;
  // (a plane's half goes to no grain: run/particle_elastic_energy.cpp)
  for (const device::PairEnergy& e : engine_->pair_energies())
    contacts.push_back(
        {index.at(e.first), e.second < 0 ? analysis::wall_partner : index.at(e.second), e.elastic});
  return analysis::grain_elastic_energy(s.n_owned(), contacts);
}

std::int64_t DeviceStepper::step() const {
  return start_step_ + engine_->step();
}

double DeviceStepper::time() const {
  return engine_->time();
}

device::DevicePhaseSeconds DeviceStepper::phase_seconds() const {
  device::DevicePhaseSeconds t = earlier_;
  if (engine_) {
    const device::DevicePhaseSeconds now = engine_->phase_seconds();
    t.list_build += now.list_build;
    t.forces += now.forces;
    t.integration += now.integration;
    t.books += now.books;
  }
  return t;
}

std::string DeviceStepper::device_name() const {
  return engine_->device_name();
}

double DeviceStepper::device_bytes_per_particle(bool peak) const {
  const double n = static_cast<double>(sim_.particles().n_owned());
  const device::DeviceMemory m = engine_->device_memory();
  return static_cast<double>(peak ? m.peak : m.total()) / std::max(n, 1.0);
}

} // namespace yuxi
