// The error that stops a simulation: the run cannot go on.
#pragma once

#include <stdexcept>

namespace yuxi {

// The run cannot go on; what() holds the diagnosis (step, grain, position, velocity).
class SimulationError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

} // namespace yuxi
