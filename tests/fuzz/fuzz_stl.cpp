// libFuzzer target: the STL reader (ASCII and binary triangle meshes). A file may be refused
// (MeshFileError); anything else is a finding, and so is an accepted mesh that breaks the
// reader's promises (no triangles, a degenerate or non-finite one kept, a wrong size).
#include "io/stl_reader.hpp"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  try {
    const yuxi::TriangleSoup soup = yuxi::parse_stl(bytes, "fuzz.stl");
    if (soup.triangles.empty() || soup.bytes != size) std::abort();
    for (const auto& t : soup.triangles) {
      for (const yuxi::Vec3& v : t)
        if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) std::abort();
      if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) std::abort();
    }
  } catch (const yuxi::MeshFileError&) {
  }
  return 0;
}
