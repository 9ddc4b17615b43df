// An error in a scene file: the message starts with "file:line:column: key:".
#pragma once

#include <stdexcept>

namespace yuxi {

class SceneError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

} // namespace yuxi
