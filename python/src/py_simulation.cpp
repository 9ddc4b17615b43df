#include "py_simulation.hpp"

#include "io/scene_error.hpp"
#include "io/scene_writer.hpp"
#include "io/source_scene_reader.hpp"
#include "py_clumps.hpp"
#include "py_contacts.hpp"
#include "run/simulation_checkpoint.hpp"
#include "scene/particle_fill.hpp"
#include "scene/wall_controller.hpp"

#include <cstring>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <pybind11/functional.h>
#include <pybind11/stl.h>

namespace py = pybind11;
using namespace pybind11::literals;
namespace fs = std::filesystem;

namespace yuxi::python {
namespace {

static_assert(sizeof(Vec3) == 3 * sizeof(double), "Vec3 must be three packed doubles");

// Progress lines through Python's sys.stderr, which a notebook shows.
void write_progress(const std::string& line) {
  py::module_::import("sys").attr("stderr").attr("write")(line);
  py::module_::import("sys").attr("stderr").attr("flush")();
}

// A controller written in Python: speed = f(resisting force, time).
class PythonController final : public WallController {
public:
  explicit PythonController(py::function f) : f_(std::move(f)) {}
  double speed(double resisting, double t) override { return f_(resisting, t).cast<double>(); }

private:
  py::function f_;
};

std::size_t insert_index(const Simulation& sim, const std::string& name) {
  std::vector<std::string> names;
  for (std::size_t k = 0; k < sim.inserts().size(); ++k) {
    if (sim.inserts()[k].name == name) return k;
    names.push_back(sim.inserts()[k].name);
  }
  throw py::key_error(
      fmt::format("no insert named '{}' (the run has: {})", name,
                  names.empty() ? "none" : fmt::format("{}", fmt::join(names, ", "))));
}

std::size_t wall_index(Simulation& sim, const std::string& name) {
  for (std::size_t w = 0; w < sim.shaped_walls().size(); ++w)
    if (wall_name(sim.shaped_walls()[w]) == name) return w;
  std::vector<std::string> names;
  for (const auto& w : sim.shaped_walls()) names.push_back(wall_name(w));
  throw py::key_error(fmt::format("no mesh or cylinder named '{}' (the scene has: {})", name,
                                  fmt::join(names, ", ")));
}

using IdArray = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>;
using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

// An (n, 3) array of doubles as Vec3s (copied: the engine's arrays are not the caller's).
std::vector<Vec3> vec3s(const DoubleArray& a, const char* what) {
  if (a.ndim() != 2 || a.shape(1) != 3)
    throw py::value_error(fmt::format("{}: expected an array of shape (n, 3)", what));
  std::vector<Vec3> out(static_cast<std::size_t>(a.shape(0)));
  const double* p = a.data();
  for (std::size_t k = 0; k < out.size(); ++k) out[k] = {p[3 * k], p[3 * k + 1], p[3 * k + 2]};
  return out;
}

// Particle ids: a one-dimensional array of integers (an empty one of any type). A boolean
// mask or floats are refused: numpy would turn a mask into the ids 0 and 1, and 1.5 into 1.
std::vector<GlobalId> ids_of(const py::array& given, const char* call) {
  if (given.ndim() != 1)
    throw py::value_error(fmt::format("{}: ids must be a one-dimensional array of particle ids, "
                                      "not of shape {}",
                                      call, py::str(given.attr("shape")).cast<std::string>()));
  const char kind = given.dtype().kind();
  if (given.size() > 0 && kind == 'b')
    throw py::type_error(fmt::format("{}: ids must be particle ids (integers), not a boolean mask; "
                                     "pass sim.particles.id[mask]",
                                     call));
  if (given.size() > 0 && kind != 'i' && kind != 'u')
    throw py::type_error(fmt::format(
        "{}: ids must be particle ids (integers), not {}; pass an integer array such as "
        "sim.particles.id",
        call, py::str(given.dtype()).cast<std::string>()));
  const IdArray a = IdArray::ensure(given);
  return {a.data(), a.data() + a.shape(0)};
}

// A view of n Vec3s or scalars of the engine's memory: no copy, read-only, keeping `owner`
// alive. (Valid until the next step: the Python layer checks the generation.)
template <class T> py::array view(const T* data, std::size_t n, py::handle owner) {
  py::array a;
  if constexpr (std::is_same_v<T, Vec3>)
    a = py::array_t<double>(
        {static_cast<py::ssize_t>(n), py::ssize_t{3}},
        {static_cast<py::ssize_t>(sizeof(Vec3)), static_cast<py::ssize_t>(sizeof(double))},
        reinterpret_cast<const double*>(data), owner);
  else
    a = py::array_t<T>({static_cast<py::ssize_t>(n)}, {static_cast<py::ssize_t>(sizeof(T))}, data,
                       owner);
  a.attr("setflags")(py::arg("write") = false);
  return a;
}

// The particle fields of the API by name: one table for the views and for gather(). `f` gets
// the field's array.
template <class F> py::object with_field(const ParticleStore& p, const std::string& name, F&& f) {
  if (name == "id") return f(p.gid);
  if (name == "kind") return f(p.kind);
  if (name == "material") return f(p.material);
  if (name == "radius") return f(p.radius);
  if (name == "mass") return f(p.mass);
  if (name == "position") return f(p.x);
  if (name == "velocity") return f(p.v);
  if (name == "angular_velocity") return f(p.w);
  if (name == "force") return f(p.f);
  if (name == "torque") return f(p.torque);
  if (name == "clump") return f(p.body);
  throw py::key_error(fmt::format("no particle field '{}'", name));
}

// A field's elements as numpy takes them (a kind as its byte).
template <class T> const T* elements(const std::vector<T>& field) {
  return field.data();
}
const std::uint8_t* elements(const std::vector<Kind>& field) {
  static_assert(sizeof(Kind) == 1);
  return reinterpret_cast<const std::uint8_t*>(field.data());
}

// A binding of one of Simulation's writes by id (velocities, angular velocities, positions).
// `moves_arrays`: the write builds the list afresh, which moves the arrays (views go stale).
auto setter(void (Simulation::*write)(std::span<const GlobalId>, std::span<const Vec3>),
            const char* call, const char* what, bool moves_arrays = false) {
  return [write, call, what, moves_arrays](PySimulation& s, const py::array& ids,
                                           const DoubleArray& values) {
    const auto id = ids_of(ids, call);
    const auto v = vec3s(values, what);
    if (moves_arrays) s.collective(call); // (a list build: collective)
    (s.sim().*write)(id, v);
    if (moves_arrays) s.edited();
  };
}

// A binding of one of Simulation's collective removals by id (grains, clumps): returns how many
// went on all ranks.
auto remover(std::int64_t (Simulation::*remove)(std::span<const GlobalId>), const char* name,
             const char* call) {
  return [remove, name, call](PySimulation& s, const py::array& ids) {
    const auto id = ids_of(ids, name);
    s.collective(call);
    const std::int64_t n = (s.sim().*remove)(id);
    s.edited();
    return n;
  };
}

// New particles' ids as a numpy array.
py::array_t<std::int64_t> id_array(const std::vector<GlobalId>& ids) {
  return py::array_t<std::int64_t>(static_cast<py::ssize_t>(ids.size()), ids.data());
}

py::dict books_dict(const EnergyBooks& e) {
  py::dict d;
  d["step"] = e.step;
  d["time"] = e.time;
  d["translational"] = e.translational;
  d["rotational"] = e.rotational;
  d["kinetic"] = e.kinetic();
  d["elastic"] = e.elastic;
  d["gravitational"] = e.gravitational;
  d["relaxation"] = e.relaxation;
  d["mechanical"] = e.mechanical();
  d["dissipated"] = e.dissipated;
  d["wall_work"] = e.wall_work;
  d["removed"] = e.removed;
  d["gravity_work"] = e.gravity_work;
  d["inserted"] = e.inserted;
  d["balance"] = e.balance();
  d["grains"] = e.grains;
  d["contacts"] = e.contacts;
  d["escaped"] = e.escaped;
  return d;
}

py::array_t<double> vec3_array(const Vec3& v) {
  py::array_t<double> a(3);
  auto m = a.mutable_unchecked<1>();
  m(0) = v.x, m(1) = v.y, m(2) = v.z;
  return a;
}

py::dict load_dict(const WallLoad& l) {
  py::dict d;
  d["force"] = vec3_array(l.force);
  d["torque"] = vec3_array(l.torque);
  d["work"] = l.work;
  d["contacts"] = l.contacts;
  return d;
}

py::list tallies(const std::vector<Simulation::SourceTally>& flows) {
  py::list out;
  for (const auto& f : flows) {
    py::dict d;
    d["name"] = f.name;
    d["grains"] = f.grains;
    d["mass"] = f.mass;
    d["owed"] = f.owed;
    out.append(d);
  }
  return out;
}

// The engine `device` names, where given (a word that names none raises ValueError).
std::optional<RunDevice> device_named(const std::optional<std::string>& device) {
  if (!device) return std::nullopt;
  const std::optional<RunDevice> named = run_device_named(*device);
  if (!named)
    throw py::value_error(
        fmt::format("device: '{}' is none of \"cpu\", \"gpu\", \"host\"", *device));
  return named;
}

// The scene's run.device set to `device`, where given; true where it was.
bool set_device(Scene& scene, std::optional<RunDevice> device) {
  if (device) scene.run.device = *device;
  return device.has_value();
}

// A run asked for the device engine that cannot run there is refused before its folder is made.
void check_device(const OpenedRun& run) {
  if (const auto choice = device_choice(run.scene.run.device)) check_device_run(*run.sim, *choice);
}

} // namespace

PySimulation::PySimulation(const PyScene& scene, const std::string& output, bool overwrite,
                           bool progress, bool force_dt, const std::optional<std::string>& device)
    : progress_(progress), force_dt_(force_dt) {
  Scene chosen = scene.scene;
  set_device(chosen, device_named(device));
  run_ = open_scene(std::move(chosen), force_dt);
  check_device(run_);
  folder_ = create_run_folder(run_.sim->comm(), output, run_.scene, overwrite, run_.scene_text);
  open_driver(false);
}

std::unique_ptr<PySimulation> PySimulation::resume(const std::string& folder,
                                                   std::optional<double> t_end, bool progress,
                                                   const std::optional<std::string>& device) {
  std::unique_ptr<PySimulation> s(new PySimulation());
  s->progress_ = progress;
  const std::optional<RunDevice> engine = device_named(device); // (before the file is read)
  s->run_ = open_resume(folder, [&](Scene& scene) {
    if (t_end) scene.run.t_end = *t_end;
    return set_device(scene, engine) || t_end.has_value();
  });
  check_device(s->run_);
  s->folder_ = folder;
  s->open_driver(true);
  return s;
}

std::unique_ptr<PySimulation> PySimulation::branch(const std::string& from, const PyScene& scene,
                                                   const std::string& output, bool overwrite,
                                                   bool progress, bool force_dt,
                                                   const std::optional<std::string>& device) {
  std::unique_ptr<PySimulation> s(new PySimulation());
  s->progress_ = progress;
  s->force_dt_ = force_dt;
  Scene chosen = scene.scene;
  set_device(chosen, device_named(device));
  s->run_ = open_branch(std::move(chosen), from, force_dt);
  check_device(s->run_);
  s->folder_ =
      create_run_folder(s->run_.sim->comm(), output, s->run_.scene, overwrite, s->run_.scene_text);
  s->open_driver(false);
  return s;
}

void PySimulation::open_driver(bool resumed) {
  RunOptions o;
  o.output_dir = folder_;
  o.scene_text = run_.scene_text;
  o.resumed = resumed;
  // Ctrl-C: Python's handler has set its flag; the run checkpoints, and the interrupt is
  // raised once it has.
  o.stop_requested = [this] {
    if (interrupt_) return true; // (asked again after the checkpoint)
    if (PyErr_CheckSignals() == 0) return false;
    interrupt_.emplace();
    return true;
  };
  o.progress_sink = write_progress;
  o.device = device_choice(run_.scene.run.device);
  driver_ = std::make_unique<RunDriver>(run_.scene, *run_.sim, o);
  guard_ = std::make_unique<CollectiveGuard>(run_.sim->comm());
}

py::tuple PySimulation::generation() const {
  return py::make_tuple(sim().step_count(), edits_);
}

void PySimulation::advance(py::object self, std::int64_t until, py::object callback,
                           std::int64_t every) {
  if (finished_) throw std::runtime_error("the simulation was closed");
  collective("advance()");
  RunDriver& d = driver();
  if (until > d.end_step()) d.set_end_time(static_cast<double>(until) * run_.scene.sim.dt);
  StepHook hook;
  // An exception in the callback stops the run at that step, and is raised once it has
  // (KeyboardInterrupt after a checkpoint, as Ctrl-C between callbacks).
  std::optional<py::error_already_set> callback_error;
  if (!callback.is_none()) {
    if (every < 1) throw py::value_error("every: must be at least 1");
    hook.every = every;
    hook.call = [&] {
      try {
        const py::object answer = callback(self);
        return !(answer.is(py::bool_(false)));
      } catch (py::error_already_set& e) {
        if (e.matches(PyExc_KeyboardInterrupt))
          interrupt_.emplace(std::move(e));
        else
          callback_error.emplace(std::move(e));
        return false;
      }
    };
  }
  d.set_show_progress(progress_);
  const bool ok = d.advance(until, hook);
  // A callback that raised on one rank stopped every rank (RunDriver::advance): each raises,
  // so that no rank goes on alone into a collective call.
  const bool raised_elsewhere =
      !callback.is_none() && sim().comm().any(callback_error.has_value()) && !callback_error;
  if (interrupt_) {
    if (ok) d.write_checkpoint(); // (a stop by signal has written one)
    py::error_already_set e = std::move(*interrupt_);
    interrupt_.reset();
    throw e;
  }
  if (raised_elsewhere)
    throw std::runtime_error("the run stopped: the callback raised an exception on another rank");
  if (callback_error) throw std::move(*callback_error);
  if (!ok) {
    const RunSummary s = d.finish();
    finished_ = true;
    throw std::runtime_error(fmt::format("the simulation stopped: {}; its last state is in {}",
                                         s.failure, (folder_ / "failure.vtu").string()));
  }
}

std::string PySimulation::add_insert(const std::string& table_toml) {
  Simulation& engine = sim();
  collective("add_insert()");
  const InsertSpec spec = add_insert_table(run_.scene, table_toml, "<add_insert>");
  try {
    engine.add_insert(spec);
  } catch (...) {
    run_.scene.inserts.pop_back();
    throw;
  }
  // The grains it pours meet the time-step check, as a scene's inserts do at the start.
  try {
    BuildReport report;
    check_running_time_step(run_.scene, engine, force_dt_, report);
  } catch (...) {
    engine.withdraw_last_insert();
    run_.scene.inserts.pop_back();
    throw;
  }
  run_.scene_text = resolved_scene_toml(run_.scene);
  driver().scene_changed(run_.scene_text);
  return spec.name;
}

void PySimulation::check_added(const char* call, const EnergyBooks& books_before,
                               const std::function<void()>& take_back) {
  // The books after the addition: its list build booked the grains that had escaped since the
  // last one as removed, which stands. What the addition and the taking back booked does not:
  // `inserted` as before the call, `removed` as after the addition.
  const EnergyBooks added = sim().cumulative_books();
  const auto undo = [&] {
    take_back();
    EnergyBooks books = sim().cumulative_books();
    books.inserted = books_before.inserted;
    books.removed = added.removed;
    sim().put_back_books(books);
  };
  try {
    BuildReport report;
    check_running_time_step(run_.scene, sim(), force_dt_, report);
  } catch (const TimeStepError& e) {
    undo();
    throw TimeStepError(fmt::format("{}: none added: with them, {}", call, e.what()));
  } catch (...) {
    undo();
    throw;
  }
}

bool PySimulation::time_step_holds() {
  try {
    BuildReport report;
    check_running_time_step(run_.scene, sim(), force_dt_, report);
    return true;
  } catch (const TimeStepError&) {
    return false;
  }
}

std::vector<GlobalId> PySimulation::add_grains(std::span<const ParticleSpec> grains) {
  collective("add_grains()");
  const bool held = time_step_holds(); // (judged only where the run's own state passes)
  const EnergyBooks books = sim().cumulative_books();
  const std::vector<GlobalId> ids = sim().add_grains(grains);
  edited();
  if (held) check_added("add_grains()", books, [&] { sim().remove_grains(ids); });
  return ids;
}

std::vector<GlobalId> PySimulation::add_clumps(std::vector<PlacedClump> clumps) {
  if (!clumps.empty() && clumps.front().members.size() == 1) {
    std::vector<ParticleSpec> spheres;
    for (const PlacedClump& c : clumps) spheres.push_back(lone_member_as_sphere(c));
    return add_grains(spheres);
  }
  collective("add_clumps()");
  const bool held = time_step_holds();
  const EnergyBooks books = sim().cumulative_books();
  const std::vector<GlobalId> ids = sim().add_clumps(std::move(clumps));
  edited();
  if (held) check_added("add_clumps()", books, [&] { sim().remove_clumps(ids); });
  return ids;
}

std::string PySimulation::checkpoint(const std::string& path) {
  RunDriver& d = driver();
  collective("checkpoint()");
  if (path.empty()) return d.write_checkpoint().string();
  write_checkpoint(path, run_.scene_text, sim());
  return path;
}

py::dict PySimulation::finish() {
  py::dict d;
  if (finished_ || !driver_) return d;
  collective("finish()");
  const RunSummary s = driver_->finish();
  finished_ = true;
  d["steps"] = s.steps;
  d["wall_seconds"] = s.wall_seconds;
  d["particle_steps_per_second"] = s.particle_steps_per_second;
  if (!s.device.empty()) {
    d["device"] = s.device;
    d["device_bytes_per_particle"] = s.device_bytes_per_particle;
    d["device_peak_bytes_per_particle"] = s.device_peak_bytes_per_particle;
  }
  d["energies"] = books_dict(s.final_energies);
  return d;
}

void PySimulation::close() {
  if (!run_.sim) return;
  collective("close()");
  finish();
  driver_.reset();
  guard_.reset();
  run_.sim.reset();
}

void bind_simulation(py::module_& m) {
  // A collective call that not every rank made (domain/collective_guard.hpp).
  py::register_exception<CollectiveMismatch>(m, "CollectiveError", PyExc_RuntimeError);
  py::class_<PySimulation>(m, "_Simulation")
      .def(py::init<const PyScene&, const std::string&, bool, bool, bool,
                    const std::optional<std::string>&>(),
           py::arg("scene"), py::arg("output") = "", py::arg("overwrite") = false,
           py::arg("progress") = true, py::arg("force_dt") = false,
           py::arg("device") = std::nullopt)
      .def_static("resume", &PySimulation::resume, py::arg("folder"),
                  py::arg("t_end") = std::nullopt, py::arg("progress") = true,
                  py::arg("device") = std::nullopt)
      .def_static("branch", &PySimulation::branch, py::arg("checkpoint"), py::arg("scene"),
                  py::arg("output") = "", py::arg("overwrite") = false, py::arg("progress") = true,
                  py::arg("force_dt") = false, py::arg("device") = std::nullopt)
      .def(
          "advance",
          [](py::object self, std::int64_t until, py::object callback, std::int64_t every) {
            self.cast<PySimulation&>().advance(self, until, callback, every);
          },
          py::arg("until"), py::arg("callback") = py::none(), py::arg("every") = 100)
      .def("checkpoint", &PySimulation::checkpoint, py::arg("path") = "")
      .def("finish", &PySimulation::finish)
      .def("close", &PySimulation::close)
      .def("set_progress", &PySimulation::set_progress)
      .def_property(
          "collective_timeout", [](PySimulation& s) { return s.guard().timeout(); },
          [](PySimulation& s, double seconds) { s.guard().set_timeout(seconds); })
      .def_property_readonly("generation", &PySimulation::generation)
      .def_property_readonly("finished", &PySimulation::finished)
      .def_property_readonly("folder", [](PySimulation& s) { return s.folder().string(); })
      .def_property_readonly("time", [](PySimulation& s) { return s.sim().time(); })
      .def_property_readonly("step_count", [](PySimulation& s) { return s.sim().step_count(); })
      .def_property_readonly("dt", [](PySimulation& s) { return s.sim().config().dt; })
      .def_property_readonly("end_step", [](PySimulation& s) { return s.driver().end_step(); })
      .def_property_readonly("rank", [](PySimulation& s) { return s.sim().comm().rank(); })
      .def_property_readonly("ranks", [](PySimulation& s) { return s.sim().comm().size(); })
      .def_property_readonly("scene_toml",
                             [](PySimulation& s) { return resolved_scene_toml(s.scene()); })
      .def_property_readonly("materials", [](PySimulation& s) { return s.scene().materials; })
      .def("_box",
           [](PySimulation& s) {
             const Box& b = s.sim().config().box;
             std::string periodic;
             for (int a = 0; a < 3; ++a)
               if (b.periodic(a)) periodic += static_cast<char>('x' + a);
             return py::dict("lo"_a = std::vector<double>{b.lo.x, b.lo.y, b.lo.z},
                             "hi"_a = std::vector<double>{b.hi.x, b.hi.y, b.hi.z},
                             "periodic"_a = periodic);
           })
      .def("_array",
           [](py::object self, const std::string& name) {
             const ParticleStore& p = self.cast<PySimulation&>().sim().particles();
             return with_field(p, name, [&](const auto& field) -> py::object {
               return view(elements(field), p.n_owned(), self);
             });
           })
      .def("gather",
           [](PySimulation& s, const std::string& name) -> py::object {
             with_field(s.sim().particles(), name, [](const auto&) { return py::object(); });
             s.collective("gather()");
             const ParticleStore all = s.sim().gather_particles(); // collective
             if (!s.sim().comm().root()) return py::none();
             return with_field(all, name, [&](const auto& field) -> py::object {
               return view(elements(field), all.n_owned(), py::none()).attr("copy")();
             });
           })
      .def("energies",
           [](PySimulation& s) {
             s.collective("energies()");
             return books_dict(s.sim().energies());
           })
      .def("wall_loads",
           [](PySimulation& s) {
             py::dict d;
             s.collective("wall_loads()");
             const auto shaped = s.sim().shaped_wall_loads(); // collective
             for (std::size_t w = 0; w < shaped.size(); ++w)
               d[py::str(wall_name(s.sim().shaped_walls()[w]))] = load_dict(shaped[w]);
             const auto planes = s.sim().plane_loads(); // collective
             for (std::size_t p = 0; p < planes.size(); ++p)
               d[py::str(s.sim().planes()[p].name)] = load_dict(planes[p]);
             return d;
           })
      .def("inflow", [](PySimulation& s) { return tallies(s.sim().inflow()); })
      .def("outflow",
           [](PySimulation& s) {
             s.collective("outflow()");
             return tallies(s.sim().outflow());
           })
      .def("set_velocities", setter(&Simulation::set_velocities, "set_velocities", "velocities"))
      .def("set_angular_velocities", setter(&Simulation::set_angular_velocities,
                                            "set_angular_velocities", "angular velocities"))
      .def("set_positions", setter(&Simulation::set_positions, "set_positions", "positions", true))
      .def("add_grains",
           [](PySimulation& s, const DoubleArray& x, const DoubleArray& radius,
              const DoubleArray& v, const std::string& material) {
             const auto at = vec3s(x, "positions");
             const auto vel = vec3s(v, "velocities");
             if (radius.ndim() != 1 || static_cast<std::size_t>(radius.shape(0)) != at.size() ||
                 vel.size() != at.size())
               throw py::value_error("add_grains: positions, radii and velocities differ in "
                                     "length");
             const auto kind = s.scene().material_index(material);
             if (!kind) throw py::value_error(fmt::format("no material '{}'", material));
             const double density = s.scene().material_properties[*kind].density;
             if (!(density > 0))
               throw py::value_error(fmt::format("material '{}' has no density", material));
             GrainKind grain;
             grain.density = density;
             std::vector<ParticleSpec> grains(at.size());
             for (std::size_t k = 0; k < at.size(); ++k) {
               const double r = radius.at(static_cast<py::ssize_t>(k));
               grains[k].position = at[k];
               grains[k].velocity = vel[k];
               grains[k].radius = r;
               grains[k].mass = grain.mass_of(r);
               grains[k].material = *kind;
             }
             const std::vector<GlobalId> ids = s.add_grains(grains);
             return id_array(ids);
           })
      .def("add_clumps",
           [](PySimulation& s, const std::string& shape, const DoubleArray& x, const DoubleArray& q,
              const DoubleArray& v, const DoubleArray& w, const DoubleArray& scale,
              const std::string& material, bool principal) {
             const std::vector<GlobalId> ids = s.add_clumps(
                 placed_clumps(s.scene(), shape, x, q, v, w, scale, material, principal));
             return id_array(ids);
           })
      .def("remove_clumps", remover(&Simulation::remove_clumps, "remove_clumps", "remove_clumps()"))
      .def("set_clump_poses",
           [](PySimulation& s, const py::array& ids, const DoubleArray& x,
              const std::optional<DoubleArray>& q) {
             const auto id = ids_of(ids, "set_clump_poses");
             const auto at = vec3s(x, "positions");
             std::vector<Quaternion> turn;
             if (q) {
               if (q->ndim() != 2 || q->shape(1) != 4)
                 throw py::value_error("set_clump_poses: orientations: expected an array of "
                                       "shape (n, 4)");
               turn = unit_quaternions({q->data(), static_cast<std::size_t>(q->size())},
                                       "set_clump_poses");
             }
             s.collective("set_clump_poses()"); // (a list build: collective)
             s.sim().set_clump_poses(id, at, turn);
             s.edited();
           })
      .def("set_clump_velocities",
           setter(&Simulation::set_clump_velocities, "set_clump_velocities", "velocities"))
      .def("set_clump_angular_velocities",
           setter(&Simulation::set_clump_angular_velocities, "set_clump_angular_velocities",
                  "angular velocities"))
      .def("remove_grains", remover(&Simulation::remove_grains, "remove_grains", "remove_grains()"))
      .def("set_wall_speed",
           [](PySimulation& s, const std::string& name, double speed) {
             const std::size_t w = wall_index(s.sim(), name);
             s.sim().set_servo_controller(w, std::make_shared<HeldSpeed>(speed));
           })
      .def("set_wall_controller",
           [](PySimulation& s, const std::string& name, py::function f) {
             const std::size_t w = wall_index(s.sim(), name);
             s.sim().set_servo_controller(w, std::make_shared<PythonController>(std::move(f)));
           })
      .def("wall_motion",
           [](PySimulation& s, const std::string& name) {
             const auto [speed, offset] = s.sim().servo_state(wall_index(s.sim(), name));
             py::dict d;
             d["speed"] = speed;
             d["offset"] = offset;
             return d;
           })
      .def("start_insert",
           [](PySimulation& s, const std::string& name) {
             s.sim().start_insert(insert_index(s.sim(), name));
           })
      .def("pause_insert",
           [](PySimulation& s, const std::string& name) {
             s.sim().pause_insert(insert_index(s.sim(), name));
           })
      .def("stop_insert",
           [](PySimulation& s, const std::string& name) {
             s.sim().stop_insert(insert_index(s.sim(), name));
           })
      .def("add_insert", &PySimulation::add_insert, py::arg("table"))
      .def("record_contacts",
           [](PySimulation& s, bool on) {
             if (on && device_choice(s.scene().run.device))
               throw std::runtime_error("contacts are recorded by the CPU engine only: this run "
                                        "is on the device engine (device = \"cpu\" records "
                                        "them)");
             s.sim().record_contacts(on);
           })
      .def("contacts", [](PySimulation& s) { return contact_arrays(s.sim()); })
      .def("clumps", [](PySimulation& s) { return clump_arrays(s.sim()); })
      .def("shape",
           [](PySimulation& s, const std::string& name) { return shape_dict(s.scene(), name); })
      .def_property_readonly("shapes",
                             [](PySimulation& s) {
                               std::vector<std::string> names;
                               for (const ClumpShape& c : s.scene().shapes) names.push_back(c.name);
                               return names;
                             })
      .def("_cg_contacts", [](PySimulation& s) { return cg_contact_arrays(s.sim()); })
      .def("_sum_over_ranks", [](PySimulation& s, py::array_t<double> values) {
        // In place, over the ranks (collective): coarse-graining's sums.
        s.collective("coarse_grain()");
        auto v = values.mutable_unchecked<1>();
        s.sim().comm().sum(v.mutable_data(0), static_cast<int>(v.shape(0)));
      });
}

} // namespace yuxi::python
