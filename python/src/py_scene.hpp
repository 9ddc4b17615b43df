// The Python API's scenes: read from a TOML file, a TOML string, or nested dicts and lists with
// the keys of docs/scene-format.md, through the same reader and checks as `yuxi run`.
#pragma once

#include "io/scene.hpp"

#include <pybind11/pybind11.h>
#include <string>

namespace yuxi::python {

struct PyScene {
  Scene scene;
  std::string resolved; // the filled-in scene as TOML (what checkpoints keep)

  static PyScene from_file(const std::string& path);
  static PyScene from_toml(const std::string& text, const std::string& source);
  static PyScene from_dict(const pybind11::dict& tables, const std::string& source);
  // The filled-in scene as nested dicts and lists.
  pybind11::dict resolved_dict() const;
};

// Nested dicts and lists as TOML text (dicts are tables; a list of dicts, an array of tables).
std::string toml_of(const pybind11::dict& tables);
// TOML text as nested dicts and lists.
pybind11::dict dict_of_toml(const std::string& text);

void bind_scene(pybind11::module_& m);

} // namespace yuxi::python
