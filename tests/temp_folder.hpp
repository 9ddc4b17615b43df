// A fresh scratch folder for a test's files, unique to the test process.
#pragma once

#include <filesystem>
#include <string>
#include <unistd.h>

namespace yuxi::test {

inline std::filesystem::path temp_dir(const std::string& name) {
  const std::filesystem::path d = std::filesystem::temp_directory_path() /
                                  ("yuxi_test_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

} // namespace yuxi::test
