// libFuzzer target: the scene reader and builder. A scene may be refused (SceneError, or
// invalid_argument from the engine's own checks); anything else is a finding.
#include "io/scene_reader.hpp"
#include "run/scene_builder.hpp"

#include <cstddef>
#include <cstdint>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const yuxi::Scene scene = yuxi::read_scene_text(text, "fuzz.toml");
    // Building allocates per particle and per cell; keep the fuzzer to scenes a test can hold.
    if (scene.basin) {
      const auto& c = scene.basin->cells;
      if (static_cast<double>(c[0]) * c[1] * c[2] > 2e5) return 0;
    }
    const auto& b = scene.sim.box;
    const double cell = scene.sim.cell_size > 0 ? scene.sim.cell_size : 0.5;
    if ((b.hi.x - b.lo.x) / cell * (b.hi.y - b.lo.y) / cell * (b.hi.z - b.lo.z) / cell > 1e6)
      return 0;
    // ... and to fills and pours of a few thousand grains.
    for (const auto& f : scene.fills) {
      const double r = f.grains.size.smallest(), grain = 4.0 / 3.0 * 3.15 * r * r * r;
      const double volume = f.region.volume_in(b);
      const double n = f.amount == yuxi::FillSpec::Amount::count ? f.value
                       : f.amount == yuxi::FillSpec::Amount::mass
                           ? f.value / (f.grains.density * grain)
                           : f.value * volume / grain;
      if (!(n < 5000)) return 0;
    }
    for (const auto& i : scene.inserts) {
      const double per_batch = i.rate * i.interval;
      if (!(per_batch < 5000) || i.by_mass) return 0;
    }
    auto sim = yuxi::build_simulation(scene, false);
    sim->run(2);
  } catch (const yuxi::SceneError&) {
  } catch (const std::invalid_argument&) {
  } catch (const yuxi::SimulationError&) {
  }
  return 0;
}
