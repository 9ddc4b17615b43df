// The grain sources and sinks of a scene file: [[fill]] (grains placed at the start), [[insert]]
// (grains poured during the run) and [[outlet]] (regions where grains leave), each with a
// region table and, for the sources, a size distribution (docs/scene-format.md, "Sources and
// sinks of grains").
#pragma once

#include "io/scene.hpp"
#include "io/toml_reader.hpp"

namespace yuxi {

// Reads every [[fill]], [[insert]] and [[outlet]] table into the scene. Each bad value fails at
// its key: a region that does not meet the domain, an impossible size distribution (negative
// sd, min above max, weights that do not sum to a positive number), a material without a
// density, an amount or rate that random placement cannot meet. Needs [run], [domain] and the
// materials read first. The fills are placed later, when the simulation is built (they must
// keep clear of every particle placed before them).
void read_sources(Scene& scene, TomlReader& root);

// One more [[insert]] for a scene under way (Python's sim.add_insert): `text` holds one
// [[insert]] table, read as the scene's own; appended to scene.inserts and returned. Throws
// SceneError naming the key.
const InsertSpec& add_insert_table(Scene& scene, std::string_view text, const std::string& source);

// The region table at `key` of `t` (docs/scene-format.md, "Regions").
Region read_region(const Scene& scene, TomlReader& t, std::string_view key = "region");

} // namespace yuxi
