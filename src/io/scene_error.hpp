// An error in a scene file: the message starts with "file:line:column: key:".
#pragma once

#include <stdexcept>
#include <string>
#include <utility>

namespace yuxi {

// `key`, where the reader knows it: the key's path in the scene ("contact.pair[1].k_n", "fill[2]"
// for a table), which Python's SceneError carries as its `key`.
class SceneError : public std::runtime_error {
public:
  explicit SceneError(const std::string& message, std::string key_path = {})
      : std::runtime_error(message), key(std::move(key_path)) {}
  std::string key;
};

// A time step above a tenth of the stiffest contact's duration: the message ends with the
// scene's way to allow it (run.allow_large_dt); each interface adds its own override (the
// command line's --force, Python's force_dt=True).
class TimeStepError : public SceneError {
public:
  using SceneError::SceneError;
};

// An output folder that cannot be used (the scene is fine): `occupied` where it already holds
// a run, to which each interface adds its own remedy (the command line's -o and --overwrite,
// Python's output= and overwrite=True).
class OutputFolderError : public std::runtime_error {
public:
  OutputFolderError(const std::string& message, bool occupied_folder)
      : std::runtime_error(message), occupied(occupied_folder) {}
  bool occupied;
};

} // namespace yuxi
