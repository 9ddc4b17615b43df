// `yuxi collide`: the collision study. Sweeps the impact speed (and the obliquity) of two equal
// grains for any contact model, in the DEM engine, and for the thermodynamic model also with
// the exact two-grain solver; writes CSV files and the plots of Jiang & Liu's Figs. 3 and 4.
#pragma once

#include <string>
#include <vector>

namespace yuxi {

struct CollideOptions {
  std::string output_dir = "runs/collide";
  bool overwrite = false;
  std::string scene_path;          // optional: the contact law of its first material pair
  std::vector<std::string> models; // built-in parameter sets (default: all models)
  double radius = 0.5, mass = 1.0; // the grains (model units by default: d = 1, m = 1)
  double v0_min = 1e-5, v0_max = 1e-1;
  int per_decade = 4;
  std::vector<double> obliquities{0.0, 0.2, 0.5, 0.8};
  double steps_per_contact = 200;
  bool plots = true;
};

// The models with a built-in parameter set: every registered contact model.
std::vector<std::string> built_in_models();

// 0 on success, 1 on bad input or a failed run.
int collide_command(const CollideOptions& options);

} // namespace yuxi
