// yuxi: 3-D soft-sphere DEM for granular matter.
#include "collide_command.hpp"
#include "domain/mpi_session.hpp"
#include "run_command.hpp"
#include "validate_command.hpp"

#include <CLI/CLI.hpp>
#include <cstdlib>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

int main(int argc, char** argv) {
  const yuxi::MpiSession mpi(&argc, &argv);
  if (!mpi.world().root()) spdlog::set_level(spdlog::level::off); // one log for the job
  CLI::App app{"yuxi: 3-D soft-sphere DEM simulation of granular matter"};
  app.set_version_flag("--version", std::string("yuxi ") + YUXI_VERSION);
  app.require_subcommand(1);
  spdlog::set_pattern("[%H:%M:%S] %v");

  yuxi::RunCommandOptions opt;
  auto* run = app.add_subcommand("run", "Run a scene (default: the built-in small fish basin)");
  auto* scene_opt =
      run->add_option("scene", opt.scene_path, "Scene file (TOML)")->check(CLI::ExistingFile);
  run->add_option("--resume", opt.resume,
                  "Continue the run in this folder from its newest valid checkpoint")
      ->check(CLI::ExistingDirectory)
      ->excludes(scene_opt);
  auto* from_opt =
      run->add_option("--from", opt.from,
                      "Start from this checkpoint (a file, or a run folder's newest valid one): "
                      "its particles, contact history, walls, time and energy books, under the "
                      "given scene")
          ->check(CLI::ExistingPath)
          ->needs(scene_opt);
  run->get_option("--resume")->excludes(from_opt);
  run->add_option("-o,--output", opt.output_dir, "Output folder (default: runs/<scene name>)");
  run->add_flag("--overwrite", opt.overwrite, "Replace an existing output folder");
  run->add_flag("--force", opt.force_dt, "Run even if dt exceeds t_c/10 of the stiffest contact");
  run->add_option("--t-end", opt.t_end, "Override run.t_end");
  run->add_option("--balance-by", opt.balance_by, "Override domain.balance_by")
      ->check(CLI::IsMember({"pairs", "time"}));
  run->add_option("--device", opt.device,
                  "Override run.device: cpu (the CPU engine), gpu (the device engine on a GPU), "
                  "host (the device engine's code on the CPU)")
      ->check(CLI::IsMember({"cpu", "gpu", "host"}));
  run->add_flag("!--no-progress", opt.progress, "Do not show progress on the terminal");
  run->add_flag("!--no-plots", opt.plots, "Do not draw the plots at the end");

  auto* check = app.add_subcommand("check", "Validate a scene and report its time step");
  check->add_option("scene", opt.scene_path, "Scene file (TOML)")->check(CLI::ExistingFile);
  check->add_flag("--force", opt.force_dt, "Accept dt above t_c/10");

  yuxi::ValidateOptions vopt{
      {}, false, false, YUXI_SOURCE_DIR "/scenes", YUXI_SOURCE_DIR "/tests/validation/data"};
  auto* validate = app.add_subcommand(
      "validate", "Run the validation suite against published numbers and print a table");
  validate->add_option("cases", vopt.cases, "Case ids (default: all quick cases)");
  validate->add_flag("--long", vopt.include_long, "Include the long cases");
  validate->add_flag("--list", vopt.list, "List the cases and their sources");
  validate->add_option("--scenes", vopt.scenes_dir, "Folder of the shipped scenes");
  validate->add_option("--reference", vopt.reference_dir, "Folder of the LAMMPS reference data");

  yuxi::CollideOptions copt;
  auto* collide = app.add_subcommand(
      "collide", "Collision study: restitution against impact speed and obliquity, any model");
  collide->add_option("-o,--output", copt.output_dir, "Output folder")->capture_default_str();
  collide->add_flag("--overwrite", copt.overwrite, "Replace an existing output folder");
  collide->add_option("--scene", copt.scene_path, "Take the contact law of this scene's first pair")
      ->check(CLI::ExistingFile);
  collide->add_option("--models", copt.models, "Built-in parameter sets (default: all models)")
      ->check(CLI::IsMember(yuxi::built_in_models()))
      ->excludes("--scene");
  collide->add_option("--radius", copt.radius, "Grain radius")->capture_default_str();
  collide->add_option("--mass", copt.mass, "Grain mass")->capture_default_str();
  collide->add_option("--v0-min", copt.v0_min, "Smallest speed of each grain")
      ->capture_default_str();
  collide->add_option("--v0-max", copt.v0_max, "Largest speed of each grain")
      ->capture_default_str();
  collide->add_option("--per-decade", copt.per_decade, "Speeds per decade")->capture_default_str();
  collide->add_option("--obliquity", copt.obliquities, "Impact parameters b/d of the oblique runs")
      ->capture_default_str();
  collide->add_option("--steps-per-contact", copt.steps_per_contact, "t_c / dt")
      ->capture_default_str();
  collide->add_flag("!--no-plots", copt.plots, "Do not draw the PNG plots");

  CLI11_PARSE(app, argc, argv);
  if (collide->parsed()) return yuxi::collide_command(copt);
  if (run->parsed()) return yuxi::run_command(opt);
  if (check->parsed()) return yuxi::check_command(opt);
  if (validate->parsed()) return yuxi::validate_command(vopt);
  return 1;
}
