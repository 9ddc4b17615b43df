// A contact model's per-contact state as named numeric columns, for analysis (the Python API's
// sim.contacts()). Every model's State lists its fields in one member,
//   template <class Field> void fields(Field&& f) const;
// which calls f(name, value) with a double or a Vec3 (three columns) for each field, in a fixed
// order. Booleans and counters come out as 0 and 1.
#pragma once

#include "core/vec3.hpp"

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace yuxi {

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
  State{}.fields(Names{out});
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
  state.fields(Values{out});
}

} // namespace yuxi
