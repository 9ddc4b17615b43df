// A contact model's per-contact state as named numeric columns, for analysis (the Python API's
// sim.contacts()). Every model's State lists its fields in one function beside the model
// (model_scene.hpp), found by argument-dependent lookup,
//   template <class Field> void columns(const State& s, Field&& f);
// which calls f(name, value) with a double or a Vec3 (three columns) for each field, in a fixed
// order. Booleans and counters come out as 0 and 1.
#pragma once

#include "contact/frictional_spring.hpp"
#include "core/vec3.hpp"

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace yuxi {

// A spring-dashpot-slider's columns, named after its degree of freedom.
template <class Field> void columns(const SliderState& s, std::string_view dof, Field&& f) {
  const std::string name(dof);
  f(name + "_spring", s.spring);
  f(name + "_sliding", static_cast<double>(s.sliding));
  f(name + "_stiffness", s.k);
}
template <class Field> void columns(const TangentialRollingState& s, Field&& f) {
  columns(s.tangential, "tangential", f);
  columns(s.rolling, "rolling", f);
}

struct StateField {
  std::string name;
  std::size_t width = 1; // 1 for a scalar, 3 for a vector
};

// The names and widths of State's fields.
template <class State> std::vector<StateField> state_fields() {
  struct Names {
    std::vector<StateField>& out;
    void operator()(std::string_view name, double) const { out.push_back({std::string(name), 1}); }
    void operator()(std::string_view name, const Vec3&) const {
      out.push_back({std::string(name), 3});
    }
  };
  std::vector<StateField> out;
  columns(State{}, Names{out});
  return out;
}

// Appends the values of one state's fields, in the order of state_fields<State>().
template <class State> void append_state_values(const State& state, std::vector<double>& out) {
  struct Values {
    std::vector<double>& out;
    void operator()(std::string_view, double v) const { out.push_back(v); }
    void operator()(std::string_view, const Vec3& v) const {
      out.insert(out.end(), {v.x, v.y, v.z});
    }
  };
  columns(state, Values{out});
}

} // namespace yuxi
