// libFuzzer target: the clump member files (io/sphere_list_reader.hpp), both formats, and the
// shape made of what they accept. A file may be refused (ShapeFileError), and a shape may be
// refused (std::invalid_argument: a member too small for its clump); anything else is a
// finding, and so is an accepted list or shape that breaks the promises (a member not finite
// or not positive; a volume, moment or frame not finite).
#include "io/sphere_list_reader.hpp"
#include "scene/clump_shape.hpp"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const auto format = data[0] % 2 ? yuxi::SphereListFormat::csv : yuxi::SphereListFormat::plain;
  const std::string_view text(reinterpret_cast<const char*>(data + 1), size - 1);
  try {
    const auto members = yuxi::parse_sphere_list(text, "fuzz", format);
    if (members.empty()) std::abort();
    for (const auto& m : members)
      if (!yuxi::is_finite(m.centre) || !(m.radius > 0) || !std::isfinite(m.radius)) std::abort();
    if (members.size() > 4) return 0; // the shape's cost grows as the members' cube
    try {
      const yuxi::ClumpShape s = yuxi::make_clump_shape("fuzz", members);
      if (!(s.volume > 0) || !std::isfinite(s.volume) || !yuxi::is_finite(s.centre) ||
          !yuxi::is_finite(s.inertia_per_density) || !(s.inertia_per_density.x > 0))
        std::abort();
    } catch (const std::invalid_argument&) {
    }
  } catch (const yuxi::ShapeFileError&) {
  }
  return 0;
}
