// libFuzzer target: the checkpoint reader. Two paths: whole files through the header and
// checksum checks, and (since mutations rarely keep a valid CRC) the state decoder behind them,
// fed the input as the state of a small simulation. Refusals (CheckpointError) are fine;
// anything else is a finding.
#include "io/scene_reader.hpp"
#include "run/scene_builder.hpp"
#include "run/simulation_checkpoint.hpp"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

namespace {

const char* const scene_text = R"(materials = ["grain", "wall"]
[run]
dt = 1e-4
t_end = 1.0
[domain]
lo = [0.0, 0.0, 0.0]
hi = [10.0, 10.0, 10.0]
boundary = ["periodic", "periodic", "wall"]
gravity = [0.0, 0.0, -1.0]
wall_material = "wall"
[contact]
model = "linear"
[[contact.pair]]
materials = ["grain", "grain"]
k_n = 1e4
k_t = 2e3
mu_s = 0.5
[[contact.pair]]
materials = ["grain", "wall"]
k_n = 1e4
[[particle]]
position = [5.0, 5.0, 5.0]
radius = 0.5
mass = 1.0
material = "grain"
)";

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  try {
    yuxi::parse_checkpoint(bytes, "fuzz.yxc");
  } catch (const yuxi::CheckpointError&) {
  }
  static const yuxi::Scene scene = yuxi::read_scene_text(scene_text, "fuzz.toml");
  auto sim = yuxi::build_simulation(scene, false);
  yuxi::CheckpointData d;
  d.file = "fuzz.yxc";
  d.sections = {bytes};
  d.n_sections = 1;
  try {
    yuxi::apply_checkpoint(d, *sim);
    sim->run(2);
  } catch (const yuxi::CheckpointError&) {
  } catch (const yuxi::SimulationError&) {
  }
  return 0;
}
