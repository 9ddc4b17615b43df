// The Python API's studies: the collision study of `yuxi collide` as arrays, the exact
// two-grain solver's time series, and the validation table of `yuxi validate`.
#include "py_studies.hpp"

#include "validation/collision_study.hpp"
#include "validation/validation_case.hpp"

#include <fmt/format.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

namespace py = pybind11;

namespace yuxi::python {
namespace {

template <class Row, class Get> py::array_t<double> column(const std::vector<Row>& rows, Get get) {
  py::array_t<double> a(static_cast<py::ssize_t>(rows.size()));
  for (std::size_t k = 0; k < rows.size(); ++k)
    a.mutable_at(static_cast<py::ssize_t>(k)) = get(rows[k]);
  return a;
}

py::dict collide(const std::vector<std::string>& models, const std::string& scene, double v0_min,
                 double v0_max, int per_decade, double mass, double radius,
                 double steps_per_contact) {
  using validation::RestitutionRow;
  const auto laws = validation::study_laws(scene, models);
  const auto rows = validation::restitution_sweep(
      laws, validation::study_speeds(v0_min, v0_max, per_decade), mass, radius, steps_per_contact);
  py::dict d;
  py::list model, source;
  for (const auto& r : rows) model.append(r.model), source.append(r.source);
  d["model"] = py::module_::import("numpy").attr("array")(model);
  d["source"] = py::module_::import("numpy").attr("array")(source);
  d["v0"] = column(rows, [](const RestitutionRow& r) { return r.v0; });
  d["impact_speed"] = column(rows, [](const RestitutionRow& r) { return r.impact_speed; });
  d["e_n"] = column(rows, [](const RestitutionRow& r) { return r.e_n; });
  d["contact_time"] = column(rows, [](const RestitutionRow& r) { return r.contact_time; });
  d["peak_force"] = column(rows, [](const RestitutionRow& r) { return r.peak_force; });
  d["max_overlap"] = column(rows, [](const RestitutionRow& r) { return r.max_overlap; });
  d["heat_fraction"] = column(rows, [](const RestitutionRow& r) { return r.heat_fraction; });
  d["energy_drift"] = column(rows, [](const RestitutionRow& r) { return r.energy_drift; });
  return d;
}

py::dict two_grain(const std::string& model, double v0, double mass, double radius) {
  const auto laws = validation::study_laws("", {model});
  const auto x = validation::head_on_series(laws.front().law, mass, radius, v0);
  if (!x)
    throw py::value_error(fmt::format("model '{}' has no exact two-grain solver (only the "
                                      "thermodynamic model has)",
                                      model));
  using thermo::Sample;
  py::dict d;
  d["restitution"] = x->restitution;
  d["contact_time"] = x->contact_time;
  d["initial_energy"] = x->initial_energy;
  d["max_energy_error"] = x->max_energy_error;
  d["t"] = column(x->series, [](const Sample& s) { return s.t; });
  d["delta"] = column(x->series, [](const Sample& s) { return s.delta; });
  d["fn"] = column(x->series, [](const Sample& s) { return s.fn; });
  d["un"] = column(x->series, [](const Sample& s) { return s.un; });
  d["w_el"] = column(x->series, [](const Sample& s) { return s.w_el; });
  d["kinetic"] = column(x->series, [](const Sample& s) { return s.kinetic; });
  d["mechanical"] = column(x->series, [](const Sample& s) { return s.mechanical; });
  d["w_relax"] = column(x->series, [](const Sample& s) { return s.w_relax; });
  d["heat"] = column(x->series, [](const Sample& s) { return s.heat; });
  d["total"] = column(x->series, [](const Sample& s) { return s.total; });
  return d;
}

py::list validate(const std::vector<std::string>& ids, bool include_long, const std::string& scenes,
                  const std::string& reference) {
  using namespace validation;
  const auto& cases = all_cases();
  for (const auto& id : ids)
    if (std::none_of(cases.begin(), cases.end(), [&](const Case& c) { return c.id == id; }))
      throw py::value_error(fmt::format("unknown validation case \"{}\"", id));
  const Paths paths{scenes, reference};
  py::list table;
  for (const auto& c : cases) {
    const bool chosen = ids.empty() ? (!c.long_running || include_long)
                                    : std::find(ids.begin(), ids.end(), c.id) != ids.end();
    if (!chosen) continue;
    const CaseResult r = c.run(paths);
    for (const auto& k : r.checks) {
      py::dict row;
      row["case"] = c.id;
      row["title"] = c.title;
      row["quantity"] = k.quantity;
      row["expected"] = k.expected;
      row["measured"] = k.measured;
      row["tolerance"] = k.tolerance;
      row["passed"] = k.pass();
      table.append(row);
    }
  }
  return table;
}

} // namespace

void bind_studies(py::module_& m) {
  m.def("built_in_models", &validation::built_in_models);
  m.def("_collide", &collide, py::arg("models"), py::arg("scene"), py::arg("v0_min"),
        py::arg("v0_max"), py::arg("per_decade"), py::arg("mass"), py::arg("radius"),
        py::arg("steps_per_contact"));
  m.def("_two_grain", &two_grain, py::arg("model"), py::arg("v0"), py::arg("mass"),
        py::arg("radius"));
  m.def("_validate", &validate, py::arg("ids"), py::arg("include_long"), py::arg("scenes"),
        py::arg("reference"));
  m.def("_validation_cases", [] {
    py::list out;
    for (const auto& c : validation::all_cases()) {
      py::dict d;
      d["case"] = c.id;
      d["title"] = c.title;
      d["source"] = c.source;
      d["long"] = c.long_running;
      out.append(d);
    }
    return out;
  });
}

} // namespace yuxi::python
