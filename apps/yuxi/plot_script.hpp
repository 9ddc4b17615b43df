// Draws plots with the Python scripts in plots/ (matplotlib from Debian belongs to the system
// interpreter, /usr/bin/python3). A missing interpreter or library costs a warning, not the run.
#pragma once

#include <string>

namespace yuxi {

// Runs plots/<script> with the arguments (each quoted); false (with a warning) on failure.
bool run_plot_script(const std::string& script, const std::string& arguments);

} // namespace yuxi
