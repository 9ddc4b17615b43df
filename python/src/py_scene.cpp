#include "py_scene.hpp"

#include "io/scene_error.hpp"
#include "io/scene_reader.hpp"
#include "io/scene_writer.hpp"

#include <fmt/format.h>
#include <pybind11/stl.h>
#include <regex>
#include <sstream>
#include <toml++/toml.h>

namespace py = pybind11;

namespace yuxi::python {
namespace {

toml::table table_of(const py::dict& d, const std::string& key);

// Calls `put` with the TOML value of a Python one (numpy scalars and arrays through their
// Python equivalents).
template <class Put> void with_toml_value(py::handle value, const std::string& key, Put&& put);

toml::array array_of(py::handle list, const std::string& key) {
  toml::array a;
  std::size_t k = 0;
  for (py::handle item : list)
    with_toml_value(item, fmt::format("{}[{}]", key, k++),
                    [&](auto&& v) { a.push_back(std::forward<decltype(v)>(v)); });
  return a;
}

toml::table table_of(const py::dict& d, const std::string& key) {
  toml::table t;
  for (auto [name, value] : d) {
    if (!py::isinstance<py::str>(name))
      throw SceneError(fmt::format("{}: keys must be strings, got {}", key.empty() ? "scene" : key,
                                   py::str(py::type::of(name)).cast<std::string>()));
    const auto k = name.cast<std::string>();
    if (value.is_none()) continue; // (a key left out)
    with_toml_value(value, key.empty() ? k : key + "." + k,
                    [&](auto&& v) { t.insert(k, std::forward<decltype(v)>(v)); });
  }
  return t;
}

template <class Put> void with_toml_value(py::handle value, const std::string& key, Put&& put) {
  if (py::hasattr(value, "tolist") && !py::isinstance<py::str>(value)) {
    with_toml_value(value.attr("tolist")(), key, put);
  } else if (py::isinstance<py::bool_>(value)) {
    put(value.cast<bool>());
  } else if (py::isinstance<py::int_>(value)) {
    put(value.cast<std::int64_t>());
  } else if (py::isinstance<py::float_>(value)) {
    put(value.cast<double>());
  } else if (py::isinstance<py::str>(value)) {
    put(value.cast<std::string>());
  } else if (py::isinstance<py::dict>(value)) {
    put(table_of(value.cast<py::dict>(), key));
  } else if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
    put(array_of(value, key));
  } else if (py::hasattr(value, "__fspath__")) {
    put(py::str(value.attr("__fspath__")()).cast<std::string>());
  } else {
    throw SceneError(fmt::format("{}: a value of type {} has no TOML form", key,
                                 py::str(py::type::of(value)).cast<std::string>()));
  }
}

py::object python_of(const toml::node& n) {
  if (const auto* t = n.as_table()) {
    py::dict d;
    for (const auto& [k, v] : *t) d[py::str(std::string(k.str()))] = python_of(v);
    return d;
  }
  if (const auto* a = n.as_array()) {
    py::list l;
    for (const auto& v : *a) l.append(python_of(v));
    return l;
  }
  if (const auto* v = n.as_boolean()) return py::bool_(v->get());
  if (const auto* v = n.as_integer()) return py::int_(v->get());
  if (const auto* v = n.as_floating_point()) return py::float_(v->get());
  if (const auto* v = n.as_string()) return py::str(v->get());
  return py::none();
}

} // namespace

std::string toml_of(const py::dict& tables) {
  std::ostringstream os;
  os << table_of(tables, "");
  return os.str();
}

py::dict dict_of_toml(const std::string& text) {
  const toml::table t = toml::parse(text);
  return python_of(t).cast<py::dict>();
}

PyScene PyScene::from_file(const std::string& path) {
  PyScene s;
  s.scene = read_scene_file(path);
  s.resolved = resolved_scene_toml(s.scene);
  return s;
}

PyScene PyScene::from_toml(const std::string& text, const std::string& source) {
  PyScene s;
  s.scene = read_scene_text(text, source);
  s.resolved = resolved_scene_toml(s.scene);
  return s;
}

PyScene PyScene::from_dict(const py::dict& tables, const std::string& source) {
  // (errors name the key's path: the TOML text made from the dict is not the user's)
  PyScene s;
  s.scene = read_scene_text(toml_of(tables), source, false);
  s.resolved = resolved_scene_toml(s.scene);
  return s;
}

py::dict PyScene::resolved_dict() const {
  return dict_of_toml(resolved);
}

void bind_scene(py::module_& m) {
  // SceneError carries the key the message names ("file:line:column: key: message").
  static py::exception<SceneError> scene_error(m, "SceneError", PyExc_ValueError);
  // The errors whose remedy the command line words as flags get Python's words here.
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const OutputFolderError& e) {
      const std::string message =
          e.occupied ? fmt::format("{}; choose another output= or pass overwrite=True", e.what())
                     : e.what();
      PyErr_SetString(e.occupied ? PyExc_FileExistsError : PyExc_OSError, message.c_str());
    } catch (const SceneError& e) {
      const bool time_step = dynamic_cast<const TimeStepError*>(&e) != nullptr;
      const std::string message =
          time_step ? fmt::format("{} (or pass force_dt=True)", e.what()) : e.what();
      static const std::regex pattern(R"(:(\d+):(\d+): ([^:\s][^:]*): )");
      std::smatch match;
      py::object key = py::none();
      if (!e.key.empty())
        key = py::str(e.key);
      else if (std::regex_search(message, match, pattern))
        key = py::str(match[3].str());
      py::object error = py::reinterpret_borrow<py::object>(scene_error)(message);
      error.attr("key") = key;
      PyErr_SetObject(scene_error.ptr(), error.ptr());
    }
  });
  py::class_<PyScene>(m, "_Scene")
      .def_static("from_file", &PyScene::from_file, py::arg("path"))
      .def_static("from_toml", &PyScene::from_toml, py::arg("text"), py::arg("source") = "<string>")
      .def_static("from_dict", &PyScene::from_dict, py::arg("tables"), py::arg("source") = "<dict>")
      .def("resolved", &PyScene::resolved_dict)
      .def("toml", [](const PyScene& s) { return s.resolved; })
      .def_property_readonly("name", [](const PyScene& s) { return s.scene.run.name; })
      .def_property_readonly("source", [](const PyScene& s) { return s.scene.source; })
      .def_property_readonly("t_end", [](const PyScene& s) { return s.scene.run.t_end; })
      .def_property_readonly("dt", [](const PyScene& s) { return s.scene.sim.dt; })
      .def_property_readonly("warnings", [](const PyScene& s) { return s.scene.warnings; })
      .def_property_readonly("materials", [](const PyScene& s) { return s.scene.materials; });
  m.def("_toml_of", &toml_of, py::arg("tables"));
}

} // namespace yuxi::python
