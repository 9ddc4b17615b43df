// Reads a clump's member spheres from a file (docs/clumps.md, section 1):
//   CSV (a name ending in .csv): a header naming the columns x, y, z and radius (or r), in any
//       order and among others (any case, quoted or not), then one member a row; cells are
//       separated by commas only, trimmed of blanks and of quotes around them, and only the
//       four named ones are read;
//   a sphere list (any other name): one member a line, "x y z r" separated by spaces, tabs or
//       commas, as LIGGGHTS's multisphere templates write them.
// '#' starts a comment; blank lines and a UTF-8 byte-order mark are skipped. Every member needs
// finite coordinates and a finite radius > 0. A malformed file is a ShapeFileError whose
// message starts with "<file>:<line>: ".
#pragma once

#include "scene/sphere_union.hpp"

#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace yuxi {

class ShapeFileError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

// A clump holds at most this many members: its mass properties cost a number of slices that
// grows with the places where three members' surfaces meet, each slice the square of the
// members it cuts.
constexpr std::size_t max_clump_members = 1000;

enum class SphereListFormat { csv, plain };

std::vector<SphereMember> parse_sphere_list(std::string_view text, std::string_view source,
                                            SphereListFormat format);
// The file at `path`, its format by its name.
std::vector<SphereMember> read_sphere_list(const std::string& path);

} // namespace yuxi
