#include "plot_script.hpp"

#include <cstdlib>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

namespace yuxi {

bool run_plot_script(const std::string& script, const std::string& arguments) {
  const std::string cmd =
      fmt::format("/usr/bin/python3 '{}/plots/{}' {}", YUXI_SOURCE_DIR, script, arguments);
  if (std::system(cmd.c_str()) == 0) return true;
  spdlog::warn("plotting failed (are /usr/bin/python3 and python3-matplotlib installed?): {}", cmd);
  return false;
}

} // namespace yuxi
